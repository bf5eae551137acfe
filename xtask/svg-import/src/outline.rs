//! One usvg path as polygon contours on the screen: its own outline (a
//! fill) or its stroke's (kurbo's stroker), flattened within the
//! tolerance and snapped to the 1/256-pixel grid.

use anyhow::{bail, Result};
use kurbo::{Affine, BezPath, Cap, Join, PathEl, Stroke, StrokeOpts};
use raster::{Point, SUBPIXEL_ONE};

/// The most dashes one stroke may be cut into: past it a dash pattern
/// far finer than its path would make millions of polygons' worth of
/// contours.
const MOST_DASHES: f64 = 100_000.0;

/// The widest stroke taken, in screen pixels: twice the range of
/// subpixel coordinates, so that no outline within it is refused, while
/// the stroker's round caps and joins, whose pieces grow in number with
/// their radius, stay few.
const WIDEST_STROKE: f64 = 16_777_216.0;

/// usvg's path data (its points in the path's own coordinates) as
/// kurbo's.
pub(crate) fn bez_path(path: &usvg::tiny_skia_path::Path) -> BezPath {
    use usvg::tiny_skia_path::PathSegment;
    let point = |p: usvg::tiny_skia_path::Point| kurbo::Point::new(f64::from(p.x), f64::from(p.y));
    let mut bez = BezPath::new();
    for segment in path.segments() {
        match segment {
            PathSegment::MoveTo(p) => bez.move_to(point(p)),
            PathSegment::LineTo(p) => bez.line_to(point(p)),
            PathSegment::QuadTo(p1, p) => bez.quad_to(point(p1), point(p)),
            PathSegment::CubicTo(p1, p2, p) => bez.curve_to(point(p1), point(p2), point(p)),
            PathSegment::Close => bez.close_path(),
        }
    }
    bez
}

/// The contours of `path` filled: each subpath, taken by `to_screen` to
/// the screen, flattened within `tolerance` pixels. `name` names the
/// element in errors.
pub(crate) fn filled(path: &BezPath, to_screen: Affine, tolerance: f64, name: &str) -> Result<Vec<Vec<Point>>> {
    contours(&(to_screen * path.clone()), tolerance, name)
}

/// The contours of `stroke` drawn along `path` (to be filled with the
/// non-zero rule): outlined by kurbo in the path's own coordinates (the
/// stroke's width, dashes and caps are in them), then taken to the
/// screen and flattened. The stroker and the flattening each get half
/// of `tolerance`.
pub(crate) fn stroked(
    path: &BezPath,
    stroke: &usvg::Stroke,
    to_screen: Affine,
    tolerance: f64,
    name: &str,
) -> Result<Vec<Vec<Point>>> {
    let style = stroke_style(stroke);
    let pattern_length: f64 = style.dash_pattern.iter().sum();
    if !style.dash_pattern.is_empty() {
        // The pattern alternates dashes and gaps (usvg repeats an odd one).
        let dashes = length_bound(path) / pattern_length * style.dash_pattern.len() as f64 / 2.0;
        if dashes > MOST_DASHES {
            bail!("{name}'s dash pattern cuts its stroke into about {dashes:.0} dashes, past the {MOST_DASHES} taken");
        }
    }
    // A tolerance in the path's units is as many screen pixels or fewer
    // in every direction once `to_screen` stretches it.
    let stretch = to_screen.spectral_norm();
    if !stretch.is_finite() {
        bail!("{name}'s transform is not finite once fitted to the screen");
    }
    if stretch == 0.0 {
        // Every point lands on one: no area.
        return Ok(Vec::new());
    }
    let width = style.width * stretch;
    if width > WIDEST_STROKE {
        bail!("{name}'s stroke is {width:.0} pixels wide once fitted to the screen, past the {WIDEST_STROKE} taken");
    }
    let local_tolerance = (tolerance / 2.0 / stretch).min(f64::MAX);
    let outline = kurbo::stroke(path.iter(), &style, &StrokeOpts::default(), local_tolerance);
    contours(&(to_screen * outline), tolerance / 2.0, name)
}

/// usvg's stroke as kurbo's style. SVG 2's `miter-clip` and `arcs` joins
/// are drawn as miters (usvg reads `arcs` as `miter`).
fn stroke_style(stroke: &usvg::Stroke) -> Stroke {
    let join = match stroke.linejoin() {
        usvg::LineJoin::Miter | usvg::LineJoin::MiterClip => Join::Miter,
        usvg::LineJoin::Round => Join::Round,
        usvg::LineJoin::Bevel => Join::Bevel,
    };
    let cap = match stroke.linecap() {
        usvg::LineCap::Butt => Cap::Butt,
        usvg::LineCap::Round => Cap::Round,
        usvg::LineCap::Square => Cap::Square,
    };
    let style = Stroke::new(f64::from(stroke.width().get()))
        .with_join(join)
        .with_miter_limit(f64::from(stroke.miterlimit().get()))
        .with_caps(cap);
    match stroke.dasharray() {
        Some(dashes) => style.with_dashes(f64::from(stroke.dashoffset()), dashes.iter().map(|&d| f64::from(d))),
        None => style,
    }
}

/// At least the length of `path`: its control polygons' lengths.
fn length_bound(path: &BezPath) -> f64 {
    let mut length = 0.0;
    let mut start = kurbo::Point::ZERO;
    let mut last = kurbo::Point::ZERO;
    for element in path.elements() {
        let points: &[kurbo::Point] = match element {
            PathEl::MoveTo(p) => {
                (start, last) = (*p, *p);
                continue;
            }
            PathEl::LineTo(p) => &[*p],
            PathEl::QuadTo(p1, p2) => &[*p1, *p2],
            PathEl::CurveTo(p1, p2, p3) => &[*p1, *p2, *p3],
            PathEl::ClosePath => &[start],
        };
        for &p in points {
            length += last.distance(p);
            last = p;
        }
    }
    length
}

/// `path` (on the screen) flattened within `tolerance` into contours of
/// subpixel vertices: each subpath one contour, closed, with no vertex
/// repeated in a row and none of fewer than three vertices (which cover
/// no area under either rule). An error naming `name` if a control point
/// lies outside the subpixels' `i32` range: checked before flattening,
/// whose number of vertices grows with the curves' size.
fn contours(path: &BezPath, tolerance: f64, name: &str) -> Result<Vec<Vec<Point>>> {
    for element in path.elements() {
        for point in element_points(element) {
            subpixel(point.x, name)?;
            subpixel(point.y, name)?;
        }
    }
    let mut contours = Vec::new();
    let mut contour: Vec<Point> = Vec::new();
    let mut error = None;
    kurbo::flatten(path.iter(), tolerance, |element| {
        let point = match element {
            PathEl::MoveTo(p) => {
                finish(&mut contour, &mut contours);
                Some(p)
            }
            PathEl::LineTo(p) => Some(p),
            PathEl::ClosePath => {
                finish(&mut contour, &mut contours);
                None
            }
            // `flatten` hands out lines only.
            PathEl::QuadTo(..) | PathEl::CurveTo(..) => None,
        };
        if let Some(p) = point {
            match (subpixel(p.x, name), subpixel(p.y, name)) {
                (Ok(x), Ok(y)) => {
                    let vertex = Point::new(x, y);
                    if contour.last() != Some(&vertex) {
                        contour.push(vertex);
                    }
                }
                (Err(e), _) | (_, Err(e)) => {
                    error.get_or_insert(e);
                }
            }
        }
    });
    if let Some(error) = error {
        return Err(error);
    }
    finish(&mut contour, &mut contours);
    Ok(contours)
}

/// The points an element names.
fn element_points(element: &PathEl) -> Vec<kurbo::Point> {
    match *element {
        PathEl::MoveTo(p) | PathEl::LineTo(p) => vec![p],
        PathEl::QuadTo(p1, p2) => vec![p1, p2],
        PathEl::CurveTo(p1, p2, p3) => vec![p1, p2, p3],
        PathEl::ClosePath => Vec::new(),
    }
}

/// Moves `contour` to `contours` if it has an area to cover: without its
/// closing vertex when that repeats the first, and only with three
/// vertices or more.
fn finish(contour: &mut Vec<Point>, contours: &mut Vec<Vec<Point>>) {
    if contour.len() > 1 && contour.first() == contour.last() {
        contour.pop();
    }
    let done = std::mem::take(contour);
    if done.len() >= 3 {
        contours.push(done);
    }
}

/// `pixels` to the nearest 1/256 pixel (halves away from zero), or an
/// error naming `name` when that is not a number or outside `i32`.
fn subpixel(pixels: f64, name: &str) -> Result<i32> {
    let subpixels = (pixels * f64::from(SUBPIXEL_ONE)).round();
    if subpixels.is_nan() {
        bail!("{name} has a coordinate that is not a number once fitted to the screen");
    }
    if !(f64::from(i32::MIN)..=f64::from(i32::MAX)).contains(&subpixels) {
        let pixels = if pixels.abs() < 1e9 { format!("{pixels:.0}") } else { format!("{pixels:.3e}") };
        bail!(
            "{name} reaches {pixels} pixels once fitted to the screen, past the range of 1/256-pixel \
             coordinates (-8388608 to 8388607.99)"
        );
    }
    Ok(subpixels as i32)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pixels(x: i32, y: i32) -> Point {
        Point::new(x * SUBPIXEL_ONE, y * SUBPIXEL_ONE)
    }

    #[test]
    fn subpaths_become_closed_contours_without_repeats_or_slivers() {
        let path = BezPath::from_svg("M0 0 L10 0 L10 0 L10 10 Z M20 20 L30 20 M40 40 L50 40 L50 50 L40 40").unwrap();
        let got = filled(&path, Affine::scale(2.0), 0.1, "shape").unwrap();
        // The repeated vertex and the closing one go; the two-vertex
        // subpath covers nothing and goes too.
        assert_eq!(
            got,
            [
                vec![pixels(0, 0), pixels(20, 0), pixels(20, 20)],
                vec![pixels(80, 80), pixels(100, 80), pixels(100, 100)]
            ]
        );
    }

    #[test]
    fn vertices_snap_to_the_nearest_subpixel() {
        let path = BezPath::from_svg("M0.001 0.002 L1.0019 0 L0 1.998").unwrap();
        let got = filled(&path, Affine::IDENTITY, 0.1, "shape").unwrap();
        assert_eq!(got, [vec![Point::new(0, 1), Point::new(256, 0), Point::new(0, 511)]]);
    }

    #[test]
    fn a_curve_is_flattened_within_the_tolerance() {
        // A circle of radius 80 pixels: every vertex on it (within the
        // snapping), every chord's middle within the tolerance of it.
        let circle = kurbo::Circle::new((160.0, 100.0), 80.0);
        let path = kurbo::Shape::to_path(&circle, 1e-6);
        for tolerance in [0.05, 0.5, 2.0] {
            let got = filled(&path, Affine::IDENTITY, tolerance, "circle").unwrap();
            assert_eq!(got.len(), 1);
            let radius = |p: (f64, f64)| (p.0 - 160.0).hypot(p.1 - 100.0);
            let at = |p: Point| (f64::from(p.x) / 256.0, f64::from(p.y) / 256.0);
            let contour = &got[0];
            for (i, &p) in contour.iter().enumerate() {
                assert!((radius(at(p)) - 80.0).abs() < 0.01, "{p:?}");
                let (a, b) = (at(p), at(contour[(i + 1) % contour.len()]));
                let middle = ((a.0 + b.0) / 2.0, (a.1 + b.1) / 2.0);
                assert!(80.0 - radius(middle) <= tolerance + 0.01, "tolerance {tolerance}: {}", radius(middle));
            }
            // Not needlessly fine: a coarser tolerance takes fewer vertices.
            assert!(contour.len() < (8.0 * (80.0 / tolerance).sqrt()) as usize, "{}", contour.len());
        }
    }

    #[test]
    fn coordinates_past_the_subpixel_range_are_refused_before_flattening() {
        let path = BezPath::from_svg("M0 0 C 0 0 9000000 0 0 9 Z").unwrap();
        let error = filled(&path, Affine::IDENTITY, 0.1, "path #far").unwrap_err().to_string();
        assert_eq!(
            error,
            "path #far reaches 9000000 pixels once fitted to the screen, past the range of 1/256-pixel coordinates \
             (-8388608 to 8388607.99)"
        );
        let error = filled(&path, Affine::scale(f64::NAN), 0.1, "shape 2 (no id)").unwrap_err().to_string();
        assert_eq!(error, "shape 2 (no id) has a coordinate that is not a number once fitted to the screen");
        assert_eq!(subpixel(-8388608.0, "x").unwrap(), i32::MIN);
        assert_eq!(subpixel(8388607.998, "x").unwrap(), i32::MAX);
        assert!(subpixel(8388607.999, "x").is_err(), "rounds to 2^31");
    }
}
