//! Exactly-once tiling: polygons that share edges draw every pixel once and
//! only once (`docs/conventions.md#shared-edges`), checked with a sink
//! that counts every draw.

mod exact_support;

use exact_support::PX;
use proptest::prelude::*;
use raster::methods::Exact;
use raster::reference::{self, SampleOffset};
use raster::{stores, CoverageReport, CoverageSink, Method, Point, Polygon, Size, SCREEN};

/// The sign of the turn `a -> b -> c`, exact for any `i32` points.
fn turn(a: Point, b: Point, c: Point) -> i128 {
    let cross = (i128::from(b.x) - i128::from(a.x)) * (i128::from(c.y) - i128::from(a.y))
        - (i128::from(b.y) - i128::from(a.y)) * (i128::from(c.x) - i128::from(a.x));
    cross.signum()
}

fn fill_triangles(triangles: &[[Point; 3]], size: Size) -> CoverageSink {
    let mut drawn = CoverageSink::new(size);
    for triangle in triangles {
        Exact.fill(&Polygon::new(triangle.to_vec(), 1), &mut drawn).expect("exact accepts every triangle");
    }
    drawn
}

/// Fleischer and Salesin's fan test: the fan of triangles from a vertex
/// inside the convex `ring` to each ring edge covers the ring, so with the
/// vertex on every subpixel position of pixel (3, 3) in turn the fan must
/// draw exactly the ring's pixels, each once.
fn assert_fan_draws_each_pixel_once(ring: &[Point]) {
    const SIZE: Size = Size { width: 8, height: 8 };
    let mut expected = CoverageSink::new(SIZE);
    reference::fill(&Polygon::new(ring.to_vec(), 1), SampleOffset::CENTRE, &mut expected);
    let ring_edges: Vec<(Point, Point)> = ring.iter().copied().zip(ring.iter().copied().cycle().skip(1)).collect();
    for sub_y in 0..PX {
        for sub_x in 0..PX {
            let hub = Point::new(3 * PX + sub_x, 3 * PX + sub_y);
            let fan: Vec<[Point; 3]> = ring_edges.iter().map(|&(a, b)| [hub, a, b]).collect();
            let first_turn = turn(hub, ring_edges[0].0, ring_edges[0].1);
            assert!(
                first_turn != 0 && fan.iter().all(|t| turn(t[0], t[1], t[2]) == first_turn),
                "hub {hub:?} must be inside the ring"
            );
            let drawn = fill_triangles(&fan, SIZE);
            let report = drawn.report(&expected);
            assert_eq!(report, CoverageReport::default(), "hub {hub:?}\n{}", drawn.ascii_against(&expected));
        }
    }
}

/// An octagon through pixel centres and corners: as the hub moves, fan
/// edges turn horizontal and vertical and pass through centres.
#[test]
fn fan_round_centres_and_corners_draws_each_pixel_once_for_every_hub_position() {
    let ring = [(256, 256), (896, 128), (1536, 256), (1664, 896), (1536, 1536), (896, 1664), (256, 1536), (128, 896)];
    assert_fan_draws_each_pixel_once(&ring.map(|(x, y)| Point::new(x, y)));
}

/// A clockwise quadrilateral on odd subpixels, reaching outside the target.
#[test]
fn fan_reaching_off_screen_draws_each_pixel_once_for_every_hub_position() {
    let ring = [(-301, -77), (-150, 1701), (1901, 2599), (2499, 517)];
    assert_fan_draws_each_pixel_once(&ring.map(|(x, y)| Point::new(x, y)));
}

/// Triangulates the rectangle `corners` (counter-clockwise on screen, y
/// down) by inserting `points` one by one: a point inside a triangle splits
/// it in three, a point on an edge splits the triangles on both sides in two
/// (children of no area are dropped); points outside or already vertices
/// are skipped. Every triangle keeps the rectangle's winding.
fn triangulate(corners: [Point; 4], points: &[Point]) -> Vec<[Point; 3]> {
    let [a, b, c, d] = corners;
    let mut triangles = vec![[a, b, c], [a, c, d]];
    let winding = turn(a, b, c);
    for &p in points {
        if triangles.iter().flatten().any(|&v| v == p) {
            continue;
        }
        triangles = triangles
            .into_iter()
            .flat_map(|t| {
                let contains = (0..3).all(|i| turn(t[i], t[(i + 1) % 3], p) != -winding);
                let children: Vec<[Point; 3]> = if contains {
                    (0..3)
                        .map(|i| [t[i], t[(i + 1) % 3], p])
                        .filter(|child| turn(child[0], child[1], child[2]) != 0)
                        .collect()
                } else {
                    vec![t]
                };
                children
            })
            .collect();
    }
    triangles
}

/// Points on the screen (its border included), half of them on a 10-pixel
/// grid so that many fall on edges and corners of earlier triangles.
fn screen_point() -> impl Strategy<Value = Point> {
    prop_oneof![
        (0..=SCREEN.width * PX, 0..=SCREEN.height * PX).prop_map(|(x, y)| Point::new(x, y)),
        (0..=SCREEN.width / 10, 0..=SCREEN.height / 10).prop_map(|(x, y)| Point::new(x * 10 * PX, y * 10 * PX)),
    ]
}

fn whole_screen() -> CoverageSink {
    let mut target = CoverageSink::new(SCREEN);
    stores::clear(&mut target, 1);
    target
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn random_triangulations_of_the_screen_cover_it_exactly_once(points in prop::collection::vec(screen_point(), 1..150)) {
        let (w, h) = (SCREEN.width * PX, SCREEN.height * PX);
        let corners = [Point::new(0, 0), Point::new(0, h), Point::new(w, h), Point::new(w, 0)];
        let drawn = fill_triangles(&triangulate(corners, &points), SCREEN);
        prop_assert_eq!(drawn.report(&whole_screen()), CoverageReport::default());
    }

    /// The same with the rectangle's corners at the `i32` extremes: huge
    /// slivers, clipped, still meet without gaps or overlaps.
    #[test]
    fn triangulations_of_the_whole_i32_plane_cover_the_screen_exactly_once(
        near in prop::collection::vec(screen_point(), 0..60),
        far in prop::collection::vec(any::<(i32, i32)>(), 1..30),
    ) {
        let (lo, hi) = (i32::MIN, i32::MAX);
        let corners = [Point::new(lo, lo), Point::new(lo, hi), Point::new(hi, hi), Point::new(hi, lo)];
        let points: Vec<Point> = far.iter().map(|&(x, y)| Point::new(x, y)).chain(near).collect();
        let drawn = fill_triangles(&triangulate(corners, &points), SCREEN);
        prop_assert_eq!(drawn.report(&whole_screen()), CoverageReport::default());
    }
}
