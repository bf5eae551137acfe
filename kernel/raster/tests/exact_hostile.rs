//! Hostile input for `exact` (`docs/conventions.md#garbage-in-never-crashes`): nothing
//! panics, nothing is refused for its range, no span leaves the target, no
//! pixel is drawn twice, and the pixels are still the reference's.

mod exact_support;

use exact_support::{against_reference, nearby_point, Draws, Seeded, PX, TARGET};
use raster::methods::Exact;
use raster::{CoverageReport, CoverageSink, FillRule, Method, Point, Polygon, Refusal, Size, SpanSink};

fn exact(polygon: &Polygon, sink: &mut dyn SpanSink) -> Result<(), Refusal> {
    Exact.fill(polygon, sink)
}

fn with_rule(contours: Vec<Vec<Point>>, rule: FillRule) -> Polygon {
    Polygon { contours, color: 1, rule }
}

/// Fills with both rules and expects the reference's pixels, drawn once.
fn assert_matches_reference(contours: Vec<Vec<Point>>, size: Size) {
    for rule in [FillRule::EvenOdd, FillRule::NonZero] {
        let polygon = with_rule(contours.clone(), rule);
        let (result, report, picture) = against_reference(exact, &polygon, size);
        assert_eq!(result, Ok(()), "{polygon:?}");
        assert_eq!(report, CoverageReport::default(), "{polygon:?}\n{picture}");
    }
}

/// Fills with both rules and expects nothing drawn.
fn assert_draws_nothing(contours: Vec<Vec<Point>>) {
    for rule in [FillRule::EvenOdd, FillRule::NonZero] {
        let polygon = with_rule(contours.clone(), rule);
        let mut drawn = CoverageSink::new(TARGET);
        assert_eq!(exact(&polygon, &mut drawn), Ok(()));
        assert_eq!(
            drawn.report(&CoverageSink::new(TARGET)),
            CoverageReport::default(),
            "{polygon:?}\n{}",
            drawn.ascii()
        );
    }
}

fn points(coordinates: &[(i32, i32)]) -> Vec<Point> {
    coordinates.iter().map(|&(x, y)| Point::new(x, y)).collect()
}

#[test]
fn fewer_than_three_vertices_draw_nothing() {
    let (lo, hi) = (i32::MIN, i32::MAX);
    assert_draws_nothing(vec![]);
    assert_draws_nothing(vec![vec![], vec![]]);
    assert_draws_nothing(vec![points(&[(5 * PX, 5 * PX)])]);
    assert_draws_nothing(vec![points(&[(lo, lo), (hi, hi)])]);
    assert_draws_nothing(vec![points(&[(0, 0), (40 * PX, 30 * PX)]), points(&[(hi, lo)])]);
}

#[test]
fn collinear_and_repeated_vertices_draw_nothing() {
    let (lo, hi) = (i32::MIN, i32::MAX);
    // Through pixel centres, back and forth, with repeats.
    let diagonal = points(&[(128, 128), (128, 128), (2688, 2688), (1408, 1408), (5248, 5248), (128, 128)]);
    let horizontal = points(&[(0, 1152), (40 * PX, 1152), (7 * PX, 1152)]);
    let vertical = points(&[(1152, -PX), (1152, 50 * PX), (1152, 3 * PX)]);
    let across_the_plane = points(&[(lo, lo), (hi, hi), (0, 0), (-1, -1)]);
    let one_point_thrice = points(&[(3000, 3000), (3000, 3000), (3000, 3000)]);
    for contour in [diagonal, horizontal, vertical, across_the_plane, one_point_thrice] {
        assert_draws_nothing(vec![contour.clone()]);
        assert_draws_nothing(vec![contour.clone(), contour]);
    }
}

/// Every triangle, in either winding, with corners from a grid of the
/// `i32` extremes and points near the target.
#[test]
fn every_triangle_on_a_grid_of_extremes_matches_reference() {
    const SIZE: Size = Size { width: 6, height: 5 };
    let values = [i32::MIN, -1, 0, 2 * PX + PX / 2, i32::MAX - 1, i32::MAX];
    let grid: Vec<Point> = values.iter().flat_map(|&x| values.iter().map(move |&y| Point::new(x, y))).collect();
    for &a in &grid {
        for &b in &grid {
            for &c in &grid {
                let polygon = Polygon::new(vec![a, b, c], 1);
                let (result, report, picture) = against_reference(exact, &polygon, SIZE);
                assert_eq!(result, Ok(()), "{polygon:?}");
                assert_eq!(report, CoverageReport::default(), "{polygon:?}\n{picture}");
            }
        }
    }
}

/// `count` points around the target, the same on every run.
fn nearby_points(draws: &mut Seeded, count: usize) -> Vec<Point> {
    (0..count).map(|_| nearby_point(draws)).collect()
}

#[test]
fn thousands_of_vertices_match_reference() {
    let mut draws = Seeded::new(7);
    assert_matches_reference(vec![nearby_points(&mut draws, 4000)], TARGET);
    let mut mixed = nearby_points(&mut draws, 1000);
    mixed.extend((0..1000).map(|_| Point::new(draws.any_i32(), draws.any_i32())));
    assert_matches_reference(vec![mixed], TARGET);
}

#[test]
fn thousands_of_contours_match_reference() {
    let contours: Vec<Vec<Point>> = nearby_points(&mut Seeded::new(8), 3000).chunks(3).map(<[Point]>::to_vec).collect();
    assert_matches_reference(contours, TARGET);
}

/// Checks the sink contract and counts spans without storing pixels, so
/// targets too large for a [`CoverageSink`] can be used.
struct ContractSink {
    size: Size,
    spans: usize,
    broken: usize,
}

impl SpanSink for ContractSink {
    fn size(&self) -> Size {
        self.size
    }

    fn span(&mut self, y: i32, x_start: i32, x_end: i32, _color: u8) {
        self.spans += 1;
        self.broken += usize::from(!self.size.holds_span(y, x_start, x_end));
    }
}

/// A polygon over the whole `i32` plane meets 2^24 scan lines; only the
/// target's are visited, one span each, on targets of every shape.
#[test]
fn polygon_covering_the_i32_plane_costs_one_span_per_target_row() {
    let (lo, hi) = (i32::MIN, i32::MAX);
    let square = points(&[(lo, lo), (hi, lo), (hi, hi), (lo, hi)]);
    // Notched far below every target: not monotone, so the active-edge path.
    let notched = points(&[(lo, lo), (hi, lo), (hi, hi), (0, hi - 5), (lo, hi)]);
    let sizes =
        [Size { width: 320, height: 200 }, Size { width: i32::MAX, height: 3 }, Size { width: 1, height: 1 << 16 }];
    for contour in [square, notched] {
        for size in sizes {
            let mut sink = ContractSink { size, spans: 0, broken: 0 };
            assert_eq!(exact(&Polygon::new(contour.clone(), 1), &mut sink), Ok(()));
            assert_eq!((sink.spans, sink.broken), (size.height as usize, 0), "{contour:?} on {size:?}");
        }
    }
}

#[test]
fn targets_without_pixels_get_no_spans() {
    let square = Polygon::new(
        points(&[(i32::MIN, i32::MIN), (i32::MAX, i32::MIN), (i32::MAX, i32::MAX), (i32::MIN, i32::MAX)]),
        1,
    );
    for size in [
        Size { width: 0, height: 0 },
        Size { width: -5, height: 10 },
        Size { width: 10, height: -5 },
        Size { width: i32::MIN, height: i32::MIN },
    ] {
        let mut sink = ContractSink { size, spans: 0, broken: 0 };
        assert_eq!(exact(&square, &mut sink), Ok(()));
        assert_eq!(sink.spans, 0, "{size:?}");
    }
}
