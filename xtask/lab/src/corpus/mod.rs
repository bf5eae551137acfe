//! The corpus: families of polygons, every one from a fixed seed, so two
//! runs (and two machines) measure the same work.
//!
//! Each family draws from its own generator, seeded from [`SEED`] and the
//! family's name, so adding or resizing a family leaves the others as they
//! were. Coordinates are generated in pixels as `f64` and snapped to the
//! nearest 1/256 px ([`Point`]), the vertex grid of
//! `docs/conventions.md#coordinates` (a tie, which random `f64`s all but
//! never make, rounds away from zero here, up in scene files).

mod family;
mod flags;
mod random;
mod real;
mod scene;
mod shapes;
mod stress;
mod tiling;
pub mod user;

pub use family::{Axis, Family, Group, Sweep, SEED};
pub use flags::FLAGS;

use anyhow::Result;

use family::random_family;

/// How much of each kind the corpus holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Budget {
    /// Polygons in each random family.
    pub random: usize,
    /// Meshes in each tiling family.
    pub meshes: usize,
    /// Step of the rotation sweeps, in degrees.
    pub angle_step: usize,
    /// Positions per axis of the subpixel translation sweep, in steps of
    /// `1 / translations` px.
    pub translations: usize,
    /// Values of the scale and vertex-count sweeps.
    pub sweep_values: usize,
    /// Polygons per value of a sweep.
    pub per_value: usize,
    /// Flags of the third-party family ([`flags::FLAGS`]).
    pub flags: usize,
}

impl Budget {
    /// The whole corpus, as the issue describes it.
    pub const FULL: Budget = Budget {
        random: 1000,
        meshes: 20,
        angle_step: 1,
        translations: 16,
        sweep_values: 24,
        per_value: 32,
        flags: 12,
    };
    /// A small corpus for CI (`--quick`).
    pub const QUICK: Budget =
        Budget { random: 60, meshes: 2, angle_step: 15, translations: 4, sweep_values: 8, per_value: 6, flags: 2 };
}

/// Builds every family for `budget`; an error where the third-party
/// family's flags are missing or do not import.
pub fn build(budget: Budget) -> Result<Vec<Family>> {
    let random = budget.random;
    Ok(vec![
        scene::demo_scenes(),
        random_family(
            "small_triangles",
            Group::Random,
            "random triangles 10-50 px across",
            random,
            random::small_triangle,
        ),
        random_family(
            "medium_convex",
            Group::Random,
            "convex hulls of random points, 50-120 px across",
            random,
            random::medium_convex,
        ),
        random_family(
            "large_convex",
            Group::Random,
            "convex polygons near full screen, some past its edges",
            random,
            random::large_convex,
        ),
        random_family(
            "concave",
            Group::Random,
            "star-shaped simple polygons with random radii",
            random,
            random::concave,
        ),
        random_family(
            "stars",
            Group::Random,
            "self-intersecting {n/k} stars, even-odd and non-zero",
            random,
            random::star,
        ),
        random_family(
            "holes",
            Group::Random,
            "outer contour with 1-3 hole contours, both rules",
            random,
            random::with_holes,
        ),
        random_family("slivers", Group::Random, "needles and narrow wedges, 0.02-2 px wide", random, random::sliver),
        random_family(
            "subpixel_triangles",
            Group::Random,
            "small triangles with vertices 0-1/256 px off sample points",
            random,
            random::subpixel_triangle,
        ),
        random_family(
            "partly_offscreen",
            Group::Random,
            "convex polygons straddling a screen edge",
            random,
            random::partly_offscreen,
        ),
        tiling::mesh_family(
            "triangle_mesh",
            "jittered grids split into triangles, covering the screen",
            budget.meshes,
            false,
        ),
        tiling::mesh_family("quad_mesh", "jittered grids of convex quads, covering the screen", budget.meshes, true),
        real::glyphs(
            "text_glyphs",
            "glyphs of DejaVu Sans at 8-16 px to the em, curves flattened within 0.1 px; non-zero, holes",
            random,
            8.0..=16.0,
        ),
        real::glyphs(
            "display_glyphs",
            "glyphs of DejaVu Sans at 17-64 px to the em, curves flattened within 0.1 px; non-zero, holes",
            random,
            17.0..=64.0,
        ),
        real::icons(
            "icons",
            "the paths of 30 Bootstrap Icons at 16-64 px, curves and arcs flattened within 0.1 px; each path's rule",
            random,
            16.0..=64.0,
        ),
        flags::flags(
            "flags",
            "country flags of Debian's iso-flags-svg (public domain), coats of arms and emblems of hundreds to thousands \
             of vertices in many contours, imported by svg_import: each fill and stroke a polygon with its rule, curves \
             and stroke outlines flattened within 0.1 px",
            budget.flags,
        )?,
        stress::rotating_fan(budget.angle_step),
        stress::rotating_mesh(budget.angle_step),
        stress::translation_sweep(budget.translations),
        stress::scale_sweep(budget.sweep_values, budget.per_value),
        stress::vertex_sweep(budget.sweep_values, budget.per_value),
        stress::magnitude_sweep(budget.per_value),
        random_family(
            "offscreen",
            Group::Stress,
            "convex polygons wholly off screen, near and far",
            random,
            stress::offscreen,
        ),
        stress::degenerate(random),
        random_family(
            "nonconvex_shapes",
            Group::Stress,
            "combs, spirals, hourglasses and zigzags: nonconvex input for the convex-only methods",
            random,
            stress::nonconvex_shape,
        ),
    ])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::corpus::family::rng_for;
    use crate::corpus::shapes::{convex_hull, scatter};
    use raster::Point;

    #[test]
    fn the_corpus_is_the_same_every_time() {
        assert_eq!(build(Budget::QUICK).unwrap(), build(Budget::QUICK).unwrap());
    }

    #[test]
    fn a_family_does_not_depend_on_the_budget_of_others() {
        let quick = build(Budget::QUICK).unwrap();
        let bigger = build(Budget { meshes: 5, ..Budget::QUICK }).unwrap();
        let small = |families: &[Family]| families.iter().find(|f| f.name == "small_triangles").cloned();
        assert_eq!(small(&quick), small(&bigger));
    }

    #[test]
    fn family_names_are_unique() {
        let families = build(Budget::QUICK).unwrap();
        let mut names: Vec<&str> = families.iter().map(|f| f.name).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), families.len());
    }

    #[test]
    fn tilings_and_sweeps_cover_their_families() {
        for family in build(Budget::QUICK).unwrap() {
            if let Some(sweep) = &family.sweep {
                assert_eq!(sweep.values.len(), family.polygons.len(), "{}", family.name);
            }
            let mut next = 0;
            for tiling in &family.tilings {
                assert_eq!(tiling.start, next, "{}", family.name);
                next = tiling.end;
            }
            assert!(family.tilings.is_empty() || next == family.polygons.len(), "{}", family.name);
        }
    }

    #[test]
    fn hulls_are_convex_and_counter_clockwise_on_screen() {
        let mut rng = rng_for("test");
        for _ in 0..100 {
            let hull = convex_hull(&scatter(&mut rng, 12, (100.0, 100.0), 50.0));
            for i in 0..hull.len() {
                let [o, a, b] = [hull[i], hull[(i + 1) % hull.len()], hull[(i + 2) % hull.len()]];
                let cross = (i64::from(a.x - o.x)) * i64::from(b.y - o.y) - i64::from(a.y - o.y) * i64::from(b.x - o.x);
                assert!(cross > 0);
            }
        }
    }

    #[test]
    fn sweep_runs_group_equal_neighbours() {
        let sweep = Sweep { axis: Axis::Area, values: vec![1.0, 1.0, 2.0, 2.0, 2.0, 1.0] };
        assert_eq!(sweep.runs(), vec![(1.0, 0..2), (2.0, 2..5), (1.0, 5..6)]);
    }

    #[test]
    fn the_real_shapes_say_their_tolerance() {
        let real: Vec<Family> = build(Budget::QUICK).unwrap().into_iter().filter(|f| f.group == Group::Real).collect();
        assert_eq!(real.len(), 4);
        for family in real {
            assert!(family.description.contains(&format!("within {} px", real::TOLERANCE)), "{}", family.name);
            if family.name != "flags" {
                assert_eq!(family.polygons.len(), Budget::QUICK.random);
            }
        }
    }

    #[test]
    fn small_triangles_stay_within_50_pixels() {
        let family = build(Budget::QUICK).unwrap().into_iter().find(|f| f.name == "small_triangles").unwrap();
        for p in &family.polygons {
            let c = &p.contours[0];
            let span = |f: fn(&Point) -> i32| c.iter().map(f).max().unwrap() - c.iter().map(f).min().unwrap();
            assert!(span(|q| q.x) <= 50 * 256 && span(|q| q.y) <= 50 * 256);
        }
    }
}
