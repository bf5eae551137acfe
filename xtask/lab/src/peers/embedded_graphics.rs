//! embedded-graphics 0.8: a filled `Triangle` (vertices rounded to whole
//! pixels, its only input), for triangle families only. Its draw target
//! writes through the same [`SpanSink`] as our methods, into the same
//! 320x200 [`Framebuffer`] when timed.

use std::hint::black_box;

use embedded_graphics::pixelcolor::Gray8;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::{PrimitiveStyle, Rectangle, Styled, Triangle};
use raster::reference::SampleOffset;
use raster::{Framebuffer, Polygon, SpanSink, SCREEN};

use super::peer::{Clock, Peer, PeerInfo};
use crate::convention::Own;
use crate::corpus::Family;

/// embedded-graphics's filled triangle.
pub struct EmbeddedGraphics;

static INFO: PeerInfo = PeerInfo {
    name: "embedded-graphics",
    source: "embedded-graphics 0.8 Triangle with fill style",
    summary: "whole-pixel vertices; i32 scanline intersections, edges drawn",
    // Pixel (x, y) at the whole-pixel point (x, y).
    own: Own::Sample(SampleOffset { x: 0, y: 0 }),
    clock: Clock {
        before: "a filled `Triangle` of whole-pixel vertices",
        setup: "none",
        fill: "`Triangle::draw` through a `DrawTarget` over the framebuffer's span store",
        surface: "320x200 `Framebuffer` (ours)",
        pixel_format: "8-bit index",
        anti_aliasing: "none; a pixel is in by its whole-pixel point",
    },
    variant_of: None,
};

impl Peer for EmbeddedGraphics {
    fn info(&self) -> &PeerInfo {
        &INFO
    }

    /// Families of triangles only.
    fn takes(&self, family: &Family) -> bool {
        family.polygons.iter().all(|p| triangle(p).is_some())
    }

    fn draw(&self, polygon: &Polygon, sink: &mut dyn SpanSink) -> Result<(), &'static str> {
        let shape = triangle(polygon).ok_or("not a triangle")?;
        draw_triangle(&shape, sink);
        Ok(())
    }

    fn pass<'a>(&self, polygons: &[&'a Polygon]) -> Box<dyn FnMut() + 'a> {
        let shapes: Vec<Styled<Triangle, PrimitiveStyle<Gray8>>> =
            polygons.iter().filter_map(|p| triangle(p)).collect();
        let mut screen = Framebuffer::new(SCREEN);
        Box::new(move || {
            for shape in &shapes {
                draw_triangle(shape, &mut screen);
            }
            black_box(&mut screen);
        })
    }
}

/// The polygon as a filled embedded-graphics triangle, vertices rounded to
/// whole pixels, or `None` unless it is one contour of three vertices.
fn triangle(polygon: &Polygon) -> Option<Styled<Triangle, PrimitiveStyle<Gray8>>> {
    let [a, b, c] = polygon.single_contour()? else { return None };
    let corner = |p: &raster::Point| {
        let q = p.round_to_pixel();
        embedded_graphics::geometry::Point::new(q.x, q.y)
    };
    Some(
        Triangle::new(corner(a), corner(b), corner(c))
            .into_styled(PrimitiveStyle::with_fill(Gray8::new(polygon.color))),
    )
}

/// Draws `shape` into `sink`; timed into a [`Framebuffer`], whose store is
/// then inlined as it is into our methods.
fn draw_triangle<S: SpanSink + ?Sized>(shape: &Styled<Triangle, PrimitiveStyle<Gray8>>, sink: &mut S) {
    let Ok(()) = shape.draw(&mut SpanTarget { sink });
}

/// An embedded-graphics draw target over a [`SpanSink`]: rows of a solid
/// rectangle become spans, single pixels one-pixel spans. As the
/// `DrawTarget` contract asks, whatever falls outside is dropped.
struct SpanTarget<'a, S: SpanSink + ?Sized> {
    sink: &'a mut S,
}

impl<S: SpanSink + ?Sized> SpanTarget<'_, S> {
    fn screen(&self) -> Rectangle {
        let size = self.sink.size();
        Rectangle::new(embedded_graphics::geometry::Point::zero(), Size::new(size.width as u32, size.height as u32))
    }
}

impl<S: SpanSink + ?Sized> Dimensions for SpanTarget<'_, S> {
    fn bounding_box(&self) -> Rectangle {
        self.screen()
    }
}

impl<S: SpanSink + ?Sized> DrawTarget for SpanTarget<'_, S> {
    type Color = Gray8;
    type Error = core::convert::Infallible;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Pixel<Gray8>>,
    {
        let screen = self.screen();
        for Pixel(p, color) in pixels {
            if screen.contains(p) {
                self.sink.span(p.y, p.x, p.x + 1, color.luma());
            }
        }
        Ok(())
    }

    fn fill_solid(&mut self, area: &Rectangle, color: Gray8) -> Result<(), Self::Error> {
        let visible = area.intersection(&self.screen());
        let columns = visible.columns();
        if !columns.is_empty() {
            for y in visible.rows() {
                self.sink.span(y, columns.start, columns.end, color.luma());
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::peers::test_support::{family, square, Spans};

    #[test]
    fn embedded_graphics_takes_only_triangles_and_clips() {
        assert!(EmbeddedGraphics.draw(&square(0, 0, 4), &mut Spans(vec![])).is_err());
        // Small enough for its i32 arithmetic: debug builds panic on the
        // square of a cross product beyond 46340 (intersection_params.rs).
        let corner = Polygon::from_pixels(&[(-10, -10), (100, -10), (-10, 100)], (0, 0), 1);
        let mut spans = Spans(vec![]);
        EmbeddedGraphics.draw(&corner, &mut spans).unwrap();
        assert!(spans.0.iter().all(|&(y, x0, x1)| (0..200).contains(&y) && 0 <= x0 && x0 < x1 && x1 <= 320));
        assert_eq!(spans.0.first(), Some(&(0, 0, 91)));
    }

    #[test]
    fn embedded_graphics_takes_only_families_of_triangles() {
        let triangle = Polygon::from_pixels(&[(0, 0), (9, 0), (0, 9)], (0, 0), 1);
        assert!(EmbeddedGraphics.takes(&family(vec![triangle.clone(), triangle.clone()])));
        assert!(!EmbeddedGraphics.takes(&family(vec![triangle, square(0, 0, 10)])));
    }
}
