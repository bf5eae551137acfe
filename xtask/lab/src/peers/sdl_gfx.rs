//! SDL2_gfx's `filledPolygonRGBA`, SDL's drawing add-on (what pygame's
//! `gfxdraw` wraps), through the `sdl2` crate 0.38 with its `gfx` feature
//! over the system SDL2 and SDL2_gfx (Debian's `libsdl2-gfx-dev`):
//! `Canvas::filled_polygon`, which calls `filledPolygonColor`, a wrapper
//! of `filledPolygonRGBA`, on SDL's software renderer
//! (`SDL_CreateSoftwareRenderer`) over an INDEX8 surface of 320x200 with
//! a grey palette. No video driver is needed.
//!
//! Its vertices are `Sint16`. For each row it computes every edge's
//! crossing in 16.16 fixed point in `int`, `((65536 * (y - y1)) / (y2 -
//! y1)) * (x2 - x1) + 65536 * x1`, sorts them and draws each pair as a
//! line through the renderer. `65536 * (y - y1)` overflows `int` once two
//! vertices are 32,768 px apart, which `Sint16` allows: within 16,383 px
//! of the origin nothing overflows, so vertices beyond are declined. It
//! keeps the crossings in one buffer for the whole library, so calls are
//! made one at a time.

use std::sync::{Mutex, MutexGuard};

use raster::{Polygon, SpanSink, SCREEN};
use sdl2::gfx::primitives::DrawRenderer;
use sdl2::pixels::{Color, Palette, PixelFormatEnum};
use sdl2::render::Canvas;
use sdl2::surface::Surface;

use super::integer::{whole_pixel_contour, Contour, IntegerPeer, Reach};
use super::peer::{Clock, PeerInfo};
use super::rows::emit_rows;
use crate::convention::Own;

/// What `filledPolygonRGBA` takes: within 16,383 px its products fit.
pub const REACH: Reach =
    Reach { pixels: 16_383, beyond: "a vertex past 16,383 px, where its 16.16 fixed point overflows int" };

/// SDL2_gfx's `filledPolygonRGBA` on SDL's software renderer.
pub static SDL_GFX: IntegerPeer<SdlCanvas> = IntegerPeer::new(PeerInfo {
    name: "sdl2_gfx",
    source: "system SDL2_gfx through the sdl2 crate 0.38: filledPolygonRGBA on SDL's software renderer over a 320x200 \
         INDEX8 surface",
    summary: "whole-pixel Sint16 vertices (within 16,383 px); each row's crossings in 16.16 fixed point, sorted; \
         whole-pixel points, spans inclusive; even-odd, one contour",
    // The closed polygon at whole-pixel points, no outline.
    own: Own::Closed { outline: false },
    clock: Clock {
        before: "the contour rounded to whole pixels, `Sint16` x and y arrays",
        setup: "none",
        fill: "`filledPolygonRGBA`: a row's blend mode, colour and line through the renderer, row by row",
        surface: "SDL's software renderer over a 320x200 surface",
        pixel_format: "INDEX8, a grey palette",
        anti_aliasing: "none; whole-pixel points, spans inclusive",
    },
    variant_of: None,
});

/// SDL2_gfx's buffer of crossings (`gfxPrimitivesPolyIntsGlobal`) is used
/// by one thread at a time.
fn lock() -> MutexGuard<'static, ()> {
    static SDL_GFX: Mutex<()> = Mutex::new(());
    SDL_GFX.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// A polygon as `filledPolygonRGBA` takes it: its x and its y, apart.
pub struct Vertices {
    x: Vec<i16>,
    y: Vec<i16>,
}

/// SDL's software renderer over a 320x200 INDEX8 surface whose palette
/// is grey: index `i` is `(i, i, i)`, so white is 255 and black, the
/// surface's first state, 0.
pub struct SdlCanvas {
    canvas: Canvas<Surface<'static>>,
}

impl super::integer::IntegerTarget for SdlCanvas {
    type Input = Vertices;

    /// Besides the reach, `filledPolygonRGBA` returns -1 for fewer than 3
    /// vertices.
    fn contour(polygon: &Polygon) -> Contour {
        let contour = whole_pixel_contour(polygon, REACH)?;
        if contour.len() < 3 {
            return Err("fewer than 3 vertices (filledPolygonRGBA returns -1)");
        }
        Ok(contour)
    }

    /// The vertices as `Sint16`, which [`REACH`] keeps them within.
    fn input(contour: &[(i32, i32)]) -> Vertices {
        let narrow = |v: i32| i16::try_from(v).expect("vertices within REACH fit in 16 bits");
        Vertices { x: contour.iter().map(|p| narrow(p.0)).collect(), y: contour.iter().map(|p| narrow(p.1)).collect() }
    }

    fn new() -> Result<Self, &'static str> {
        let made = || -> Result<Self, String> {
            let mut surface = Surface::new(SCREEN.width as u32, SCREEN.height as u32, PixelFormatEnum::Index8)?;
            let greys: Vec<Color> = (0..=255).map(|i| Color::RGB(i, i, i)).collect();
            surface.set_palette(&Palette::with_colors(&greys)?)?;
            Ok(Self { canvas: surface.into_canvas()? })
        };
        made().map_err(|_| "SDL made no surface or renderer")
    }

    /// Fills each of `polygons` in white; an error if any call returned one.
    fn fill(&mut self, polygons: &[Vertices]) -> Result<(), &'static str> {
        let _sdl_gfx = lock();
        let mut result = Ok(());
        for polygon in polygons {
            let filled = self.canvas.filled_polygon(&polygon.x, &polygon.y, Color::RGB(255, 255, 255));
            result = result.and(filled);
        }
        result.map_err(|_| "filledPolygonRGBA returned an error")
    }

    fn emit_runs(&self, color: u8, sink: &mut dyn SpanSink) {
        let surface = self.canvas.surface();
        let stride = surface.pitch() as usize;
        surface.with_lock(|rows| emit_rows(rows, stride, SCREEN.width as usize, color, sink));
    }
}
