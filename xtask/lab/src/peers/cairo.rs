//! Cairo, the C library most Linux desktops fill with, through
//! `cairo-rs` 0.22 over the system libcairo: `Context::fill` with
//! `Antialias::None` (its mono scan converter: pixel centres, 24.8
//! fixed-point edges) into an A8 image surface of 320x200. Its paths are
//! `f64` pixels, exact for our subpixels, set up for each polygon inside
//! the timed pass, as a program using Cairo would.

use std::hint::black_box;

use cairo::{Antialias, Context, Format, ImageSurface};
use raster::reference::SampleOffset;
use raster::{FillRule, Polygon, SpanSink, SCREEN};

use super::peer::{Peer, PeerInfo};
use super::rows::emit_rows;
use crate::convention::Own;

/// Cairo's aliased fill into a 320x200 A8 surface.
pub struct Cairo;

static INFO: PeerInfo = PeerInfo {
    name: "cairo",
    source: "system libcairo through cairo-rs 0.22: Context::fill, Antialias::None, A8 surface",
    summary: "f64 path, 24.8 fixed-point edges; pixel centres",
    own: Own::Sample(SampleOffset::CENTRE),
};

impl Peer for Cairo {
    fn info(&self) -> &PeerInfo {
        &INFO
    }

    fn draw(&self, polygon: &Polygon, sink: &mut dyn SpanSink) -> Result<(), &'static str> {
        let mut canvas = CairoCanvas::new().map_err(|_| "cairo made no surface")?;
        canvas.fill(polygon).map_err(|_| "cairo failed to fill")?;
        canvas.emit_runs(polygon.color, sink).map_err(|_| "cairo's pixels could not be read")
    }

    fn pass<'a>(&self, polygons: &[&'a Polygon]) -> Box<dyn FnMut() + 'a> {
        let polygons = polygons.to_vec();
        let mut canvas = CairoCanvas::new().expect("cairo makes a 320x200 A8 surface");
        Box::new(move || {
            for polygon in &polygons {
                // A failed fill costs what it costs, as a refusal does.
                let _ = canvas.fill(polygon);
            }
            black_box(&mut canvas);
        })
    }
}

/// Cairo's drawing state for one 320x200 A8 surface: aliased, opaque.
struct CairoCanvas {
    surface: ImageSurface,
    context: Context,
}

impl CairoCanvas {
    fn new() -> Result<Self, cairo::Error> {
        let surface = ImageSurface::create(Format::A8, SCREEN.width, SCREEN.height)?;
        let context = Context::new(&surface)?;
        context.set_antialias(Antialias::None);
        context.set_source_rgba(0.0, 0.0, 0.0, 1.0);
        Ok(Self { surface, context })
    }

    /// Fills `polygon`: one closed subpath per contour, in pixels.
    fn fill(&mut self, polygon: &Polygon) -> Result<(), cairo::Error> {
        let one = f64::from(raster::SUBPIXEL_ONE);
        let context = &self.context;
        context.set_fill_rule(match polygon.rule {
            FillRule::EvenOdd => cairo::FillRule::EvenOdd,
            FillRule::NonZero => cairo::FillRule::Winding,
        });
        for contour in &polygon.contours {
            let Some((first, rest)) = contour.split_first() else { continue };
            context.move_to(f64::from(first.x) / one, f64::from(first.y) / one);
            for p in rest {
                context.line_to(f64::from(p.x) / one, f64::from(p.y) / one);
            }
            context.close_path();
        }
        context.fill()
    }

    /// The surface's covered pixels, as spans into `sink`.
    fn emit_runs(&self, color: u8, sink: &mut dyn SpanSink) -> Result<(), cairo::BorrowError> {
        self.surface.flush();
        let (stride, width) = (self.surface.stride() as usize, self.surface.width() as usize);
        self.surface.with_data(|rows| emit_rows(rows, stride, width, color, sink))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::peers::test_support::{square, Spans};

    #[test]
    fn cairo_fills_a_grid_square_by_its_pixel_centres() {
        let mut spans = Spans(vec![]);
        Cairo.draw(&square(2, 3, 4), &mut spans).unwrap();
        assert_eq!(spans.0, vec![(3, 2, 6), (4, 2, 6), (5, 2, 6), (6, 2, 6)]);
    }

    #[test]
    fn cairo_leaves_a_hole_by_either_rule() {
        let mut holed = square(0, 0, 6);
        let mut hole = square(2, 2, 2).contours.remove(0);
        hole.reverse();
        holed.contours.push(hole);
        for rule in [FillRule::EvenOdd, FillRule::NonZero] {
            holed.rule = rule;
            let mut spans = Spans(vec![]);
            Cairo.draw(&holed, &mut spans).unwrap();
            assert_eq!(&spans.0[2..4], &[(2, 0, 2), (2, 4, 6)], "{rule:?}");
        }
    }
}
