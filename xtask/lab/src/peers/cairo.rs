//! Cairo, the C library most Linux desktops fill with, through
//! `cairo-rs` 0.22 over the system libcairo: `Context::fill` with
//! `Antialias::None` (its mono scan converter: pixel centres, 24.8
//! fixed-point edges) into an A8 image surface of 320x200. Its paths are
//! `f64` pixels, exact for our subpixels: set up for each polygon inside
//! the timed pass, as most programs using Cairo do ([`CAIRO`]), or made
//! once before timing and appended to the context for every fill
//! (`copy_path` and `append_path`, [`CAIRO_PATH_KEPT`]), which still
//! copies the path into the context each time: Cairo has no path object
//! it fills without that copy.

use std::hint::black_box;

use cairo::{Antialias, Context, Format, ImageSurface};
use raster::reference::SampleOffset;
use raster::{FillRule, Polygon, SpanSink, SCREEN};

use super::peer::{Clock, Peer, PeerInfo};
use super::rows::emit_rows;
use crate::convention::Own;

/// Cairo's aliased fill into a 320x200 A8 surface, its paths set up for
/// every fill or kept.
pub struct Cairo {
    info: PeerInfo,
    path_kept: bool,
}

const SURFACE: &str = "320x200 A8 `ImageSurface`";
const PIXELS: &str = "8-bit alpha (A8)";
const ALIASED: &str = "off (`Antialias::None`); a pixel is in by its centre";
const FILL: &str = "`Context::fill`";

/// What both ways do alike inside the clock.
const BOTH_WAYS: Clock =
    Clock { before: "", setup: "", fill: FILL, surface: SURFACE, pixel_format: PIXELS, anti_aliasing: ALIASED };

/// Its path set up for each polygon inside the clock.
pub static CAIRO: Cairo = Cairo {
    info: PeerInfo {
        name: "cairo",
        source: "system libcairo through cairo-rs 0.22: Context::fill, Antialias::None, A8 surface; each path set up \
             inside the timed pass",
        summary: "f64 path, 24.8 fixed-point edges; pixel centres",
        own: Own::Sample(SampleOffset::CENTRE),
        clock: Clock {
            before: "nothing",
            setup: "`set_fill_rule`, `move_to`, `line_to` a vertex, `close_path` a contour (f64)",
            ..BOTH_WAYS
        },
        variant_of: None,
    },
    path_kept: false,
};

/// Its paths made once before the clock, appended for each fill.
pub static CAIRO_PATH_KEPT: Cairo = Cairo {
    info: PeerInfo {
        name: "cairo, path kept",
        source: "system libcairo through cairo-rs 0.22: Context::append_path then fill, Antialias::None, A8 surface; \
             paths made once before timing (copy_path)",
        summary: "f64 path, 24.8 fixed-point edges; pixel centres",
        own: Own::Sample(SampleOffset::CENTRE),
        clock: Clock {
            before: "a `cairo::Path` (f64), made once (`copy_path`), and its fill rule",
            setup: "`set_fill_rule`, `append_path` (Cairo copies the path into the context)",
            ..BOTH_WAYS
        },
        variant_of: Some("cairo"),
    },
    path_kept: true,
};

impl Peer for Cairo {
    fn info(&self) -> &PeerInfo {
        &self.info
    }

    fn draw(&self, polygon: &Polygon, sink: &mut dyn SpanSink) -> Result<(), &'static str> {
        let mut canvas = CairoCanvas::new().map_err(|_| "cairo made no surface")?;
        let filled = if self.path_kept {
            canvas.kept_path(polygon).and_then(|path| canvas.fill_kept(&path, fill_rule(polygon.rule)))
        } else {
            canvas.fill(polygon)
        };
        filled.map_err(|_| "cairo failed to fill")?;
        canvas.emit_runs(polygon.color, sink).map_err(|_| "cairo's pixels could not be read")
    }

    fn pass<'a>(&self, polygons: &[&'a Polygon]) -> Box<dyn FnMut() + 'a> {
        let mut canvas = CairoCanvas::new().expect("cairo makes a 320x200 A8 surface");
        if self.path_kept {
            let paths: Vec<(cairo::Path, cairo::FillRule)> =
                polygons.iter().filter_map(|p| Some((canvas.kept_path(p).ok()?, fill_rule(p.rule)))).collect();
            return Box::new(move || {
                for (path, rule) in &paths {
                    let _ = canvas.fill_kept(path, *rule);
                }
                black_box(&mut canvas);
            });
        }
        let polygons = polygons.to_vec();
        Box::new(move || {
            for polygon in &polygons {
                // A failed fill costs what it costs, as a refusal does.
                let _ = canvas.fill(polygon);
            }
            black_box(&mut canvas);
        })
    }
}

fn fill_rule(rule: FillRule) -> cairo::FillRule {
    match rule {
        FillRule::EvenOdd => cairo::FillRule::EvenOdd,
        FillRule::NonZero => cairo::FillRule::Winding,
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
        self.context.set_fill_rule(fill_rule(polygon.rule));
        self.set_path(polygon);
        self.context.fill()
    }

    /// `polygon`'s path, made in the context and copied out of it, to be
    /// filled later by [`CairoCanvas::fill_kept`].
    fn kept_path(&mut self, polygon: &Polygon) -> Result<cairo::Path, cairo::Error> {
        self.set_path(polygon);
        let path = self.context.copy_path();
        self.context.new_path();
        path
    }

    /// Fills a path made by [`CairoCanvas::kept_path`].
    fn fill_kept(&mut self, path: &cairo::Path, rule: cairo::FillRule) -> Result<(), cairo::Error> {
        self.context.set_fill_rule(rule);
        self.context.append_path(path);
        self.context.fill()
    }

    /// Makes `polygon` the context's path: one closed subpath per contour.
    fn set_path(&mut self, polygon: &Polygon) {
        let one = f64::from(raster::SUBPIXEL_ONE);
        let context = &self.context;
        for contour in &polygon.contours {
            let Some((first, rest)) = contour.split_first() else { continue };
            context.move_to(f64::from(first.x) / one, f64::from(first.y) / one);
            for p in rest {
                context.line_to(f64::from(p.x) / one, f64::from(p.y) / one);
            }
            context.close_path();
        }
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
        CAIRO.draw(&square(2, 3, 4), &mut spans).unwrap();
        assert_eq!(spans.0, vec![(3, 2, 6), (4, 2, 6), (5, 2, 6), (6, 2, 6)]);
    }

    /// The kept path fills what the path set up for the fill does.
    #[test]
    fn a_kept_path_fills_the_same_pixels() {
        let mut star = Polygon::from_pixels(&[(50, 0), (80, 90), (5, 35), (95, 35), (20, 90)], (0, 0), 1);
        for rule in [FillRule::EvenOdd, FillRule::NonZero] {
            star.rule = rule;
            let mut each = CairoCanvas::new().unwrap();
            each.fill(&star).unwrap();
            let mut kept = CairoCanvas::new().unwrap();
            let path = kept.kept_path(&star).unwrap();
            kept.fill_kept(&path, fill_rule(rule)).unwrap();
            let (mut a, mut b) = (Spans(vec![]), Spans(vec![]));
            each.emit_runs(1, &mut a).unwrap();
            kept.emit_runs(1, &mut b).unwrap();
            assert!(!a.0.is_empty());
            assert_eq!(a.0, b.0, "{rule:?}");
        }
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
            CAIRO.draw(&holed, &mut spans).unwrap();
            assert_eq!(&spans.0[2..4], &[(2, 0, 2), (2, 4, 6)], "{rule:?}");
        }
    }
}
