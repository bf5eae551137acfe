//! imageproc 0.27's `draw_polygon_mut`, the image-processing crate of the
//! `image` family, into a 320x200 `GrayImage`.
//!
//! It takes `Point<i32>` vertices. For each row (clipped to the image) it
//! finds every edge's crossing in `f32`, rounded to a whole pixel, sorts
//! them and fills each pair inclusively, then draws every edge as a line
//! with `draw_line_segment_mut`, walking it pixel by pixel from end to
//! end, on the image or not (a far polygon costs its whole perimeter).
//! Its integers cannot overflow for any vertex we give it (at most 2^23
//! px), so it declines nothing for its reach.

use imageproc::drawing::draw_polygon_mut;
use imageproc::image::{GrayImage, Luma};
use imageproc::point::Point;
use raster::{SpanSink, SCREEN};

use super::emit_rows;

/// A polygon as `draw_polygon_mut` takes it.
pub fn points(contour: &[(i32, i32)]) -> Vec<Point<i32>> {
    contour.iter().map(|&(x, y)| Point::new(x, y)).collect()
}

/// A 320x200 grey image, black at first.
pub fn new_image() -> GrayImage {
    GrayImage::new(SCREEN.width as u32, SCREEN.height as u32)
}

/// Fills each of `polygons` in white.
pub fn fill<'a>(image: &mut GrayImage, polygons: impl IntoIterator<Item = &'a [Point<i32>]>) {
    for points in polygons {
        draw_polygon_mut(image, points, Luma([255]));
    }
}

/// The painted pixels, as spans into `sink`.
pub fn emit_runs(image: &GrayImage, color: u8, sink: &mut dyn SpanSink) {
    emit_rows(image.as_raw(), image.width() as usize, image.width() as usize, color, sink);
}
