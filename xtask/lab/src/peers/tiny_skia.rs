//! tiny-skia 0.12, aliased: `Mask::fill_path` with `anti_alias = false`
//! (Skia's non-AA scan converter: pixel centres, 26.6 fixed-point edges).
//! Its paths are `f32`, built from our subpixels: before timing starts,
//! as a program that keeps its paths would ([`TINY_SKIA`]), and inside
//! the timed pass, for every fill ([`TINY_SKIA_PATH_EACH_FILL`]).

use std::hint::black_box;

use raster::reference::SampleOffset;
use raster::{FillRule, Polygon, SpanSink, SCREEN};
use tiny_skia::{Mask, Path, PathBuilder, Transform};

use super::peer::{Clock, Peer, PeerInfo};
use super::rows::emit_rows;
use crate::convention::Own;

/// tiny-skia's aliased fill into a 320x200 mask, its paths built before
/// the clock starts or inside it.
pub struct TinySkia {
    info: PeerInfo,
    path_each_fill: bool,
}

const SURFACE: &str = "320x200 `Mask`";
const PIXELS: &str = "8-bit coverage (A8)";
const ALIASED: &str = "off (`anti_alias` false); a pixel is in by its centre";
const FILL: &str = "`Mask::fill_path`";

/// What both ways do alike inside the clock.
const BOTH_WAYS: Clock =
    Clock { before: "", setup: "", fill: FILL, surface: SURFACE, pixel_format: PIXELS, anti_aliasing: ALIASED };

/// Its paths built once, before the clock starts.
pub static TINY_SKIA: TinySkia = TinySkia {
    info: PeerInfo {
        name: "tiny-skia",
        source: "tiny-skia 0.12 Mask::fill_path, anti_alias false; paths built before timing",
        summary: "f32 path, 26.6 fixed-point edges; pixel centres",
        own: Own::Sample(SampleOffset::CENTRE),
        clock: Clock { before: "a `Path` (f32 pixels) and its fill rule", setup: "none", ..BOTH_WAYS },
        variant_of: None,
    },
    path_each_fill: false,
};

/// Its path built for every fill, inside the clock.
pub static TINY_SKIA_PATH_EACH_FILL: TinySkia = TinySkia {
    info: PeerInfo {
        name: "tiny-skia, path each fill",
        source: "tiny-skia 0.12 Mask::fill_path, anti_alias false; each path built inside the timed pass",
        summary: "f32 path, 26.6 fixed-point edges; pixel centres",
        own: Own::Sample(SampleOffset::CENTRE),
        clock: Clock {
            before: "nothing",
            setup: "`PathBuilder`: `move_to`, `line_to` a vertex, `close` a contour, `finish` (f32)",
            ..BOTH_WAYS
        },
        variant_of: Some("tiny-skia"),
    },
    path_each_fill: true,
};

impl Peer for TinySkia {
    fn info(&self) -> &PeerInfo {
        &self.info
    }

    fn draw(&self, polygon: &Polygon, sink: &mut dyn SpanSink) -> Result<(), &'static str> {
        let path = path(polygon).ok_or("tiny-skia builds no path from it")?;
        let mut mask = new_mask();
        mask.fill_path(&path, fill_rule(polygon.rule), false, Transform::identity());
        emit_runs(&mask, polygon.color, sink);
        Ok(())
    }

    fn pass<'a>(&self, polygons: &[&'a Polygon]) -> Box<dyn FnMut() + 'a> {
        let mut mask = new_mask();
        if self.path_each_fill {
            let polygons = polygons.to_vec();
            return Box::new(move || {
                for polygon in &polygons {
                    if let Some(path) = path(polygon) {
                        mask.fill_path(&path, fill_rule(polygon.rule), false, Transform::identity());
                    }
                }
                black_box(&mut mask);
            });
        }
        let paths: Vec<(Path, tiny_skia::FillRule)> =
            polygons.iter().filter_map(|p| Some((path(p)?, fill_rule(p.rule)))).collect();
        Box::new(move || {
            for (path, rule) in &paths {
                mask.fill_path(path, *rule, false, Transform::identity());
            }
            black_box(&mut mask);
        })
    }
}

fn new_mask() -> Mask {
    Mask::new(SCREEN.width as u32, SCREEN.height as u32).expect("a 320x200 mask is a valid size")
}

fn fill_rule(rule: FillRule) -> tiny_skia::FillRule {
    match rule {
        FillRule::EvenOdd => tiny_skia::FillRule::EvenOdd,
        FillRule::NonZero => tiny_skia::FillRule::Winding,
    }
}

/// The polygon as a tiny-skia path in pixels, one closed subpath per
/// contour; `None` where tiny-skia makes no path (nothing to draw).
fn path(polygon: &Polygon) -> Option<Path> {
    let one = raster::SUBPIXEL_ONE as f32;
    let mut builder = PathBuilder::new();
    for contour in &polygon.contours {
        let Some((first, rest)) = contour.split_first() else { continue };
        builder.move_to(first.x as f32 / one, first.y as f32 / one);
        for p in rest {
            builder.line_to(p.x as f32 / one, p.y as f32 / one);
        }
        builder.close();
    }
    builder.finish()
}

/// Every run of set mask bytes, as spans into `sink`.
fn emit_runs(mask: &Mask, color: u8, sink: &mut dyn SpanSink) {
    emit_rows(mask.data(), mask.width() as usize, mask.width() as usize, color, sink);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::peers::test_support::{square, Spans};

    #[test]
    fn tiny_skia_fills_a_grid_square_by_its_pixel_centres() {
        let mut spans = Spans(vec![]);
        TINY_SKIA.draw(&square(2, 3, 4), &mut spans).unwrap();
        assert_eq!(spans.0, vec![(3, 2, 6), (4, 2, 6), (5, 2, 6), (6, 2, 6)]);
    }

    #[test]
    fn tiny_skia_has_no_path_without_vertices() {
        assert!(TINY_SKIA.draw(&Polygon::default(), &mut Spans(vec![])).is_err());
    }
}
