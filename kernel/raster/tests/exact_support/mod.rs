//! What the `exact_*` tests share: the polygon generators and the
//! comparison with the reference (`method_ids.rs` takes its corpus from
//! the generators too).
//!
//! The generators are plain functions of a stream of random draws
//! ([`Draws`]), so that one generator serves two ends: proptest feeds it
//! draws it can shrink (toward zero, the low end of every range, so a
//! failing polygon shrinks to fewer and smaller vertices), and the golden
//! hash feeds it a seeded stream of our own ([`Seeded`]), which no
//! dependency's upgrade can change.
#![allow(dead_code)] // Each test binary uses its own part of this module.

use proptest::prelude::*;
use raster::reference::{self, SampleOffset};
use raster::{CoverageReport, CoverageSink, FillRule, Point, Polygon, Refusal, Size, SpanSink};
use std::ops::Range;

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

/// A source of random choices, each made from one 64-bit draw.
pub trait Draws {
    fn draw(&mut self) -> u64;

    /// A value in `0..n`, `n > 0`: the draw modulo `n` (a draw of zero
    /// gives zero).
    fn below(&mut self, n: u64) -> u64 {
        self.draw() % n
    }

    /// A value in `low..high`, `low < high`.
    fn range(&mut self, low: i32, high: i32) -> i32 {
        (i64::from(low) + self.below((i64::from(high) - i64::from(low)) as u64) as i64) as i32
    }

    /// A count in `counts`, not empty.
    fn count(&mut self, counts: Range<usize>) -> usize {
        counts.start + self.below((counts.end - counts.start) as u64) as usize
    }

    fn coin(&mut self) -> bool {
        self.draw() & 1 == 1
    }

    /// Any `i32`: the draw's low half.
    fn any_i32(&mut self) -> i32 {
        self.draw() as u32 as i32
    }

    fn pick<T: Copy>(&mut self, choices: &[T]) -> T {
        choices[self.below(choices.len() as u64) as usize]
    }
}

/// A seeded stream of draws (SplitMix64, Steele, Lea and Flood's
/// "Fast splittable pseudorandom number generators", 2014): the same
/// polygons on every machine and with every version of every dependency.
pub struct Seeded(u64);

impl Seeded {
    pub fn new(seed: u64) -> Self {
        Self(seed)
    }
}

impl Draws for Seeded {
    fn draw(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
}

/// Draws proptest made, played back in order; zero once they run out.
struct Replay<'a> {
    draws: &'a [u64],
    next: usize,
}

impl Draws for Replay<'_> {
    fn draw(&mut self) -> u64 {
        let draw = self.draws.get(self.next).copied().unwrap_or(0);
        self.next += 1;
        draw
    }
}

/// More draws than any generator here makes for one polygon.
const DRAWS: usize = 160;

/// A proptest strategy for what `generate` makes of a stream of draws.
fn from_draws<T: std::fmt::Debug>(generate: impl Fn(&mut Replay) -> T) -> impl Strategy<Value = T> {
    prop::collection::vec(any::<u64>(), DRAWS).prop_map(move |draws| generate(&mut Replay { draws: &draws, next: 0 }))
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

/// Every kind but [`Kind::Huge`].
const NEARBY_KINDS: [Kind; 7] =
    [Kind::Collinear, Kind::Triangle, Kind::Monotone, Kind::Star, Kind::Scribble, Kind::Holes, Kind::Contours];

/// A subpixel coordinate from `low` to `high` pixels.
fn coordinate(draws: &mut impl Draws, low: i32, high: i32) -> i32 {
    draws.range(low * PX, high * PX)
}

/// A point around the target, often partly and sometimes wholly outside it.
pub fn nearby_point(draws: &mut impl Draws) -> Point {
    let x = coordinate(draws, -16, 64);
    Point::new(x, coordinate(draws, -16, 56))
}

/// `counts` points around the target, as [`nearby_point`] makes them.
pub fn nearby_points(counts: Range<usize>) -> impl Strategy<Value = Vec<Point>> {
    prop::collection::vec((any::<u64>(), any::<u64>()), counts)
        .prop_map(|draws| draws.iter().map(|&(x, y)| nearby_point(&mut Replay { draws: &[x, y], next: 0 })).collect())
}

fn contour_of(draws: &mut impl Draws, points: usize) -> Vec<Point> {
    (0..points).map(|_| nearby_point(draws)).collect()
}

fn collinear_contour(draws: &mut impl Draws) -> Vec<Point> {
    let origin = nearby_point(draws);
    let (dx, dy) = (draws.range(-3 * PX, 3 * PX), draws.range(-3 * PX, 3 * PX));
    let steps = draws.count(0..7);
    (0..steps)
        .map(|_| {
            let t = draws.range(-8, 8);
            Point::new(origin.x + t * dx, origin.y + t * dy)
        })
        .collect()
}

fn monotone_contour(draws: &mut impl Draws) -> Vec<Point> {
    let levels = draws.count(2..7);
    let mut ys: Vec<i32> = (0..levels).map(|_| coordinate(draws, -16, 56)).collect();
    let right: Vec<i32> = (0..levels).map(|_| coordinate(draws, -16, 64)).collect();
    let left: Vec<i32> = (0..levels).map(|_| coordinate(draws, -16, 64)).collect();
    ys.sort_unstable();
    // Down the right chain, then up the left one.
    let down = ys.iter().zip(&right).map(|(&y, &x)| Point::new(x, y));
    let up = ys.iter().zip(&left).rev().map(|(&y, &x)| Point::new(x, y));
    down.chain(up).collect()
}

/// Sixteen directions in angular order, scaled to 256.
pub const DIRECTIONS: [(i32, i32); 16] = [
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
/// `centre`, at a distance in `radii` (subpixels), reversed half the time.
fn star_around(draws: &mut impl Draws, centre: Point, radii: Range<i32>) -> Vec<Point> {
    let mut contour: Vec<Point> = DIRECTIONS
        .iter()
        .map(|&(dx, dy)| {
            let r = draws.range(radii.start, radii.end);
            Point::new(centre.x + dx * r / 256, centre.y + dy * r / 256)
        })
        .collect();
    if draws.coin() {
        contour.reverse();
    }
    contour
}

fn star_contour(draws: &mut impl Draws) -> Vec<Point> {
    let centre = nearby_point(draws);
    star_around(draws, centre, PX..24 * PX)
}

fn polygon_with_holes(draws: &mut impl Draws) -> Vec<Vec<Point>> {
    let centre = nearby_point(draws);
    vec![star_around(draws, centre, 12 * PX..24 * PX), star_around(draws, centre, PX..6 * PX)]
}

/// Any `i32`, with the extremes and their neighbours made likely.
fn huge_coordinate(draws: &mut impl Draws) -> i32 {
    const SPECIAL: [i32; 9] = [i32::MIN, i32::MIN + 1, -(1 << 24), -1, 0, 1, 1 << 24, i32::MAX - 1, i32::MAX];
    match draws.below(3) {
        0 => coordinate(draws, -16, 64),
        1 => draws.pick(&SPECIAL),
        _ => draws.any_i32(),
    }
}

fn huge_contours(draws: &mut impl Draws) -> Vec<Vec<Point>> {
    let contours = draws.count(1..3);
    (0..contours)
        .map(|_| {
            let points = draws.count(3..7);
            (0..points)
                .map(|_| {
                    let x = huge_coordinate(draws);
                    Point::new(x, huge_coordinate(draws))
                })
                .collect()
        })
        .collect()
}

/// Vertices on multiples of half a pixel: edges then run through pixel
/// centres and corners, where the tie rules decide.
fn snap_to_half_pixels(contours: &mut [Vec<Point>]) {
    for p in contours.iter_mut().flatten() {
        *p = Point::new(p.x & !(PX / 2 - 1), p.y & !(PX / 2 - 1));
    }
}

/// Contours of one kind, before snapping and the choice of rule.
fn contours(draws: &mut impl Draws, kind: Kind) -> Vec<Vec<Point>> {
    match kind {
        Kind::Triangle => vec![contour_of(draws, 3)],
        Kind::Monotone => vec![monotone_contour(draws)],
        Kind::Star => vec![star_contour(draws)],
        Kind::Scribble => {
            let points = draws.count(4..12);
            vec![contour_of(draws, points)]
        }
        Kind::Holes => polygon_with_holes(draws),
        Kind::Contours => {
            let contours = draws.count(2..4);
            (0..contours)
                .map(|_| {
                    let points = draws.count(3..8);
                    contour_of(draws, points)
                })
                .collect()
        }
        Kind::Huge => huge_contours(draws),
        Kind::Collinear => vec![collinear_contour(draws)],
    }
}

/// A polygon of `kind`, snapped to half pixels a third of the time, with
/// either fill rule.
pub fn generate(draws: &mut impl Draws, kind: Kind) -> Polygon {
    let mut contours = contours(draws, kind);
    // Snapping would move the extremes off them and bend collinear
    // contours.
    if draws.below(3) == 0 && !matches!(kind, Kind::Huge | Kind::Collinear) {
        snap_to_half_pixels(&mut contours);
    }
    Polygon { contours, color: 1, rule: if draws.coin() { FillRule::NonZero } else { FillRule::EvenOdd } }
}

/// A polygon of any kind but huge, with the kind it was built as.
pub fn generate_any(draws: &mut impl Draws) -> (Kind, Polygon) {
    let kind = draws.pick(&NEARBY_KINDS);
    (kind, generate(draws, kind))
}

/// [`generate`] as a proptest strategy.
pub fn polygon_of(kind: Kind) -> impl Strategy<Value = Polygon> {
    from_draws(move |draws| generate(draws, kind))
}

/// [`generate_any`] as a proptest strategy.
pub fn any_polygon() -> impl Strategy<Value = (Kind, Polygon)> {
    from_draws(|draws| generate_any(draws))
}
