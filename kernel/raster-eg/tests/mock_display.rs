//! The adapter in embedded-graphics' own terms: drawn on its
//! `MockDisplay` (64x64), which panics on a pixel drawn twice or out of
//! bounds, every pixel is the one raster's reference draws. The shapes are
//! placed and clipped to fit it: holes under both rules, stars crossing
//! themselves, vertices far outside, 1/256-px vertices, a target whose box
//! does not start at (0, 0); a triangle embedded-graphics' own `Triangle`
//! panics on, and a fan of triangles whose shared edges it draws twice.

use std::panic::{catch_unwind, AssertUnwindSafe};

use embedded_graphics::mock_display::MockDisplay;
use embedded_graphics::pixelcolor::BinaryColor;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::{PrimitiveStyle, Rectangle, Triangle};
use raster::reference::{self, SampleOffset};
use raster::{CoverageSink, Polygon};
use raster_eg::{FillRule, FilledPolygon, FixedScratch, Refusal};

const SIDE: i32 = 64;

/// The pixels raster's reference draws for these whole-pixel contours on
/// a 64x64 target.
fn reference_pixels(contours: &[&[Point]], rule: FillRule) -> Vec<Point> {
    let contours = contours.iter().map(|c| c.iter().map(|p| raster::Point::from_pixels(p.x, p.y)).collect()).collect();
    reference_of(&Polygon { contours, color: 1, rule })
}

fn reference_of(polygon: &Polygon) -> Vec<Point> {
    let mut judge = CoverageSink::new(raster::Size { width: SIDE, height: SIDE });
    reference::fill(polygon, SampleOffset::CENTRE, &mut judge);
    (0..SIDE).flat_map(|y| (0..SIDE).map(move |x| Point::new(x, y))).filter(|p| judge.count(p.x, p.y) > 0).collect()
}

/// Draws `shape` on a fresh MockDisplay (which panics on overdraw or a
/// pixel out of bounds) and asserts its pixels are `expected`.
fn assert_draws<const V: usize>(shape: FilledPolygon<'_, V>, expected: &[Point], what: &str) {
    let mut display = MockDisplay::<BinaryColor>::new();
    let drawn = shape.into_styled(PrimitiveStyle::with_fill(BinaryColor::On)).draw(&mut display);
    assert_eq!(drawn, Ok(Ok(())), "{what}");
    display.assert_eq_with_message(&MockDisplay::from_points(expected.iter().copied(), BinaryColor::On), |f| {
        write!(f, "{what}")
    });
}

fn points(pairs: &[(i32, i32)]) -> Vec<Point> {
    pairs.iter().map(|&(x, y)| Point::new(x, y)).collect()
}

#[test]
fn every_shape_draws_the_references_pixels_once_each() {
    let square = points(&[(4, 4), (60, 4), (60, 60), (4, 60)]);
    let hole = points(&[(20, 20), (44, 20), (44, 44), (20, 44)]);
    let mut hole_back = hole.clone();
    hole_back.reverse();
    let star = points(&[(32, 2), (51, 60), (2, 24), (62, 24), (13, 60)]);
    let moved: Vec<Point> = star.iter().map(|p| *p + Point::new(-9, 3)).collect();
    let bridged =
        points(&[(2, 2), (40, 2), (40, 40), (2, 40), (2, 2), (10, 10), (10, 30), (30, 30), (30, 10), (10, 10)]);
    // Past every side of the display, and far out: clipped to it.
    let far = points(&[(-5_000_000, 30), (40, -3_000_000), (8_000_000, 70), (20, 4_000_000)]);
    let spike = points(&[(-100, -100), (100, 50), (-100, 63)]);
    let cases: Vec<(&str, Vec<&[Point]>)> = vec![
        ("square", vec![&square]),
        ("square with a hole", vec![&square, &hole]),
        ("square with a hole running back", vec![&square, &hole_back]),
        ("star", vec![&star]),
        ("bridged hole", vec![&bridged]),
        ("far corners", vec![&far]),
        ("spike past the left", vec![&spike]),
        ("two stars overlapping", vec![&star, &moved]),
    ];
    for (name, contours) in &cases {
        for rule in [FillRule::EvenOdd, FillRule::NonZero] {
            let what = format!("{name}, {rule:?}");
            let expected = reference_pixels(contours, rule);
            assert!(!expected.is_empty(), "{what} draws nothing");
            assert_draws(FilledPolygon::new(contours, rule), &expected, &what);
        }
    }
}

#[test]
fn subpixel_vertices_draw_the_references_pixels() {
    // Vertices off the pixel grid, on pixel centres, and at the ends of
    // the i32 range.
    let wedge = [raster::Point::new(100, 300), raster::Point::new(15_000, 3_000), raster::Point::new(640, 16_000)];
    let on_centres = [
        raster::Point::new(3 * 256 + 128, 128),
        raster::Point::new(60 * 256 + 128, 40 * 256 + 128),
        raster::Point::new(128, 50 * 256 + 128),
    ];
    let huge =
        [raster::Point::new(i32::MIN, i32::MIN), raster::Point::new(i32::MAX, 0), raster::Point::new(0, i32::MAX)];
    for contour in [&wedge[..], &on_centres, &huge] {
        for rule in [FillRule::EvenOdd, FillRule::NonZero] {
            let expected = reference_of(&Polygon { contours: vec![contour.to_vec()], color: 1, rule });
            assert_draws(FilledPolygon::subpixels(&[contour], rule), &expected, &format!("{contour:?}"));
        }
    }
}

#[test]
fn a_target_that_does_not_start_at_the_origin_gets_the_shape_at_its_own_coordinates() {
    // The display's bottom-right quarter, as a target of its own: the
    // polygon keeps its coordinates, and is clipped to that quarter.
    let diamond = points(&[(32, 0), (64, 32), (32, 64), (0, 32)]);
    let expected: Vec<Point> =
        reference_pixels(&[&diamond], FillRule::EvenOdd).into_iter().filter(|p| p.x >= 32 && p.y >= 32).collect();
    let mut display = MockDisplay::<BinaryColor>::new();
    let mut quarter = display.clipped(&Rectangle::new(Point::new(32, 32), Size::new(32, 32)));
    let subpixel: Vec<raster::Point> = diamond.iter().map(|p| raster::Point::from_pixels(p.x, p.y)).collect();
    let style = PrimitiveStyle::with_fill(BinaryColor::On);
    assert_eq!(FilledPolygon::new(&[&diamond], FillRule::EvenOdd).into_styled(style).draw(&mut quarter), Ok(Ok(())));
    display.assert_eq(&MockDisplay::from_points(expected.iter().copied(), BinaryColor::On));
    let mut display = MockDisplay::<BinaryColor>::new();
    let mut quarter = display.clipped(&Rectangle::new(Point::new(32, 32), Size::new(32, 32)));
    let contours: [&[raster::Point]; 1] = [&subpixel];
    let shape = FilledPolygon::subpixels(&contours, FillRule::EvenOdd);
    assert_eq!(shape.into_styled(style).draw(&mut quarter), Ok(Ok(())));
    display.assert_eq(&MockDisplay::from_points(expected.iter().copied(), BinaryColor::On));
}

/// A comb of `teeth` teeth 1 px wide under a bar: 4 * teeth edges.
fn comb(teeth: i32) -> Vec<Point> {
    let mut comb = points(&[(0, 0), (2 * teeth - 1, 0)]);
    for tooth in (0..teeth).rev() {
        let x = 2 * tooth;
        comb.extend(points(&[(x + 1, 60), (x, 60)]));
        if tooth > 0 {
            comb.extend(points(&[(x, 30), (x - 1, 30)]));
        }
    }
    comb
}

#[test]
fn a_polygon_beyond_the_room_is_refused_whole_and_drawn_with_more() {
    // 31 teeth, 124 edges: more than the 64 vertices converted by default.
    let teeth = comb(31);
    let expected = reference_pixels(&[&teeth], FillRule::NonZero);
    let mut display = MockDisplay::<BinaryColor>::new();
    let contours: [&[Point]; 1] = [&teeth];
    let shape = FilledPolygon::new(&contours, FillRule::NonZero);
    let style = PrimitiveStyle::with_fill(BinaryColor::On);
    assert_eq!(shape.into_styled(style).draw(&mut display), Ok(Err(Refusal::TooManyVertices)));
    assert_eq!(display.affected_area(), Rectangle::zero());
    assert_draws(shape.with_capacity::<124>(), &expected, "with room for its vertices");
    // Twice as many contours, 248 edges, of which the stack's tables take
    // all; and with a scratch of its own.
    let mut scratch = FixedScratch::<248>::new();
    let mut display = MockDisplay::<BinaryColor>::new();
    let twice: [&[Point]; 2] = [&teeth, &teeth];
    let both = FilledPolygon::new(&twice, FillRule::NonZero).with_capacity::<248>();
    assert_eq!(both.fill_with(BinaryColor::On, &mut display, &mut scratch), Ok(Ok(())));
    display.assert_eq(&MockDisplay::from_points(expected.iter().copied(), BinaryColor::On));
}

#[test]
fn triangles_embedded_graphics_panics_on_draw_exactly_through_the_adapter() {
    // Far corners: its cross products overflow i32 in a debug build (its
    // issue #719).
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let far = [Point::new(-60_000, -60_000), Point::new(60_000, 10), Point::new(10, 60_000)];
    let mut display = MockDisplay::<BinaryColor>::new();
    let style = PrimitiveStyle::with_fill(BinaryColor::On);
    let triangle = Triangle::new(far[0], far[1], far[2]).into_styled(style);
    let panicked = catch_unwind(AssertUnwindSafe(|| triangle.draw(&mut display))).is_err();
    std::panic::set_hook(hook);
    assert!(panicked, "embedded-graphics drew the far triangle");
    let contour = far.to_vec();
    let expected = reference_pixels(&[&contour], FillRule::EvenOdd);
    assert_draws(FilledPolygon::new(&[&contour], FillRule::EvenOdd), &expected, "far triangle");
}

#[test]
fn a_fan_of_triangles_draws_each_pixel_once_where_embedded_graphics_draws_shared_edges_twice() {
    // A quadrilateral cut into four triangles around an inner point: each
    // edge from it is shared by two triangles.
    let (centre, corners) = (Point::new(30, 28), points(&[(4, 4), (60, 10), (50, 58), (8, 50)]));
    let fan: Vec<Vec<Point>> = (0..4).map(|i| vec![centre, corners[i], corners[(i + 1) % 4]]).collect();
    let style = PrimitiveStyle::with_fill(BinaryColor::On);
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let mut theirs = MockDisplay::<BinaryColor>::new();
    let overdrawn = catch_unwind(AssertUnwindSafe(|| {
        for t in &fan {
            Triangle::new(t[0], t[1], t[2]).into_styled(style).draw(&mut theirs).unwrap();
        }
    }))
    .is_err();
    std::panic::set_hook(hook);
    assert!(overdrawn, "embedded-graphics drew the fan's shared edges once");
    let mut ours = MockDisplay::<BinaryColor>::new();
    for t in &fan {
        let contours: [&[Point]; 1] = [t];
        assert_eq!(FilledPolygon::new(&contours, FillRule::EvenOdd).into_styled(style).draw(&mut ours), Ok(Ok(())));
    }
    let whole = reference_pixels(&[&corners], FillRule::EvenOdd);
    ours.assert_eq(&MockDisplay::from_points(whole.iter().copied(), BinaryColor::On));
}

#[test]
fn the_bounding_box_holds_every_pixel_drawn() {
    let star = points(&[(32, 2), (51, 60), (2, 24), (62, 24), (13, 60)]);
    let contours: [&[Point]; 1] = [&star];
    let shape = FilledPolygon::new(&contours, FillRule::NonZero);
    assert_eq!(shape.bounding_box(), Rectangle::new(Point::new(2, 2), Size::new(60, 58)));
    let mut display = MockDisplay::<BinaryColor>::new();
    assert_eq!(shape.fill(BinaryColor::On, &mut display), Ok(Ok(())));
    let drawn = display.affected_area();
    assert_eq!(shape.bounding_box().intersection(&drawn), drawn);
    // 1/256-px vertices: the rows and columns whose centres are in the box.
    let thin = [raster::Point::new(129, 127), raster::Point::new(640, 127), raster::Point::new(129, 900)];
    assert_eq!(
        FilledPolygon::subpixels(&[&thin], FillRule::EvenOdd).bounding_box(),
        Rectangle::new(Point::new(1, 0), Size::new(2, 4))
    );
}
