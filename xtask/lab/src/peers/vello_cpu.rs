//! vello_cpu 0.3 (linebender), the state of the art in Rust CPU
//! rendering, with its aliasing threshold: a pixel is painted when the
//! part of it the polygon covers is above 127/255 (it thresholds area
//! coverage, not a sample point), opaque, with the polygon's fill rule,
//! into an RGBA pixmap of 320x200, single threaded, at the SIMD level it
//! detects. A timed pass fills its polygons one after another into one
//! render context and renders them once, compositing over what the pixmap
//! holds, as a program draws a frame with it (rendering each polygon on
//! its own costs a whole render of the 320x200 target per polygon); each
//! polygon's time includes its share of that render. Its `kurbo` paths are
//! `f64` pixels, exact for our subpixels: built before timing starts, as a
//! program that keeps its paths would ([`VELLO_CPU`]), and inside the
//! timed pass, for every fill ([`VELLO_CPU_PATH_EACH_FILL`]).

use std::hint::black_box;

use raster::{FillRule, Polygon, SpanSink, SCREEN};
use vello_cpu::color::palette::css::WHITE;
use vello_cpu::kurbo::BezPath;
use vello_cpu::peniko::Fill;
use vello_cpu::{Pixmap, RasterizerSettings, RenderContext, Resources, TargetInit};

use super::peer::{Clock, Peer, PeerInfo};
use super::rows::emit_rows;
use crate::convention::Own;

/// vello_cpu's aliasing threshold: painted above 127/255 of a pixel.
const VELLO_THRESHOLD: u8 = 127;

/// vello_cpu's aliased fill into a 320x200 pixmap, its paths built
/// before the clock starts or inside it.
pub struct VelloCpu {
    info: PeerInfo,
    path_each_fill: bool,
}

const SUMMARY: &str = "f64 path flattened to f32 lines, sparse strips of 4-pixel tiles, analytic area coverage; \
     thresholds area coverage (painted above 127/255 of the pixel) rather than sampling centres";
const FILL: &str = "`set_fill_rule`, `fill_path` (flattened, strips); once a pass, `render_with` of the whole target, \
     composited over it";
const SURFACE: &str = "320x200 `Pixmap`";
const PIXELS: &str = "RGBA, 8 bits a channel, premultiplied";
const ALIASED: &str = "area coverage computed, then thresholded: in above 127/255 of the pixel";

/// What both ways do alike inside the clock.
const BOTH_WAYS: Clock =
    Clock { before: "", setup: "", fill: FILL, surface: SURFACE, pixel_format: PIXELS, anti_aliasing: ALIASED };

/// Its paths built once, before the clock starts.
pub static VELLO_CPU: VelloCpu = VelloCpu {
    info: PeerInfo {
        name: "vello_cpu",
        source:
            "vello_cpu 0.3 RenderContext::fill_path, aliasing threshold 127, rendered into a 320x200 pixmap once a \
             pass; paths built before timing",
        summary: SUMMARY,
        // By the part of the pixel covered.
        own: Own::Coverage { threshold: VELLO_THRESHOLD },
        clock: Clock { before: "a kurbo `BezPath` (f64 pixels) and its fill rule", setup: "none", ..BOTH_WAYS },
        variant_of: None,
    },
    path_each_fill: false,
};

/// Its path built for every fill, inside the clock.
pub static VELLO_CPU_PATH_EACH_FILL: VelloCpu = VelloCpu {
    info: PeerInfo {
        name: "vello_cpu, path each fill",
        source:
            "vello_cpu 0.3 RenderContext::fill_path, aliasing threshold 127, rendered into a 320x200 pixmap once a \
             pass; each path built inside the timed pass",
        summary: SUMMARY,
        own: Own::Coverage { threshold: VELLO_THRESHOLD },
        clock: Clock {
            before: "nothing",
            setup: "`BezPath`: `move_to`, `line_to` a vertex, `close_path` a contour (f64)",
            ..BOTH_WAYS
        },
        variant_of: Some("vello_cpu"),
    },
    path_each_fill: true,
};

impl Peer for VelloCpu {
    fn info(&self) -> &PeerInfo {
        &self.info
    }

    fn draw(&self, polygon: &Polygon, sink: &mut dyn SpanSink) -> Result<(), &'static str> {
        let mut canvas = VelloCanvas::new();
        canvas.fill(&bez_path(polygon), vello_rule(polygon.rule));
        canvas.render(TargetInit::Clear(WHITE.with_alpha(0.0)));
        canvas.emit_runs(polygon.color, sink);
        Ok(())
    }

    fn pass<'a>(&self, polygons: &[&'a Polygon]) -> Box<dyn FnMut() + 'a> {
        let mut canvas = VelloCanvas::new();
        if self.path_each_fill {
            let polygons = polygons.to_vec();
            return Box::new(move || {
                for polygon in &polygons {
                    canvas.fill(&bez_path(polygon), vello_rule(polygon.rule));
                }
                canvas.render(TargetInit::SrcOver);
                black_box(&mut canvas);
            });
        }
        let paths: Vec<(BezPath, Fill)> = polygons.iter().map(|p| (bez_path(p), vello_rule(p.rule))).collect();
        Box::new(move || {
            for (path, rule) in &paths {
                canvas.fill(path, *rule);
            }
            canvas.render(TargetInit::SrcOver);
            black_box(&mut canvas);
        })
    }
}

/// The polygon as a vello path in pixels, one closed subpath per contour.
fn bez_path(polygon: &Polygon) -> BezPath {
    let one = f64::from(raster::SUBPIXEL_ONE);
    let mut path = BezPath::new();
    for contour in &polygon.contours {
        let Some((first, rest)) = contour.split_first() else { continue };
        path.move_to((f64::from(first.x) / one, f64::from(first.y) / one));
        for p in rest {
            path.line_to((f64::from(p.x) / one, f64::from(p.y) / one));
        }
        path.close_path();
    }
    path
}

fn vello_rule(rule: FillRule) -> Fill {
    match rule {
        FillRule::EvenOdd => Fill::EvenOdd,
        FillRule::NonZero => Fill::NonZero,
    }
}

/// vello_cpu's drawing state for one 320x200 pixmap: single threaded,
/// aliased by its threshold, opaque white.
struct VelloCanvas {
    context: RenderContext,
    resources: Resources,
    pixmap: Pixmap,
}

impl VelloCanvas {
    fn new() -> Self {
        let (width, height) = (SCREEN.width as u16, SCREEN.height as u16);
        let mut context = RenderContext::new(width, height);
        context.set_aliasing_threshold(Some(VELLO_THRESHOLD));
        context.set_paint(WHITE);
        Self { context, resources: Resources::new(), pixmap: Pixmap::new(width, height) }
    }

    /// Adds `path` to what the next [`VelloCanvas::render`] draws.
    fn fill(&mut self, path: &BezPath, rule: Fill) {
        self.context.set_fill_rule(rule);
        self.context.fill_path(path);
    }

    /// Draws what was filled since the last render into the pixmap, `init`
    /// saying whether it is cleared first, and starts afresh.
    fn render(&mut self, init: TargetInit) {
        let context = &mut self.context;
        context.flush();
        let settings = RasterizerSettings { target_init: init, ..RasterizerSettings::default() };
        context.render_with(&mut self.pixmap, &mut self.resources, settings);
        // A reset forgets the threshold and the paint too.
        context.reset();
        context.set_aliasing_threshold(Some(VELLO_THRESHOLD));
        context.set_paint(WHITE);
    }

    /// The painted pixels (any alpha), as spans into `sink`.
    fn emit_runs(&self, color: u8, sink: &mut dyn SpanSink) {
        let alpha: Vec<u8> = self.pixmap.data().iter().map(|pixel| pixel.a).collect();
        emit_rows(&alpha, SCREEN.width as usize, SCREEN.width as usize, color, sink);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::peers::test_support::{square, Spans};

    #[test]
    fn vello_cpu_fills_a_grid_square_whole() {
        let mut spans = Spans(vec![]);
        VELLO_CPU.draw(&square(2, 3, 4), &mut spans).unwrap();
        assert_eq!(spans.0, vec![(3, 2, 6), (4, 2, 6), (5, 2, 6), (6, 2, 6)]);
    }

    /// Half a pixel past a pixel's centre on the right is 60% of it: in
    /// by area; a sliver 0.4 px wide covers no pixel by more than half.
    #[test]
    fn vello_cpu_paints_by_the_part_of_the_pixel_covered() {
        let px = |v: f64| (v * 256.0) as i32;
        let rect = |x0: f64, x1: f64| {
            Polygon::new(
                [(x0, 1.0), (x1, 1.0), (x1, 2.0), (x0, 2.0)]
                    .iter()
                    .map(|&(x, y)| raster::Point::new(px(x), px(y)))
                    .collect(),
                1,
            )
        };
        let mut spans = Spans(vec![]);
        VELLO_CPU.draw(&rect(1.0, 3.6), &mut spans).unwrap();
        assert_eq!(spans.0, vec![(1, 1, 4)]);
        let mut spans = Spans(vec![]);
        VELLO_CPU.draw(&rect(5.3, 5.7), &mut spans).unwrap();
        assert_eq!(spans.0, vec![]);
    }
}
