//! The shapes the families are made of, in pixels as `f64`, and how they
//! become polygons: snapped to the nearest subpixel.

use std::f64::consts::TAU;

use rand::RngExt;
use rand_pcg::Pcg64Mcg;
use raster::{FillRule, Point, Polygon, SCREEN};

pub(super) const WIDTH: f64 = SCREEN.width as f64;
pub(super) const HEIGHT: f64 = SCREEN.height as f64;

/// A point in pixels, snapped to the nearest subpixel (saturating at `i32`).
pub(super) fn snap(x: f64, y: f64) -> Point {
    let to_subpixels =
        |v: f64| (v * f64::from(raster::SUBPIXEL_ONE)).round().clamp(f64::from(i32::MIN), f64::from(i32::MAX)) as i32;
    Point::new(to_subpixels(x), to_subpixels(y))
}

pub(super) fn polygon(points: &[(f64, f64)], color: u8, rule: FillRule) -> Polygon {
    Polygon { contours: vec![points.iter().map(|&(x, y)| snap(x, y)).collect()], color, rule }
}

pub(super) fn color(rng: &mut Pcg64Mcg) -> u8 {
    rng.random_range(1..=255)
}

pub(super) fn rule(rng: &mut Pcg64Mcg) -> FillRule {
    if rng.random_bool(0.5) {
        FillRule::EvenOdd
    } else {
        FillRule::NonZero
    }
}

/// `n` points evenly around a circle, starting at angle `phase`.
pub(super) fn regular(n: usize, (cx, cy): (f64, f64), radius: f64, phase: f64) -> Vec<(f64, f64)> {
    (0..n)
        .map(|i| {
            let a = phase + TAU * i as f64 / n as f64;
            (cx + radius * a.cos(), cy + radius * a.sin())
        })
        .collect()
}

/// Convex hull (Andrew's monotone chain) of snapped points, so the result
/// stays convex in subpixels, counter-clockwise on screen (y down).
pub(super) fn convex_hull(points: &[(f64, f64)]) -> Vec<Point> {
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

pub(super) fn hull_polygon(points: &[(f64, f64)], color: u8) -> Polygon {
    Polygon::new(convex_hull(points), color)
}

/// `n` random points in a disc.
pub(super) fn scatter(rng: &mut Pcg64Mcg, n: usize, (cx, cy): (f64, f64), radius: f64) -> Vec<(f64, f64)> {
    (0..n)
        .map(|_| {
            let (a, r) = (rng.random_range(0.0..TAU), radius * rng.random_range(0.0f64..1.0).sqrt());
            (cx + r * a.cos(), cy + r * a.sin())
        })
        .collect()
}

pub(super) fn on_screen(rng: &mut Pcg64Mcg, margin: f64) -> (f64, f64) {
    (rng.random_range(margin..WIDTH - margin), rng.random_range(margin..HEIGHT - margin))
}

pub(super) fn rotate_about((cx, cy): (f64, f64), degrees: f64) -> impl Fn((f64, f64)) -> (f64, f64) {
    let (sin, cos) = degrees.to_radians().sin_cos();
    move |(x, y)| (cx + (x - cx) * cos - (y - cy) * sin, cy + (x - cx) * sin + (y - cy) * cos)
}
