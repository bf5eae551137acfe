//! The corpus: families of polygons, every one from a fixed seed, so two
//! runs (and two machines) measure the same work.
//!
//! Each family draws from its own generator, seeded from [`SEED`] and the
//! family's name, so adding or resizing a family leaves the others as they
//! were. Coordinates are generated in pixels as `f64` and snapped to the
//! nearest 1/256 px ([`Point`]), the vertex grid of
//! `docs/conventions.md#coordinates` (a tie, which random `f64`s all but
//! never make, rounds away from zero here, up in scene files).

use std::f64::consts::TAU;
use std::ops::Range;

use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64Mcg;
use raster::{FillRule, Point, Polygon, SCREEN};
use scenes::{builtin, Op};

/// The corpus seed. Changing it changes every family.
pub const SEED: u64 = 0x1AB_5EED;

const WIDTH: f64 = SCREEN.width as f64;
const HEIGHT: f64 = SCREEN.height as f64;

/// How a family is read in the report and the charts.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Group {
    /// The demo scenes of `raster::scenes`.
    Scene,
    /// Random polygons of one kind: everyday work.
    Random,
    /// Meshes that tile the screen exactly once under the exact rule.
    Tiling,
    /// Sweeps and hostile input: where methods break.
    Stress,
}

/// What a sweep varies.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Axis {
    /// Rotation in degrees.
    Angle,
    /// Polygon area in square pixels.
    Area,
    /// Vertex count.
    Vertices,
    /// log2 of the largest coordinate magnitude, in subpixels.
    Magnitude,
}

impl Axis {
    /// Whether each value of the axis gets its own timing (the scaling
    /// chart's time against area and vertex count).
    pub const fn timed_per_value(self) -> bool {
        matches!(self, Axis::Area | Axis::Vertices)
    }

    pub const fn label(self) -> &'static str {
        match self {
            Axis::Angle => "rotation (degrees)",
            Axis::Area => "area (px²)",
            Axis::Vertices => "vertices",
            Axis::Magnitude => "log2 coordinate magnitude (subpixels)",
        }
    }
}

/// The swept value of every polygon of a family, in polygon order.
#[derive(Clone, Debug, PartialEq)]
pub struct Sweep {
    pub axis: Axis,
    pub values: Vec<f64>,
}

impl Sweep {
    /// Consecutive runs of polygons sharing one value: `(value, range)`.
    pub fn runs(&self) -> Vec<(f64, Range<usize>)> {
        let mut runs: Vec<(f64, Range<usize>)> = Vec::new();
        for (i, &value) in self.values.iter().enumerate() {
            match runs.last_mut() {
                Some((v, range)) if *v == value => range.end = i + 1,
                _ => runs.push((value, i..i + 1)),
            }
        }
        runs
    }
}

/// One family of polygons.
#[derive(Clone, Debug, PartialEq)]
pub struct Family {
    pub name: &'static str,
    pub group: Group,
    pub description: &'static str,
    pub polygons: Vec<Polygon>,
    /// Runs of polygons that together tile a region exactly once under the
    /// exact rule; overdraw and gaps are counted per tiling. Empty when the
    /// family does not tile.
    pub tilings: Vec<Range<usize>>,
    pub sweep: Option<Sweep>,
}

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
}

impl Budget {
    /// The whole corpus, as the issue describes it.
    pub const FULL: Budget =
        Budget { random: 1000, meshes: 20, angle_step: 1, translations: 16, sweep_values: 24, per_value: 32 };
    /// A small corpus for CI (`--quick`).
    pub const QUICK: Budget =
        Budget { random: 60, meshes: 2, angle_step: 15, translations: 4, sweep_values: 8, per_value: 6 };
}

/// Builds every family for `budget`.
pub fn build(budget: Budget) -> Vec<Family> {
    let random = budget.random;
    vec![
        demo_scenes(),
        random_family("small_triangles", Group::Random, "random triangles 10-50 px across", random, small_triangle),
        random_family(
            "medium_convex",
            Group::Random,
            "convex hulls of random points, 50-120 px across",
            random,
            medium_convex,
        ),
        random_family(
            "large_convex",
            Group::Random,
            "convex polygons near full screen, some past its edges",
            random,
            large_convex,
        ),
        random_family("concave", Group::Random, "star-shaped simple polygons with random radii", random, concave),
        random_family("stars", Group::Random, "self-intersecting {n/k} stars, even-odd and non-zero", random, star),
        random_family("holes", Group::Random, "outer contour with 1-3 hole contours, both rules", random, with_holes),
        random_family("slivers", Group::Random, "needles and narrow wedges, 0.02-2 px wide", random, sliver),
        random_family(
            "subpixel_triangles",
            Group::Random,
            "small triangles with vertices 0-1/256 px off sample points",
            random,
            subpixel_triangle,
        ),
        random_family(
            "partly_offscreen",
            Group::Random,
            "convex polygons straddling a screen edge",
            random,
            partly_offscreen,
        ),
        mesh_family("triangle_mesh", "jittered grids split into triangles, covering the screen", budget.meshes, false),
        mesh_family("quad_mesh", "jittered grids of convex quads, covering the screen", budget.meshes, true),
        rotating_fan(budget.angle_step),
        rotating_mesh(budget.angle_step),
        translation_sweep(budget.translations),
        scale_sweep(budget.sweep_values, budget.per_value),
        vertex_sweep(budget.sweep_values, budget.per_value),
        magnitude_sweep(budget.per_value),
        random_family("offscreen", Group::Stress, "convex polygons wholly off screen, near and far", random, offscreen),
        degenerate(random),
        random_family(
            "nonconvex_shapes",
            Group::Stress,
            "combs, spirals, hourglasses and zigzags: nonconvex input for the convex-only methods",
            random,
            nonconvex_shape,
        ),
    ]
}

/// The generator for the family called `name`.
fn rng_for(name: &str) -> Pcg64Mcg {
    // FNV-1a: a stable hash, unlike `std`'s, so seeds never move.
    let hash = name.bytes().fold(0xcbf2_9ce4_8422_2325u64, |h, b| (h ^ u64::from(b)).wrapping_mul(0x100_0000_01b3));
    Pcg64Mcg::seed_from_u64(SEED ^ hash)
}

/// A point in pixels, snapped to the nearest subpixel (saturating at `i32`).
fn snap(x: f64, y: f64) -> Point {
    let to_subpixels =
        |v: f64| (v * f64::from(raster::SUBPIXEL_ONE)).round().clamp(f64::from(i32::MIN), f64::from(i32::MAX)) as i32;
    Point::new(to_subpixels(x), to_subpixels(y))
}

fn polygon(points: &[(f64, f64)], color: u8, rule: FillRule) -> Polygon {
    Polygon { contours: vec![points.iter().map(|&(x, y)| snap(x, y)).collect()], color, rule }
}

fn color(rng: &mut Pcg64Mcg) -> u8 {
    rng.random_range(1..=255)
}

fn rule(rng: &mut Pcg64Mcg) -> FillRule {
    if rng.random_bool(0.5) {
        FillRule::EvenOdd
    } else {
        FillRule::NonZero
    }
}

/// `n` points evenly around a circle, starting at angle `phase`.
fn regular(n: usize, (cx, cy): (f64, f64), radius: f64, phase: f64) -> Vec<(f64, f64)> {
    (0..n)
        .map(|i| {
            let a = phase + TAU * i as f64 / n as f64;
            (cx + radius * a.cos(), cy + radius * a.sin())
        })
        .collect()
}

/// Convex hull (Andrew's monotone chain) of snapped points, so the result
/// stays convex in subpixels, counter-clockwise on screen (y down).
fn convex_hull(points: &[(f64, f64)]) -> Vec<Point> {
    let mut p: Vec<Point> = points.iter().map(|&(x, y)| snap(x, y)).collect();
    p.sort_by_key(|q| (q.x, q.y));
    p.dedup();
    if p.len() < 3 {
        return p;
    }
    let cross = |o: Point, a: Point, b: Point| {
        (i64::from(a.x) - i64::from(o.x)) * (i64::from(b.y) - i64::from(o.y))
            - (i64::from(a.y) - i64::from(o.y)) * (i64::from(b.x) - i64::from(o.x))
    };
    let mut hull: Vec<Point> = Vec::with_capacity(2 * p.len());
    for pass in [p.clone(), p.iter().rev().copied().collect()] {
        let floor = hull.len();
        for q in pass {
            while hull.len() >= floor + 2 && cross(hull[hull.len() - 2], hull[hull.len() - 1], q) <= 0 {
                hull.pop();
            }
            hull.push(q);
        }
        hull.pop();
    }
    hull
}

fn hull_polygon(points: &[(f64, f64)], color: u8) -> Polygon {
    Polygon::new(convex_hull(points), color)
}

/// `n` random points in a disc.
fn scatter(rng: &mut Pcg64Mcg, n: usize, (cx, cy): (f64, f64), radius: f64) -> Vec<(f64, f64)> {
    (0..n)
        .map(|_| {
            let (a, r) = (rng.random_range(0.0..TAU), radius * rng.random_range(0.0f64..1.0).sqrt());
            (cx + r * a.cos(), cy + r * a.sin())
        })
        .collect()
}

fn on_screen(rng: &mut Pcg64Mcg, margin: f64) -> (f64, f64) {
    (rng.random_range(margin..WIDTH - margin), rng.random_range(margin..HEIGHT - margin))
}

fn random_family(
    name: &'static str,
    group: Group,
    description: &'static str,
    count: usize,
    make: fn(&mut Pcg64Mcg) -> Polygon,
) -> Family {
    let mut rng = rng_for(name);
    Family {
        name,
        group,
        description,
        polygons: (0..count).map(|_| make(&mut rng)).collect(),
        tilings: vec![],
        sweep: None,
    }
}

fn demo_scenes() -> Family {
    let mut polygons: Vec<Polygon> = Vec::new();
    for page in &builtin::ALL {
        for op in page.scene().ops {
            // Pages are cumulative: keep each polygon once.
            if let Op::Fill(p) = op {
                if !polygons.contains(&p) {
                    polygons.push(p);
                }
            }
        }
    }
    Family {
        name: "demo_scenes",
        group: Group::Scene,
        description: "every polygon of the built-in scenes (Listing 38.3)",
        polygons,
        tilings: vec![],
        sweep: None,
    }
}

fn small_triangle(rng: &mut Pcg64Mcg) -> Polygon {
    let size = rng.random_range(10.0..50.0);
    let (x, y) = on_screen(rng, 0.0);
    loop {
        let p: Vec<(f64, f64)> =
            (0..3).map(|_| (x + rng.random_range(0.0..size), y + rng.random_range(0.0..size))).collect();
        // Keep triangles that look like triangles: area at least a fifth of the box's.
        let area = ((p[1].0 - p[0].0) * (p[2].1 - p[0].1) - (p[2].0 - p[0].0) * (p[1].1 - p[0].1)).abs() / 2.0;
        if area >= size * size / 10.0 {
            return polygon(&p, color(rng), FillRule::EvenOdd);
        }
    }
}

fn medium_convex(rng: &mut Pcg64Mcg) -> Polygon {
    let radius = rng.random_range(25.0..60.0);
    let centre = on_screen(rng, 0.0);
    let n = rng.random_range(4..16);
    hull_polygon(&scatter(rng, n, centre, radius), color(rng))
}

fn large_convex(rng: &mut Pcg64Mcg) -> Polygon {
    let n = rng.random_range(3..10);
    let centre = (WIDTH / 2.0 + rng.random_range(-20.0..20.0), HEIGHT / 2.0 + rng.random_range(-15.0..15.0));
    let stretch = rng.random_range(0.8..1.2);
    let points: Vec<(f64, f64)> = regular(n, (0.0, 0.0), 1.0, rng.random_range(0.0..TAU))
        .into_iter()
        .map(|(x, y)| {
            let r = rng.random_range(0.85..1.05);
            (centre.0 + x * r * WIDTH * 0.55 * stretch, centre.1 + y * r * HEIGHT * 0.6)
        })
        .collect();
    hull_polygon(&points, color(rng))
}

fn concave(rng: &mut Pcg64Mcg) -> Polygon {
    let n = rng.random_range(5..17);
    let radius = rng.random_range(20.0..90.0);
    let centre = on_screen(rng, 10.0);
    let mut angles: Vec<f64> = (0..n).map(|_| rng.random_range(0.0..TAU)).collect();
    angles.sort_by(f64::total_cmp);
    let points: Vec<(f64, f64)> = angles
        .iter()
        .map(|a| {
            let r = radius * rng.random_range(0.3..1.0);
            (centre.0 + r * a.cos(), centre.1 + r * a.sin())
        })
        .collect();
    polygon(&points, color(rng), FillRule::EvenOdd)
}

fn star(rng: &mut Pcg64Mcg) -> Polygon {
    const STARS: &[(usize, usize)] = &[(5, 2), (7, 2), (7, 3), (8, 3), (9, 2), (9, 4), (11, 3), (11, 5)];
    let (n, k) = STARS[rng.random_range(0..STARS.len())];
    let corners = regular(n, on_screen(rng, 10.0), rng.random_range(15.0..90.0), rng.random_range(0.0..TAU));
    let points: Vec<(f64, f64)> = (0..n).map(|i| corners[i * k % n]).collect();
    polygon(&points, color(rng), rule(rng))
}

fn with_holes(rng: &mut Pcg64Mcg) -> Polygon {
    let radius = rng.random_range(30.0..90.0);
    let centre = on_screen(rng, 10.0);
    let phase = rng.random_range(0.0..TAU);
    let outer = regular(rng.random_range(5..13), centre, radius, phase);
    let holes = rng.random_range(1..4);
    let mut contours = vec![outer.iter().map(|&(x, y)| snap(x, y)).collect::<Vec<_>>()];
    for h in 0..holes {
        // Hole centres on a circle of radius R/2, hole radius at most R/4:
        // inside the outer contour and apart from each other.
        let a = phase + TAU * h as f64 / holes as f64;
        let at = (centre.0 + radius / 2.0 * a.cos(), centre.1 + radius / 2.0 * a.sin());
        let hole =
            regular(rng.random_range(3..9), at, radius * rng.random_range(0.08..0.25), rng.random_range(0.0..TAU));
        // Reversed, so the non-zero rule leaves the hole empty too.
        contours.push(hole.iter().rev().map(|&(x, y)| snap(x, y)).collect());
    }
    Polygon { contours, color: color(rng), rule: rule(rng) }
}

fn sliver(rng: &mut Pcg64Mcg) -> Polygon {
    let from = on_screen(rng, 0.0);
    let length = rng.random_range(40.0..300.0);
    let width = rng.random_range(0.02..2.0);
    let a = rng.random_range(0.0..TAU);
    let (dx, dy) = (a.cos(), a.sin());
    let to = (from.0 + length * dx, from.1 + length * dy);
    let (nx, ny) = (-dy * width / 2.0, dx * width / 2.0);
    let points = if rng.random_bool(0.5) {
        // A narrow wedge from `from`.
        [from, (to.0 + nx, to.1 + ny), (to.0 - nx, to.1 - ny)]
    } else {
        // A needle: the third point just off the middle of the long edge.
        [from, to, ((from.0 + to.0) / 2.0 + 2.0 * nx, (from.1 + to.1) / 2.0 + 2.0 * ny)]
    };
    polygon(&points, color(rng), FillRule::EvenOdd)
}

fn subpixel_triangle(rng: &mut Pcg64Mcg) -> Polygon {
    let (x, y) = on_screen(rng, 0.0);
    let (x, y) = (x as i32, y as i32);
    let contour = (0..3)
        .map(|_| {
            // A pixel centre (128) or grid corner (0), then -1, 0 or +1 subpixel.
            let base = if rng.random_bool(0.5) { 128 } else { 0 };
            let at = |v: i32, rng: &mut Pcg64Mcg| (v + rng.random_range(0..30)) * 256 + base + rng.random_range(-1..=1);
            Point::new(at(x, rng), at(y, rng))
        })
        .collect();
    Polygon::new(contour, color(rng))
}

fn partly_offscreen(rng: &mut Pcg64Mcg) -> Polygon {
    loop {
        let radius = rng.random_range(15.0..120.0);
        let centre = (rng.random_range(-100.0..WIDTH + 100.0), rng.random_range(-100.0..HEIGHT + 100.0));
        let n = rng.random_range(3..12);
        let points = scatter(rng, n, centre, radius);
        let (x0, x1) = points.iter().fold((f64::MAX, f64::MIN), |(lo, hi), p| (lo.min(p.0), hi.max(p.0)));
        let (y0, y1) = points.iter().fold((f64::MAX, f64::MIN), |(lo, hi), p| (lo.min(p.1), hi.max(p.1)));
        let straddles =
            (x0 < 0.0 || x1 > WIDTH || y0 < 0.0 || y1 > HEIGHT) && x1 > 0.0 && x0 < WIDTH && y1 > 0.0 && y0 < HEIGHT;
        if straddles {
            return hull_polygon(&points, color(rng));
        }
    }
}

fn offscreen(rng: &mut Pcg64Mcg) -> Polygon {
    let radius = rng.random_range(5.0..80.0);
    // Up to 40 px away (an edge may lie exactly on the border) or far.
    let gap = if rng.random_bool(0.7) { rng.random_range(0.0..40.0) } else { rng.random_range(1e3..1e6) };
    let n = rng.random_range(3..10);
    let points = scatter(rng, n, (0.0, 0.0), radius);
    let (x0, x1) = points.iter().fold((f64::MAX, f64::MIN), |(lo, hi), p| (lo.min(p.0), hi.max(p.0)));
    let (y0, y1) = points.iter().fold((f64::MAX, f64::MIN), |(lo, hi), p| (lo.min(p.1), hi.max(p.1)));
    let along_x = rng.random_range(-radius..WIDTH + radius);
    let along_y = rng.random_range(-radius..HEIGHT + radius);
    let (dx, dy) = match rng.random_range(0..4) {
        0 => (-x1 - gap, along_y),
        1 => (WIDTH - x0 + gap, along_y),
        2 => (along_x, -y1 - gap),
        _ => (along_x, HEIGHT - y0 + gap),
    };
    let moved: Vec<(f64, f64)> = points.iter().map(|&(x, y)| (x + dx, y + dy)).collect();
    hull_polygon(&moved, color(rng))
}

/// A jittered grid of `columns` x `rows` cells of `cell` px from `origin`,
/// every inner point moved by at most a fifth of a cell (which keeps every
/// cell a convex quad), as points in pixels.
fn jittered_grid(
    rng: &mut Pcg64Mcg,
    origin: (f64, f64),
    cell: f64,
    columns: usize,
    rows: usize,
) -> Vec<Vec<(f64, f64)>> {
    (0..=rows)
        .map(|j| {
            (0..=columns)
                .map(|i| {
                    let inner = i > 0 && j > 0 && i < columns && j < rows;
                    let jitter = if inner { cell / 5.0 } else { 0.0 };
                    let mut wiggle = || if inner { rng.random_range(-jitter..jitter) } else { 0.0 };
                    (origin.0 + i as f64 * cell + wiggle(), origin.1 + j as f64 * cell + wiggle())
                })
                .collect()
        })
        .collect()
}

/// The cells of a grid as quads, or split along a random diagonal into
/// triangles, all with one colour per tile.
fn grid_tiles(
    rng: &mut Pcg64Mcg,
    grid: &[Vec<(f64, f64)>],
    quads: bool,
    map: impl Fn((f64, f64)) -> (f64, f64),
) -> Vec<Polygon> {
    let mut tiles = Vec::new();
    for j in 0..grid.len() - 1 {
        for i in 0..grid[j].len() - 1 {
            let [a, b, c, d] = [grid[j][i], grid[j][i + 1], grid[j + 1][i + 1], grid[j + 1][i]].map(&map);
            if quads {
                tiles.push(polygon(&[a, b, c, d], color(rng), FillRule::EvenOdd));
            } else if rng.random_bool(0.5) {
                tiles.push(polygon(&[a, b, c], color(rng), FillRule::EvenOdd));
                tiles.push(polygon(&[a, c, d], color(rng), FillRule::EvenOdd));
            } else {
                tiles.push(polygon(&[a, b, d], color(rng), FillRule::EvenOdd));
                tiles.push(polygon(&[b, c, d], color(rng), FillRule::EvenOdd));
            }
        }
    }
    tiles
}

fn mesh_family(name: &'static str, description: &'static str, meshes: usize, quads: bool) -> Family {
    let mut rng = rng_for(name);
    let mut polygons = Vec::new();
    let mut tilings = Vec::new();
    for _ in 0..meshes {
        let cell = rng.random_range(12.0..40.0);
        // One cell of margin on every side, so the mesh covers the screen.
        let origin = (-cell + rng.random_range(0.0..1.0), -cell + rng.random_range(0.0..1.0));
        let (columns, rows) = ((WIDTH / cell).ceil() as usize + 2, (HEIGHT / cell).ceil() as usize + 2);
        let grid = jittered_grid(&mut rng, origin, cell, columns, rows);
        let start = polygons.len();
        polygons.extend(grid_tiles(&mut rng, &grid, quads, |p| p));
        tilings.push(start..polygons.len());
    }
    Family { name, group: Group::Tiling, description, polygons, tilings, sweep: None }
}

fn rotate_about((cx, cy): (f64, f64), degrees: f64) -> impl Fn((f64, f64)) -> (f64, f64) {
    let (sin, cos) = degrees.to_radians().sin_cos();
    move |(x, y)| (cx + (x - cx) * cos - (y - cy) * sin, cy + (x - cx) * sin + (y - cy) * cos)
}

/// A fan of six triangles around a shared centre, making a hexagon.
fn hexagon_fan(centre: (f64, f64), radius: f64, degrees: f64) -> Vec<Polygon> {
    let rim = regular(6, centre, radius, degrees.to_radians());
    (0..6).map(|i| polygon(&[centre, rim[i], rim[(i + 1) % 6]], 1 + i as u8, FillRule::EvenOdd)).collect()
}

fn rotating_fan(step: usize) -> Family {
    // Off the pixel grid, so that no angle is symmetric by accident.
    let centre = (160.0 + 0.37, 100.0 + 0.61);
    let mut family = Family {
        name: "rotating_fan",
        group: Group::Stress,
        description: "a hexagon fan of six triangles rotated 0-359 degrees (LaMothe's test)",
        polygons: vec![],
        tilings: vec![],
        sweep: Some(Sweep { axis: Axis::Angle, values: vec![] }),
    };
    for degrees in (0..360).step_by(step) {
        push_tiling(&mut family, hexagon_fan(centre, 90.0, degrees as f64), degrees as f64);
    }
    family
}

fn rotating_mesh(step: usize) -> Family {
    let mut rng = rng_for("rotating_mesh");
    let centre = (WIDTH / 2.0, HEIGHT / 2.0);
    // Wide enough to cover the screen at any angle: half its diagonal is 189 px.
    let (cell, cells) = (32.0, 13);
    let half = cell * cells as f64 / 2.0;
    let grid = jittered_grid(&mut rng, (centre.0 - half, centre.1 - half), cell, cells, cells);
    let mut family = Family {
        name: "rotating_mesh",
        group: Group::Stress,
        description: "one triangle mesh covering the screen, rotated 0-359 degrees about its centre",
        polygons: vec![],
        tilings: vec![],
        sweep: Some(Sweep { axis: Axis::Angle, values: vec![] }),
    };
    for degrees in (0..360).step_by(step) {
        // The same triangulation at every angle: reseed the diagonal choices.
        let mut diagonals = rng_for("rotating_mesh diagonals");
        let tiles = grid_tiles(&mut diagonals, &grid, false, rotate_about(centre, degrees as f64));
        push_tiling(&mut family, tiles, degrees as f64);
    }
    family
}

fn push_tiling(family: &mut Family, tiles: Vec<Polygon>, value: f64) {
    let start = family.polygons.len();
    if let Some(sweep) = &mut family.sweep {
        sweep.values.extend(std::iter::repeat_n(value, tiles.len()));
    }
    family.polygons.extend(tiles);
    family.tilings.push(start..family.polygons.len());
}

fn translation_sweep(steps: usize) -> Family {
    let mut family = Family {
        name: "subpixel_translation",
        group: Group::Stress,
        description: "a small hexagon fan moved in equal subpixel steps across one pixel",
        polygons: vec![],
        tilings: vec![],
        sweep: None,
    };
    for j in 0..steps {
        for i in 0..steps {
            let (dx, dy) = (i as f64 / steps as f64, j as f64 / steps as f64);
            // Spread over the screen so that every fan is drawn somewhere new.
            let at = (20.0 + (i * 18) as f64 % 280.0 + dx, 20.0 + (j * 10) as f64 % 160.0 + dy);
            push_tiling(&mut family, hexagon_fan(at, 12.0, 7.0), 0.0);
        }
    }
    family
}

/// Log-spaced values from `low` to `high`, `n` of them (`n >= 2`).
fn log_spaced(low: f64, high: f64, n: usize) -> impl Iterator<Item = f64> {
    (0..n).map(move |i| low * (high / low).powf(i as f64 / (n - 1) as f64))
}

fn scale_sweep(values: usize, per_value: usize) -> Family {
    let mut rng = rng_for("scale_sweep");
    let (mut polygons, mut areas) = (Vec::new(), Vec::new());
    // Hexagons from 0.2 px (well under a pixel) to 100 px in radius.
    for radius in log_spaced(0.2, 100.0, values) {
        let area = 1.5 * 3f64.sqrt() * radius * radius;
        for _ in 0..per_value {
            let centre = (WIDTH / 2.0 + rng.random_range(-50.0..50.0), HEIGHT / 2.0 + rng.random_range(-0.5..0.5));
            polygons.push(polygon(
                &regular(6, centre, radius, rng.random_range(0.0..TAU)),
                color(&mut rng),
                FillRule::EvenOdd,
            ));
            areas.push(area);
        }
    }
    Family {
        name: "scale_sweep",
        group: Group::Stress,
        description: "hexagons scaled from 0.2 px to 100 px in radius",
        polygons,
        tilings: vec![],
        sweep: Some(Sweep { axis: Axis::Area, values: areas }),
    }
}

fn vertex_sweep(values: usize, per_value: usize) -> Family {
    let mut rng = rng_for("vertex_sweep");
    let (mut polygons, mut counts) = (Vec::new(), Vec::new());
    let mut previous = 0;
    for n in log_spaced(3.0, 1024.0, values) {
        let n = (n.round() as usize).max(previous + 1);
        previous = n;
        for _ in 0..per_value {
            let centre = (WIDTH / 2.0 + rng.random_range(-5.0..5.0), HEIGHT / 2.0 + rng.random_range(-5.0..5.0));
            polygons.push(hull_polygon(&regular(n, centre, 90.0, rng.random_range(0.0..TAU)), color(&mut rng)));
            counts.push(n as f64);
        }
    }
    Family {
        name: "vertex_sweep",
        group: Group::Stress,
        description: "regular polygons 90 px in radius with 3 to 1024 vertices",
        polygons,
        tilings: vec![],
        sweep: Some(Sweep { axis: Axis::Vertices, values: counts }),
    }
}

fn magnitude_sweep(per_value: usize) -> Family {
    let mut rng = rng_for("magnitude_sweep");
    let (mut polygons, mut magnitudes) = (Vec::new(), Vec::new());
    for bits in 10..=31 {
        // In pixels: 2^bits subpixels, so 2^31 reaches the i32 limits.
        let far = (1u64 << bits) as f64 / f64::from(raster::SUBPIXEL_ONE);
        for k in 0..per_value {
            let points = if k % 2 == 0 {
                // Two points on screen and one far away: long edges across it.
                let a = rng.random_range(0.0..TAU);
                let (p, q) = (on_screen(&mut rng, 0.0), on_screen(&mut rng, 0.0));
                vec![p, q, (p.0 + far * a.cos(), p.1 + far * a.sin())]
            } else {
                // Every vertex far away: the screen is inside, or an edge crosses it.
                regular(rng.random_range(3..6), on_screen(&mut rng, 0.0), far, rng.random_range(0.0..TAU))
            };
            polygons.push(polygon(&points, color(&mut rng), FillRule::EvenOdd));
            magnitudes.push(f64::from(bits));
        }
    }
    Family {
        name: "magnitude_sweep",
        group: Group::Stress,
        description: "polygons with vertices 2^10 to 2^31 subpixels away, up to the i32 limits",
        polygons,
        tilings: vec![],
        sweep: Some(Sweep { axis: Axis::Magnitude, values: magnitudes }),
    }
}

fn degenerate(count: usize) -> Family {
    let mut rng = rng_for("degenerate");
    let (min, max) = (i32::MIN, i32::MAX);
    let p = Point::new;
    let fixed: Vec<Vec<Vec<Point>>> = vec![
        vec![],
        vec![vec![]],
        vec![vec![p(5000, 5000)]],
        vec![vec![p(5000, 5000), p(9000, 7000)]],
        vec![vec![p(5000, 5000); 3]],
        vec![vec![p(2560, 2560), p(25600, 2560), p(51200, 2560)]],
        vec![vec![p(2560, 2560), p(2560, 25600), p(2560, 51200)]],
        vec![vec![p(2560, 2560), p(12800, 12800), p(25600, 25600)]],
        vec![vec![p(2560, 2560), p(25600, 25600), p(2560, 2560), p(25600, 25600)]],
        vec![vec![p(min, min); 4]],
        vec![vec![p(max, max); 4]],
        vec![vec![p(min, min), p(max, min), p(max, max), p(min, max)]],
        vec![vec![p(min, max), p(max, min), p(min, min)]],
        vec![vec![p(0, 0), p(max, 0), p(0, max)]],
        vec![vec![p(min, 0), p(0, min), p(max, max)]],
        vec![vec![p(10_000, 10_000), p(20_000, 10_000), p(10_000, 10_000), p(15_000, 30_000)]],
        vec![vec![p(10_000, 10_000), p(20_000, 20_000), p(30_000, 10_000)], vec![]],
        vec![(0..4096).map(|i| p(i * 20, 12_800)).collect()],
        vec![(0..4096).map(|i| p(i * 20, if i % 2 == 0 { 12_800 } else { 13_056 })).collect()],
        vec![(0..4096).map(|i| p(i * 20 % 81_920, (i * 7919) % 51_200)).collect()],
        vec![vec![p(128 * 257, 128 * 257), p(128 * 257 + 1, 128 * 257), p(128 * 257, 128 * 257 + 1)]],
    ];
    let mut polygons: Vec<Polygon> =
        fixed.into_iter().map(|contours| Polygon { contours, color: 9, rule: FillRule::EvenOdd }).collect();
    // Random collinear and repeated-vertex polygons fill the rest.
    let total = count.max(polygons.len());
    while polygons.len() < total {
        let a = on_screen(&mut rng, 0.0);
        let b = on_screen(&mut rng, 0.0);
        let t: Vec<f64> = (0..rng.random_range(3..8)).map(|_| rng.random_range(-0.5..1.5)).collect();
        let points: Vec<(f64, f64)> = t.iter().map(|t| (a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1))).collect();
        polygons.push(polygon(&points, color(&mut rng), rule(&mut rng)));
    }
    Family {
        name: "degenerate",
        group: Group::Stress,
        description: "0-2 vertices, repeated and collinear vertices, i32 extremes, 4096-vertex lines and zigzags",
        polygons,
        tilings: vec![],
        sweep: None,
    }
}

fn nonconvex_shape(rng: &mut Pcg64Mcg) -> Polygon {
    let unit: Vec<(f64, f64)> = match rng.random_range(0..5) {
        // A comb: teeth hanging from a bar.
        0 => {
            let teeth = rng.random_range(2..7);
            let mut points = vec![(0.0, 0.0), (1.0, 0.0)];
            for t in (0..teeth).rev() {
                let x = t as f64 / teeth as f64;
                let w = 0.5 / teeth as f64;
                points.extend([(x + w * 2.0, 1.0), (x + w * 1.5, 1.0), (x + w * 1.5, 0.3), (x + w * 0.5, 0.3)]);
            }
            points.push((0.0, 1.0));
            points
        }
        // A spiral band.
        1 => {
            let turns = rng.random_range(1.2..3.0);
            let steps = (turns * 24.0) as usize;
            let arm = |r: f64, i: usize| {
                let a = TAU * turns * i as f64 / steps as f64;
                let rr = r * (0.2 + 0.8 * i as f64 / steps as f64);
                (0.5 + rr * a.cos(), 0.5 + rr * a.sin())
            };
            let mut points: Vec<(f64, f64)> = (0..=steps).map(|i| arm(0.5, i)).collect();
            points.extend((0..=steps).rev().map(|i| arm(0.38, i)));
            points
        }
        // An hourglass (bowtie): two triangles meeting at a crossing.
        2 => vec![(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)],
        // A zigzag band.
        3 => {
            let zigs = rng.random_range(2..8);
            let top: Vec<(f64, f64)> =
                (0..=zigs).map(|i| (i as f64 / zigs as f64, if i % 2 == 0 { 0.0 } else { 0.4 })).collect();
            let mut points = top.clone();
            points.extend(top.iter().rev().map(|&(x, y)| (x, y + 0.3)));
            points
        }
        // A C shape, opening to a random side after the rotation below.
        _ => vec![(0.0, 0.0), (1.0, 0.0), (1.0, 0.25), (0.3, 0.25), (0.3, 0.75), (1.0, 0.75), (1.0, 1.0), (0.0, 1.0)],
    };
    let size = rng.random_range(20.0..150.0);
    let centre = on_screen(rng, 10.0);
    let turn = rotate_about((0.0, 0.0), rng.random_range(0.0..360.0));
    let points: Vec<(f64, f64)> = unit
        .into_iter()
        .map(|(x, y)| {
            let (x, y) = turn(((x - 0.5) * size, (y - 0.5) * size));
            (centre.0 + x, centre.1 + y)
        })
        .collect();
    polygon(&points, color(rng), rule(rng))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_corpus_is_the_same_every_time() {
        assert_eq!(build(Budget::QUICK), build(Budget::QUICK));
    }

    #[test]
    fn a_family_does_not_depend_on_the_budget_of_others() {
        let quick = build(Budget::QUICK);
        let bigger = build(Budget { meshes: 5, ..Budget::QUICK });
        let small = |families: &[Family]| families.iter().find(|f| f.name == "small_triangles").cloned();
        assert_eq!(small(&quick), small(&bigger));
    }

    #[test]
    fn family_names_are_unique() {
        let families = build(Budget::QUICK);
        let mut names: Vec<&str> = families.iter().map(|f| f.name).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), families.len());
    }

    #[test]
    fn tilings_and_sweeps_cover_their_families() {
        for family in build(Budget::QUICK) {
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
    fn small_triangles_stay_within_50_pixels() {
        let family = build(Budget::QUICK).into_iter().find(|f| f.name == "small_triangles").unwrap();
        for p in &family.polygons {
            let c = &p.contours[0];
            let span = |f: fn(&Point) -> i32| c.iter().map(f).max().unwrap() - c.iter().map(f).min().unwrap();
            assert!(span(|q| q.x) <= 50 * 256 && span(|q| q.y) <= 50 * 256);
        }
    }
}
