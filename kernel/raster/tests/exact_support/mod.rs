//! What the `exact_*` tests share: polygon generators for proptest and the
//! comparison with the reference.
#![allow(dead_code)] // Each test binary uses its own part of this module.

use proptest::prelude::*;
use raster::reference::{self, SampleOffset};
use raster::{CoverageReport, CoverageSink, FillRule, Point, Polygon, Refusal, Size, SpanSink};

/// The target of the property tests: small, so the brute-force reference
/// stays fast in debug builds, and odd-sized.
pub const TARGET: Size = Size { width: 47, height: 39 };

/// One pixel in subpixels.
pub const PX: i32 = raster::SUBPIXEL_ONE;

/// Draws `polygon` with `fill` and with the reference into `size`; the
/// report is all zero when they agree pixel for pixel and `fill` drew no
/// pixel twice and no span outside. The picture, drawn only when they
/// differ, marks the differences.
pub fn against_reference(
    fill: impl Fn(&Polygon, &mut dyn SpanSink) -> Result<(), Refusal>,
    polygon: &Polygon,
    size: Size,
) -> (Result<(), Refusal>, CoverageReport, String) {
    let mut expected = CoverageSink::new(size);
    reference::fill(polygon, SampleOffset::CENTRE, &mut expected);
    let mut drawn = CoverageSink::new(size);
    let result = fill(polygon, &mut drawn);
    let report = drawn.report(&expected);
    let picture = if report == CoverageReport::default() { String::new() } else { drawn.ascii_against(&expected) };
    (result, report, picture)
}

/// `against_reference` as a proptest assertion: the fill must accept the
/// polygon and match the reference exactly.
pub fn prop_assert_matches_reference(
    fill: impl Fn(&Polygon, &mut dyn SpanSink) -> Result<(), Refusal>,
    polygon: &Polygon,
    size: Size,
) -> Result<(), TestCaseError> {
    let (result, report, picture) = against_reference(fill, polygon, size);
    prop_assert_eq!(result, Ok(()));
    prop_assert_eq!(report, CoverageReport::default(), "\n{}", picture);
    Ok(())
}

/// What a generated polygon was built to be.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    Triangle,
    /// Two y-monotone chains (Abrash's "convex"), possibly crossing.
    Monotone,
    /// Vertices in angular order round a centre: simple, usually concave.
    Star,
    /// Random vertices: self-intersecting.
    Scribble,
    /// A star with a star-shaped hole, each wound either way.
    Holes,
    /// Several scribbles.
    Contours,
    /// Vertices anywhere in `i32`, or at its extremes.
    Huge,
    /// Up to six vertices on one line: nothing to fill.
    Collinear,
}

/// Subpixel coordinates from `low` to `high` pixels.
fn coordinate(low: i32, high: i32) -> impl Strategy<Value = i32> {
    low * PX..high * PX
}

/// Points around the target, often partly and sometimes wholly outside it.
pub fn nearby_point() -> impl Strategy<Value = Point> {
    (coordinate(-16, 64), coordinate(-16, 56)).prop_map(|(x, y)| Point::new(x, y))
}

fn contour_of(points: usize) -> impl Strategy<Value = Vec<Point>> {
    prop::collection::vec(nearby_point(), points)
}

fn collinear_contour() -> impl Strategy<Value = Vec<Point>> {
    (nearby_point(), (-3 * PX..3 * PX, -3 * PX..3 * PX), prop::collection::vec(-8..8, 0..7)).prop_map(
        |(origin, (dx, dy), steps)| steps.iter().map(|&t| Point::new(origin.x + t * dx, origin.y + t * dy)).collect(),
    )
}

fn monotone_contour() -> impl Strategy<Value = Vec<Point>> {
    (2usize..7).prop_flat_map(|levels| {
        (
            prop::collection::vec(coordinate(-16, 56), levels),
            prop::collection::vec(coordinate(-16, 64), levels),
            prop::collection::vec(coordinate(-16, 64), levels),
        )
            .prop_map(|(mut ys, right, left)| {
                ys.sort_unstable();
                // Down the right chain, then up the left one.
                let down = ys.iter().zip(&right).map(|(&y, &x)| Point::new(x, y));
                let up = ys.iter().zip(&left).rev().map(|(&y, &x)| Point::new(x, y));
                down.chain(up).collect()
            })
    })
}

/// Sixteen directions in angular order, scaled to 256.
const DIRECTIONS: [(i32, i32); 16] = [
    (256, 0),
    (237, 98),
    (181, 181),
    (98, 237),
    (0, 256),
    (-98, 237),
    (-181, 181),
    (-237, 98),
    (-256, 0),
    (-237, -98),
    (-181, -181),
    (-98, -237),
    (0, -256),
    (98, -237),
    (181, -181),
    (237, -98),
];

/// A contour with one vertex on each of the sixteen directions from
/// `centre`, at a distance from `radii` (in subpixels); reversed when
/// `clockwise`.
fn star_around(centre: Point, radii: &[i32], clockwise: bool) -> Vec<Point> {
    let mut contour: Vec<Point> = DIRECTIONS
        .iter()
        .zip(radii)
        .map(|(&(dx, dy), &r)| Point::new(centre.x + dx * r / 256, centre.y + dy * r / 256))
        .collect();
    if clockwise {
        contour.reverse();
    }
    contour
}

fn star_contour() -> impl Strategy<Value = Vec<Point>> {
    (nearby_point(), prop::collection::vec(PX..24 * PX, 16), any::<bool>())
        .prop_map(|(centre, radii, clockwise)| star_around(centre, &radii, clockwise))
}

fn polygon_with_holes() -> impl Strategy<Value = Vec<Vec<Point>>> {
    (
        nearby_point(),
        prop::collection::vec(12 * PX..24 * PX, 16),
        prop::collection::vec(PX..6 * PX, 16),
        any::<(bool, bool)>(),
    )
        .prop_map(|(centre, outer, inner, (outer_clockwise, inner_clockwise))| {
            vec![star_around(centre, &outer, outer_clockwise), star_around(centre, &inner, inner_clockwise)]
        })
}

/// Any `i32`, with the extremes and their neighbours made likely.
fn huge_coordinate() -> impl Strategy<Value = i32> {
    prop_oneof![
        any::<i32>(),
        prop::sample::select(vec![i32::MIN, i32::MIN + 1, -(1 << 24), -1, 0, 1, 1 << 24, i32::MAX - 1, i32::MAX]),
        coordinate(-16, 64),
    ]
}

fn huge_contours() -> impl Strategy<Value = Vec<Vec<Point>>> {
    let point = (huge_coordinate(), huge_coordinate()).prop_map(|(x, y)| Point::new(x, y));
    prop::collection::vec(prop::collection::vec(point, 3..7), 1..3)
}

/// Vertices on multiples of half a pixel: edges then run through pixel
/// centres and corners, where the tie rules decide.
fn snap_to_half_pixels(contours: &mut [Vec<Point>]) {
    for p in contours.iter_mut().flatten() {
        *p = Point::new(p.x & !(PX / 2 - 1), p.y & !(PX / 2 - 1));
    }
}

/// Contours of one kind, before snapping and the choice of rule.
fn contours(kind: Kind) -> BoxedStrategy<Vec<Vec<Point>>> {
    match kind {
        Kind::Triangle => contour_of(3).prop_map(|c| vec![c]).boxed(),
        Kind::Monotone => monotone_contour().prop_map(|c| vec![c]).boxed(),
        Kind::Star => star_contour().prop_map(|c| vec![c]).boxed(),
        Kind::Scribble => (4usize..12).prop_flat_map(contour_of).prop_map(|c| vec![c]).boxed(),
        Kind::Holes => polygon_with_holes().boxed(),
        Kind::Contours => prop::collection::vec((3usize..8).prop_flat_map(contour_of), 2..4).boxed(),
        Kind::Huge => huge_contours().boxed(),
        Kind::Collinear => collinear_contour().prop_map(|c| vec![c]).boxed(),
    }
}

/// A polygon of `kind`, snapped to half pixels a third of the time, with
/// either fill rule.
pub fn polygon_of(kind: Kind) -> impl Strategy<Value = Polygon> {
    (contours(kind), prop::bool::weighted(0.33), any::<bool>()).prop_map(move |(mut contours, snap, non_zero)| {
        // Snapping would move the extremes off them and bend collinear
        // contours.
        if snap && !matches!(kind, Kind::Huge | Kind::Collinear) {
            snap_to_half_pixels(&mut contours);
        }
        Polygon { contours, color: 1, rule: if non_zero { FillRule::NonZero } else { FillRule::EvenOdd } }
    })
}

/// A polygon of any kind but huge, with the kind it was built as.
pub fn any_polygon() -> impl Strategy<Value = (Kind, Polygon)> {
    let kinds =
        vec![Kind::Collinear, Kind::Triangle, Kind::Monotone, Kind::Star, Kind::Scribble, Kind::Holes, Kind::Contours];
    prop::sample::select(kinds).prop_flat_map(|kind| polygon_of(kind).prop_map(move |polygon| (kind, polygon)))
}
