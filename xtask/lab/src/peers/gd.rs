//! GD's `gdImageFilledPolygon`, the image library of PHP and many web
//! back ends, through the system `libgd` (Debian's `libgd-dev`), into a
//! palette image of 320x200 (`gdImageCreate`).
//!
//! Its functions are declared here by hand (no maintained crate binds
//! GD); a palette image's rows (`im->pixels[y]`, a field of its struct)
//! are read through the C shim (`shim.c`), which includes GD's header
//! rather than a copy of its layout here. `gdPoint` is two `int`s, as
//! `gd.h` declares it.
//!
//! For each row (clipped to the image) it computes every edge's crossing
//! as `(int) ((float) ((y - y1) * (x2 - x1)) / (float) (y2 - y1) + 0.5 +
//! x1)`, sorts them and draws each pair inclusively. `(y - y1) * (x2 -
//! x1)` is an `int` product: within 23,170 px of the origin (46,340 px
//! apart at most, 46,340² < 2^31) it cannot overflow, so vertices beyond
//! are declined. Every image keeps its own crossings, so images on
//! different threads do not meet.

use std::ffi::{c_int, c_uchar};
use std::ptr::NonNull;
use std::slice;

use raster::{Polygon, SpanSink, SCREEN};

use super::integer::{whole_pixel_contour, Contour, IntegerPeer, IntegerTarget, Reach};
use super::peer::{Clock, PeerInfo};
use super::rows::emit_row;
use crate::convention::Own;

/// What `gdImageFilledPolygon` takes: within 23,170 px its products fit.
pub const REACH: Reach =
    Reach { pixels: 23_170, beyond: "a vertex past 23,170 px, where its products of coordinates overflow int" };

/// GD's `gdImageFilledPolygon` into a palette image.
pub static GD: IntegerPeer<GdCanvas> = IntegerPeer::new(PeerInfo {
    name: "gd",
    source: "system GD (libgd): gdImageFilledPolygon into gdImageCreate(320, 200), a palette image",
    summary: "whole-pixel vertices (within 23,170 px); each row's crossings in float, rounded, sorted; whole-pixel \
         points, spans inclusive; even-odd, one contour",
    // The closed polygon at whole-pixel points, no outline.
    own: Own::Closed { outline: false },
    clock: Clock {
        before: "the contour rounded to whole pixels, a `gdPoint` array",
        setup: "none",
        fill: "`gdImageFilledPolygon` (each span pixel by pixel)",
        surface: "`gdImageCreate(320, 200)`, a palette image",
        pixel_format: "8-bit palette index",
        anti_aliasing: "none; whole-pixel points, spans inclusive",
    },
    variant_of: None,
});

/// GD's point: `typedef struct { int x, y; } gdPoint;`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct GdPoint {
    x: c_int,
    y: c_int,
}

/// A GD image, only ever behind a pointer.
#[repr(C)]
struct Image {
    _opaque: [u8; 0],
}

extern "C" {
    fn gdImageCreate(sx: c_int, sy: c_int) -> *mut Image;
    fn gdImageDestroy(im: *mut Image);
    fn gdImageColorAllocate(im: *mut Image, r: c_int, g: c_int, b: c_int) -> c_int;
    fn gdImageFilledPolygon(im: *mut Image, p: *const GdPoint, n: c_int, c: c_int);
    // shim.c
    fn lab_gd_row(im: *mut Image, y: c_int) -> *mut c_uchar;
}

/// A 320x200 GD palette image: black (index 0, the background) and white.
pub struct GdCanvas {
    image: NonNull<Image>,
    white: c_int,
}

impl IntegerTarget for GdCanvas {
    type Input = Vec<GdPoint>;

    fn contour(polygon: &Polygon) -> Contour {
        whole_pixel_contour(polygon, REACH)
    }

    fn input(contour: &[(i32, i32)]) -> Vec<GdPoint> {
        contour.iter().map(|&(x, y)| GdPoint { x, y }).collect()
    }

    fn new() -> Result<Self, &'static str> {
        // SAFETY: a valid size; GD allocates the image or returns null.
        let image = NonNull::new(unsafe { gdImageCreate(SCREEN.width, SCREEN.height) })
            .ok_or("gdImageCreate(320, 200) failed")?;
        // SAFETY: `image` is live. The first colour allocated is the
        // background every pixel starts with, as GD's users know.
        let white = unsafe {
            gdImageColorAllocate(image.as_ptr(), 0, 0, 0);
            gdImageColorAllocate(image.as_ptr(), 255, 255, 255)
        };
        Ok(Self { image, white })
    }

    /// Fills each of `polygons` (whole pixels, within [`REACH`]) with
    /// `gdImageFilledPolygon`, which returns nothing.
    fn fill(&mut self, polygons: &[Vec<GdPoint>]) -> Result<(), &'static str> {
        for points in polygons {
            // SAFETY: the image is live and ours alone; `points` holds
            // `len` points, which is all GD reads; within REACH its
            // arithmetic stays in int, and it clips to the image.
            unsafe { gdImageFilledPolygon(self.image.as_ptr(), points.as_ptr(), points.len() as c_int, self.white) };
        }
        Ok(())
    }

    fn emit_runs(&self, color: u8, sink: &mut dyn SpanSink) {
        for y in 0..SCREEN.height {
            // SAFETY: a 320x200 palette image has 200 rows of 320 bytes,
            // and `y` is one of them; nothing writes while the slice lives.
            let row = unsafe { slice::from_raw_parts(lab_gd_row(self.image.as_ptr(), y), SCREEN.width as usize) };
            emit_row(y, row, color, sink);
        }
    }
}

impl Drop for GdCanvas {
    fn drop(&mut self) {
        // SAFETY: the image is live and destroyed once.
        unsafe { gdImageDestroy(self.image.as_ptr()) };
    }
}
