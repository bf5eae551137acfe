//! The random group: everyday polygons of one kind a family, each made
//! from the family's generator.

use std::f64::consts::TAU;

use rand::RngExt;
use rand_pcg::Pcg64Mcg;
use raster::{FillRule, Point, Polygon};

use super::shapes::{color, hull_polygon, on_screen, polygon, regular, rule, scatter, snap, HEIGHT, WIDTH};

pub(super) fn small_triangle(rng: &mut Pcg64Mcg) -> Polygon {
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

pub(super) fn medium_convex(rng: &mut Pcg64Mcg) -> Polygon {
    let radius = rng.random_range(25.0..60.0);
    let centre = on_screen(rng, 0.0);
    let n = rng.random_range(4..16);
    hull_polygon(&scatter(rng, n, centre, radius), color(rng))
}

pub(super) fn large_convex(rng: &mut Pcg64Mcg) -> Polygon {
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

pub(super) fn concave(rng: &mut Pcg64Mcg) -> Polygon {
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

pub(super) fn star(rng: &mut Pcg64Mcg) -> Polygon {
    const STARS: &[(usize, usize)] = &[(5, 2), (7, 2), (7, 3), (8, 3), (9, 2), (9, 4), (11, 3), (11, 5)];
    let (n, k) = STARS[rng.random_range(0..STARS.len())];
    let corners = regular(n, on_screen(rng, 10.0), rng.random_range(15.0..90.0), rng.random_range(0.0..TAU));
    let points: Vec<(f64, f64)> = (0..n).map(|i| corners[i * k % n]).collect();
    polygon(&points, color(rng), rule(rng))
}

pub(super) fn with_holes(rng: &mut Pcg64Mcg) -> Polygon {
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

pub(super) fn sliver(rng: &mut Pcg64Mcg) -> Polygon {
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

pub(super) fn subpixel_triangle(rng: &mut Pcg64Mcg) -> Polygon {
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

pub(super) fn partly_offscreen(rng: &mut Pcg64Mcg) -> Polygon {
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
