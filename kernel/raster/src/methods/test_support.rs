//! What the methods' unit tests share: filling into a [`CoverageSink`],
//! which counts every draw (several methods draw some pixels twice, by
//! their convention) and every span that breaks the sink contract, and
//! its [`CoverageSink::ascii`] pictures. Hostile input for every method is
//! one suite, `tests/hostile.rs`.

use alloc::string::String;

use crate::coverage::CoverageSink;
use crate::geometry::{Point, Polygon, SUBPIXEL_ONE};
use crate::methods::interface::Method;
use crate::target::{Size, SCREEN};

/// The target of the small pictures.
pub(crate) const SMALL: Size = Size { width: 8, height: 6 };

/// `polygon` filled by `method` into a target of `size`. Fails the test if
/// the method declines it or emits a span outside the target.
pub(crate) fn fill(method: &dyn Method, polygon: &Polygon, size: Size) -> CoverageSink {
    let mut sink = CoverageSink::new(size);
    let name = method.info().name;
    assert_eq!(method.fill(polygon, &mut sink), Ok(()), "{name} declined {polygon:?}");
    assert_eq!(sink.out_of_bounds(), 0, "{name} drew outside {size:?}:\n{}", sink.ascii());
    sink
}

/// The picture of whole-pixel `points` filled by `method` into [`SMALL`]:
/// `.` never drawn, `#` once, the count for more.
pub(crate) fn draw(method: &dyn Method, points: &[(i32, i32)]) -> String {
    fill(method, &Polygon::from_pixels(points, (0, 0), 1), SMALL).ascii()
}

/// [`SMALL`] wholly drawn, once.
pub(crate) fn full() -> String {
    "########\n".repeat(SMALL.height as usize)
}

/// [`SMALL`] with nothing drawn.
pub(crate) fn empty() -> String {
    "........\n".repeat(SMALL.height as usize)
}

/// Triangles reaching 1000 rows above the screen and on into it, for
/// [`assert_clipping_changes_no_pixel`]: X-major edges both ways, Y-major
/// edges both ways, a diagonal and a vertical.
pub(crate) const TALL_TRIANGLES: [&[(i32, i32)]; 3] = [
    &[(160, 0), (2900, 1999), (-2500, 1999)],
    &[(5, 0), (250, 1200), (0, 1100)],
    &[(100, 3), (2000, 1903), (100, 1903)],
];

/// Fills `polygon` whole into a target 2000 rows tall and, moved up 1000
/// rows, into the screen, which must then show rows 1000 to 1199 of the
/// tall picture, and some pixels: clipping away the rows above the target
/// must not move a pixel.
pub(crate) fn assert_clipping_changes_no_pixel(method: &dyn Method, polygon: &Polygon) {
    const ROWS_ABOVE: i32 = 1000;
    let tall = Size { width: SCREEN.width, height: 2000 };
    let whole = fill(method, polygon, tall).ascii();
    let mut moved = polygon.clone();
    for point in moved.contours.iter_mut().flatten() {
        *point = Point::new(point.x, point.y - ROWS_ABOVE * SUBPIXEL_ONE);
    }
    let clipped = fill(method, &moved, SCREEN).ascii();
    let row_length = SCREEN.width as usize + 1;
    let start = ROWS_ABOVE as usize * row_length;
    assert!(clipped.contains('#'), "{polygon:?} is not on the screen");
    assert!(clipped == whole[start..start + clipped.len()], "clipping moved pixels of {polygon:?}");
}
