//! The stress group: rotation, translation, scale, vertex-count and
//! coordinate-magnitude sweeps, off-screen, degenerate and nonconvex
//! input: where methods break.

use std::f64::consts::TAU;

use rand::RngExt;
use rand_pcg::Pcg64Mcg;
use raster::{FillRule, Point, Polygon};

use super::family::{rng_for, Axis, Family, Group, Sweep};
use super::shapes::{color, hull_polygon, on_screen, polygon, regular, rotate_about, rule, scatter, HEIGHT, WIDTH};
use super::tiling::{grid_tiles, jittered_grid, push_tiling};

/// A fan of six triangles around a shared centre, making a hexagon.
pub(super) fn hexagon_fan(centre: (f64, f64), radius: f64, degrees: f64) -> Vec<Polygon> {
    let rim = regular(6, centre, radius, degrees.to_radians());
    (0..6).map(|i| polygon(&[centre, rim[i], rim[(i + 1) % 6]], 1 + i as u8, FillRule::EvenOdd)).collect()
}

pub(super) fn rotating_fan(step: usize) -> Family {
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

pub(super) fn rotating_mesh(step: usize) -> Family {
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

pub(super) fn translation_sweep(steps: usize) -> Family {
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
pub(super) fn log_spaced(low: f64, high: f64, n: usize) -> impl Iterator<Item = f64> {
    (0..n).map(move |i| low * (high / low).powf(i as f64 / (n - 1) as f64))
}

pub(super) fn scale_sweep(values: usize, per_value: usize) -> Family {
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

pub(super) fn vertex_sweep(values: usize, per_value: usize) -> Family {
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

pub(super) fn magnitude_sweep(per_value: usize) -> Family {
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

pub(super) fn offscreen(rng: &mut Pcg64Mcg) -> Polygon {
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

pub(super) fn degenerate(count: usize) -> Family {
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

pub(super) fn nonconvex_shape(rng: &mut Pcg64Mcg) -> Polygon {
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
