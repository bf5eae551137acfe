//! `reference`: the rule of `docs/conventions.md#what-exact-means`
//! computed the plainest way, to judge every method by. Not a method (it is
//! not one of [`crate::MethodId::ALL`]): it is slow on purpose, visiting every
//! pixel of the polygon's bounding box within the target and testing every
//! edge at its sample point, with products in `i128` so that no `i32`
//! input can overflow.
//!
//! The sample point is a parameter, so a classic method can be judged under
//! its own convention as well as ours.

use alloc::vec::Vec;

use crate::geometry::{FillRule, Point, Polygon, SUBPIXEL_ONE};
use crate::target::SpanSink;

/// Where a method samples a pixel, in subpixels from the pixel's top-left
/// corner: (128, 128) is the centre (our convention), (0, 0) the integer
/// grid point (Abrash's). The lab judges a method against the reference
/// under our convention and under its own.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Convention {
    pub sample_x: i32,
    pub sample_y: i32,
    /// One line for people: how the method decides which pixels are in.
    pub summary: &'static str,
}

/// Where each pixel is sampled, in subpixels from its top-left corner.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SampleOffset {
    pub x: i32,
    pub y: i32,
}

impl SampleOffset {
    /// The pixel centre: our convention.
    pub const CENTRE: Self = Self { x: SUBPIXEL_ONE / 2, y: SUBPIXEL_ONE / 2 };

    /// The sample point a method states in its convention.
    pub const fn of(convention: &Convention) -> Self {
        Self { x: convention.sample_x, y: convention.sample_y }
    }
}

/// Draws into `sink`, as spans of `polygon.color`, every pixel whose sample
/// point is inside `polygon` by its fill rule.
///
/// # Examples
///
/// Judging a method: `exact` draws the reference's pixels, each once.
///
/// ```
/// use raster::reference::{self, SampleOffset};
/// use raster::{fill_auto, CoverageReport, CoverageSink, Point, Polygon, Size};
///
/// let size = Size { width: 12, height: 9 };
/// let star = Polygon::new(
///     [(6.0, 0.0), (8.5, 8.5), (0.5, 3.0), (11.5, 3.0), (3.5, 8.5)]
///         .map(|(x, y): (f64, f64)| Point::new((x * 256.0) as i32, (y * 256.0) as i32))
///         .to_vec(),
///     1,
/// );
/// let (mut expected, mut drawn) = (CoverageSink::new(size), CoverageSink::new(size));
/// reference::fill(&star, SampleOffset::CENTRE, &mut expected);
/// fill_auto(&star, &mut drawn).unwrap();
/// assert_eq!(drawn.report(&expected), CoverageReport::default());
/// ```
pub fn fill(polygon: &Polygon, sample: SampleOffset, sink: &mut dyn SpanSink) {
    let Some((low, high)) = bounding_box(polygon) else {
        return;
    };
    let size = sink.size();
    let edges: Vec<(Point, Point)> = polygon
        .contours
        .iter()
        .flat_map(|contour| contour.iter().copied().zip(contour.iter().copied().cycle().skip(1)))
        .collect();
    let columns = pixels_sampling(low.x, high.x, sample.x, size.width);
    for y in pixels_sampling(low.y, high.y, sample.y, size.height) {
        let sample_y = pixel_to_subpixels(y) + i64::from(sample.y);
        let meeting: Vec<(Point, Point)> = edges.iter().copied().filter(|&(a, b)| meets(a, b, sample_y)).collect();
        let mut run_start = None;
        for x in columns.clone() {
            let sample_x = pixel_to_subpixels(x) + i64::from(sample.x);
            match (run_start, is_inside(&meeting, polygon.rule, sample_x, sample_y)) {
                (None, true) => run_start = Some(x),
                (Some(start), false) => {
                    sink.span(y as i32, start as i32, x as i32, polygon.color);
                    run_start = None;
                }
                _ => {}
            }
        }
        if let Some(start) = run_start {
            sink.span(y as i32, start as i32, columns.end as i32, polygon.color);
        }
    }
}

/// The smallest and largest vertex coordinates, or `None` without vertices.
fn bounding_box(polygon: &Polygon) -> Option<(Point, Point)> {
    let mut vertices = polygon.contours.iter().flatten();
    let first = *vertices.next()?;
    Some(vertices.fold((first, first), |(low, high), p| {
        (Point::new(low.x.min(p.x), low.y.min(p.y)), Point::new(high.x.max(p.x), high.y.max(p.y)))
    }))
}

/// The pixels along one axis, within `0..limit`, that may sample a point in
/// `low..=high`, plus at most one before (floor division keeps it simple).
/// No pixel sampling outside the box can be inside: on its scan line every
/// crossing, if any, is on one side of it, and a closed contour crosses a
/// line as often down as up, so the count is even and the sum zero.
fn pixels_sampling(low: i32, high: i32, offset: i32, limit: i32) -> core::ops::Range<i64> {
    let one = i64::from(SUBPIXEL_ONE);
    let first = (i64::from(low) - i64::from(offset)).div_euclid(one).max(0);
    let last = (i64::from(high) - i64::from(offset)).div_euclid(one).min(i64::from(limit) - 1);
    first..(last + 1).max(first)
}

fn pixel_to_subpixels(pixel: i64) -> i64 {
    pixel * i64::from(SUBPIXEL_ONE)
}

/// Whether edge `a-b` meets the scan line at `sample_y`:
/// `y_top <= sample_y < y_bottom`, so horizontal edges never do.
fn meets(a: Point, b: Point, sample_y: i64) -> bool {
    let (top, bottom) = (i64::from(a.y.min(b.y)), i64::from(a.y.max(b.y)));
    top <= sample_y && sample_y < bottom
}

/// The fill rule at one sample point, over the edges meeting its scan line:
/// count the crossings at or left of it (even-odd: odd count is in) and sum
/// their directions, the sign of `dy` (non-zero: non-zero sum is in).
fn is_inside(meeting: &[(Point, Point)], rule: FillRule, sample_x: i64, sample_y: i64) -> bool {
    let (mut count, mut winding) = (0u64, 0i64);
    for &(a, b) in meeting.iter().filter(|&&(a, b)| crosses_at_or_left_of(a, b, sample_x, sample_y)) {
        count += 1;
        winding += if b.y > a.y { 1 } else { -1 };
    }
    match rule {
        FillRule::EvenOdd => count % 2 == 1,
        FillRule::NonZero => winding != 0,
    }
}

/// Whether edge `a-b`, which meets the scan line at `sample_y`, crosses it at
/// `x <= sample_x`. The crossing is `x = a.x + (sample_y - a.y) * dx / dy`;
/// multiplying `x - sample_x <= 0` through by `dy` keeps it exact, and flips
/// it when `dy` is negative.
fn crosses_at_or_left_of(a: Point, b: Point, sample_x: i64, sample_y: i64) -> bool {
    let (dx, dy) = (i128::from(b.x) - i128::from(a.x), i128::from(b.y) - i128::from(a.y));
    let scaled = (i128::from(a.x) - i128::from(sample_x)) * dy + (i128::from(sample_y) - i128::from(a.y)) * dx;
    if dy > 0 {
        scaled <= 0
    } else {
        scaled >= 0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::coverage::CoverageSink;
    use crate::target::Size;

    fn draw(polygon: &Polygon, sample: SampleOffset) -> alloc::string::String {
        let mut sink = CoverageSink::new(Size { width: 6, height: 4 });
        fill(polygon, sample, &mut sink);
        sink.ascii()
    }

    #[test]
    fn centre_samples_take_the_pixels_inside_a_grid_rectangle() {
        let rectangle = Polygon::from_pixels(&[(1, 1), (4, 1), (4, 3), (1, 3)], (0, 0), 1);
        assert_eq!(draw(&rectangle, SampleOffset::CENTRE), "......\n.###..\n.###..\n......\n");
    }

    #[test]
    fn corner_samples_take_the_left_and_top_edges() {
        // Abrash's convention: the rectangle's own top-left corner points are
        // on its edges and in; its right and bottom edges are out.
        let rectangle = Polygon::from_pixels(&[(1, 1), (4, 1), (4, 3), (1, 3)], (0, 0), 1);
        assert_eq!(draw(&rectangle, SampleOffset { x: 0, y: 0 }), "......\n.###..\n.###..\n......\n");
        // Shifted by half a pixel, centres and corners disagree.
        let shifted = Polygon::new(rectangle.contours[0].iter().map(|p| Point::new(p.x + 128, p.y + 128)).collect(), 1);
        assert_eq!(draw(&shifted, SampleOffset::CENTRE), "......\n.###..\n.###..\n......\n");
        assert_eq!(draw(&shifted, SampleOffset { x: 0, y: 0 }), "......\n......\n..###.\n..###.\n");
    }

    #[test]
    fn fill_rules_differ_on_a_doubly_wound_pentagram() {
        // A pentagram's centre is wound twice: out by even-odd, in by non-zero.
        let star = [(3, 0), (5, 4), (0, 1), (6, 1), (1, 4)];
        let mut polygon = Polygon::new(star.iter().map(|&(x, y)| Point::new(x * 256, y * 256)).collect(), 1);
        let even_odd = draw(&polygon, SampleOffset::CENTRE);
        polygon.rule = FillRule::NonZero;
        let non_zero = draw(&polygon, SampleOffset::CENTRE);
        // Worked by hand: on row 1 the crossings are at x = 5/6 (up), 2.25
        // (up), 3.75 (down), 31/6 (down), so centres 2.5 and 3.5 have two
        // crossings to their left, both upward.
        assert_eq!(even_odd, "......\n.#..#.\n...#..\n.#..#.\n");
        assert_eq!(non_zero, "......\n.####.\n..##..\n.#..#.\n");
    }

    #[test]
    fn extreme_coordinates_cover_the_whole_target() {
        let (lo, hi) = (i32::MIN, i32::MAX);
        let square = Polygon::new(
            alloc::vec![Point::new(lo, lo), Point::new(hi, lo), Point::new(hi, hi), Point::new(lo, hi)],
            1,
        );
        assert_eq!(draw(&square, SampleOffset::CENTRE), "######\n######\n######\n######\n");
    }
}
