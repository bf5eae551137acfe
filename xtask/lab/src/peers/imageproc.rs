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

use std::hint::black_box;

use imageproc::drawing::draw_polygon_mut;
use imageproc::image::{GrayImage, Luma};
use imageproc::point::Point;
use raster::{Polygon, SpanSink, SCREEN};

use super::integer::{inputs, takes_any, whole_pixel_contour, Contour, Reach};
use super::rows::emit_rows;
use super::Peer;
use crate::convention::Own;
use crate::corpus::Family;

/// imageproc's `draw_polygon_mut` into a grey image.
pub struct Imageproc;

impl Peer for Imageproc {
    fn name(&self) -> &'static str {
        "imageproc"
    }

    fn source(&self) -> &'static str {
        "imageproc 0.27 draw_polygon_mut into a 320x200 GrayImage"
    }

    fn summary(&self) -> &'static str {
        "whole-pixel vertices; each row's crossings in f32, rounded, sorted; whole-pixel points, spans inclusive, \
         the outline drawn too; even-odd, one contour"
    }

    /// The closed polygon at whole-pixel points, its outline drawn too.
    fn own(&self) -> Own {
        Own::Closed { outline: true }
    }

    fn takes(&self, family: &Family) -> bool {
        takes_any(family, contour)
    }

    fn draw(&self, polygon: &Polygon, sink: &mut dyn SpanSink) -> Result<(), &'static str> {
        let points = points(&contour(polygon)?);
        let mut image = new_image();
        fill(&mut image, [points.as_slice()]);
        emit_runs(&image, polygon.color, sink);
        Ok(())
    }

    fn pass<'a>(&self, polygons: &[&'a Polygon]) -> Box<dyn FnMut() + 'a> {
        let polygons = inputs(polygons, contour, points);
        let mut image = new_image();
        Box::new(move || {
            fill(&mut image, polygons.iter().map(Vec::as_slice));
            black_box(&mut image);
        })
    }
}

/// The polygon as imageproc is given it, or why it is declined: no reach
/// of its own.
fn contour(polygon: &Polygon) -> Contour {
    whole_pixel_contour(polygon, Reach::ANY)
}

/// A polygon as `draw_polygon_mut` takes it.
fn points(contour: &[(i32, i32)]) -> Vec<Point<i32>> {
    contour.iter().map(|&(x, y)| Point::new(x, y)).collect()
}

/// A 320x200 grey image, black at first.
fn new_image() -> GrayImage {
    GrayImage::new(SCREEN.width as u32, SCREEN.height as u32)
}

/// Fills each of `polygons` in white.
fn fill<'a>(image: &mut GrayImage, polygons: impl IntoIterator<Item = &'a [Point<i32>]>) {
    for points in polygons {
        draw_polygon_mut(image, points, Luma([255]));
    }
}

/// The painted pixels, as spans into `sink`.
fn emit_runs(image: &GrayImage, color: u8, sink: &mut dyn SpanSink) {
    emit_rows(image.as_raw(), image.width() as usize, image.width() as usize, color, sink);
}
