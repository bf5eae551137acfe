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
use raster::{Polygon, SpanSink, SCREEN};

use super::integer::{whole_pixel_contour, Contour, IntegerPeer, IntegerTarget, Reach};
use super::peer::{Clock, PeerInfo};
use super::rows::emit_rows;
use crate::convention::Own;

/// imageproc's `draw_polygon_mut` into a grey image.
pub static IMAGEPROC: IntegerPeer<GrayCanvas> = IntegerPeer::new(PeerInfo {
    name: "imageproc",
    source: "imageproc 0.27 draw_polygon_mut into a 320x200 GrayImage",
    summary:
        "whole-pixel vertices; each row's crossings in f32, rounded, sorted; whole-pixel points, spans inclusive, \
         the outline drawn too; even-odd, one contour",
    // The closed polygon at whole-pixel points, its outline drawn too.
    own: Own::Closed { outline: true },
    clock: Clock {
        before: "the contour rounded to whole pixels, a `Vec<Point<i32>>`",
        setup: "none",
        fill: "`draw_polygon_mut`: the spans, then every edge as a line",
        surface: "320x200 `GrayImage`",
        pixel_format: "8-bit luma",
        anti_aliasing: "none; whole-pixel points, spans inclusive, the outline too",
    },
    variant_of: None,
});

/// A 320x200 grey image, black at first.
pub struct GrayCanvas(GrayImage);

impl IntegerTarget for GrayCanvas {
    type Input = Vec<Point<i32>>;

    /// No reach of its own.
    fn contour(polygon: &Polygon) -> Contour {
        whole_pixel_contour(polygon, Reach::ANY)
    }

    fn input(contour: &[(i32, i32)]) -> Vec<Point<i32>> {
        contour.iter().map(|&(x, y)| Point::new(x, y)).collect()
    }

    fn new() -> Result<Self, &'static str> {
        Ok(Self(GrayImage::new(SCREEN.width as u32, SCREEN.height as u32)))
    }

    /// Fills each of `polygons` in white.
    fn fill(&mut self, polygons: &[Vec<Point<i32>>]) -> Result<(), &'static str> {
        for points in polygons {
            draw_polygon_mut(&mut self.0, points, Luma([255]));
        }
        Ok(())
    }

    fn emit_runs(&self, color: u8, sink: &mut dyn SpanSink) {
        let image = &self.0;
        emit_rows(image.as_raw(), image.width() as usize, image.width() as usize, color, sink);
    }
}
