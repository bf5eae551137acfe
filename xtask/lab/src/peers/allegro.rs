//! Allegro 4.4's `polygon()`, the DOS-era game library's filled polygon,
//! through the system `liballeg` (Debian's `liballegro4-dev`), into an
//! 8-bit memory bitmap of 320x200 (`create_bitmap_ex(8, 320, 200)`),
//! with no system driver (`install_allegro(SYSTEM_NONE, ...)`).
//!
//! Its functions are declared here by hand: no crate binds Allegro 4. Its
//! start-up call (a macro for the system id, C's `errno` and `atexit`)
//! and a bitmap's rows (`bmp->line[y]`, a field of its `BITMAP` struct)
//! go through the C shim (`shim.c`), which includes Allegro's own header
//! rather than a copy of its layout here.
//!
//! `polygon()` keeps its edges in 14.18 fixed point in `int`: a vertex's
//! x shifted left 18 bits, a horizontal edge's width 19. Past 2,047 px on
//! either axis a horizontal edge's width may overflow `int`, so vertices
//! beyond are declined (see `integer.rs`). It walks a sorted active-edge
//! list row by row and draws each edge's own pixels on the row too, so
//! its fill includes the outline. It keeps its edges in one scratch
//! buffer for the whole library, so calls are made one at a time.

use std::ffi::{c_int, c_uchar};
use std::ptr::NonNull;
use std::slice;
use std::sync::{Mutex, MutexGuard, OnceLock};

use raster::{Polygon, SpanSink, SCREEN};

use super::integer::{whole_pixel_contour, Contour, IntegerPeer, IntegerTarget, Reach};
use super::peer::{Clock, PeerInfo};
use super::rows::emit_row;
use crate::convention::Own;

/// What `polygon()` takes: within 2,047 px its fixed point cannot overflow.
pub const REACH: Reach =
    Reach { pixels: 2047, beyond: "a vertex past 2,047 px, where its 14.18 fixed point overflows int" };

/// Allegro's `polygon()` into an 8-bit memory bitmap.
pub static ALLEGRO: IntegerPeer<AllegroCanvas> = IntegerPeer::new(PeerInfo {
    name: "allegro",
    source: "system Allegro 4.4 (liballeg): polygon() into create_bitmap_ex(8, 320, 200)",
    summary: "whole-pixel vertices (within 2,047 px); sorted active edges in 14.18 fixed point; whole-pixel points, \
         spans inclusive, each edge's pixels drawn too; even-odd, one contour",
    // The closed polygon at whole-pixel points, its outline drawn too.
    own: Own::Closed { outline: true },
    clock: Clock {
        before: "the contour rounded to whole pixels, an `int` array",
        setup: "none",
        fill: "`polygon()`",
        surface: "`create_bitmap_ex(8, 320, 200)`, a memory bitmap",
        pixel_format: "8-bit index",
        anti_aliasing: "none; whole-pixel points, spans inclusive, each edge's own pixels too",
    },
    variant_of: None,
});

/// The colour index it fills with (0 is the cleared bitmap).
const INK: c_int = 255;

/// An Allegro `BITMAP`, only ever behind a pointer.
#[repr(C)]
struct Bitmap {
    _opaque: [u8; 0],
}

extern "C" {
    fn create_bitmap_ex(color_depth: c_int, width: c_int, height: c_int) -> *mut Bitmap;
    fn destroy_bitmap(bitmap: *mut Bitmap);
    fn clear_bitmap(bitmap: *mut Bitmap);
    fn polygon(bitmap: *mut Bitmap, vertices: c_int, points: *const c_int, color: c_int);
    // shim.c
    fn lab_allegro_install() -> c_int;
    fn lab_allegro_row(bitmap: *mut Bitmap, y: c_int) -> *mut c_uchar;
}

/// Allegro's global state (its start-up and the scratch buffer
/// `polygon()` keeps its edges in) is used by one thread at a time.
fn lock() -> MutexGuard<'static, ()> {
    static ALLEGRO: Mutex<()> = Mutex::new(());
    ALLEGRO.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// Starts Allegro once per process, with no system driver.
fn install() -> Result<(), &'static str> {
    static INSTALLED: OnceLock<bool> = OnceLock::new();
    // SAFETY: called once, under the lock; SYSTEM_NONE opens no device.
    let installed = *INSTALLED.get_or_init(|| unsafe { lab_allegro_install() } == 0);
    installed.then_some(()).ok_or("install_allegro(SYSTEM_NONE) failed")
}

/// A 320x200 8-bit Allegro memory bitmap, cleared to 0.
pub struct AllegroCanvas {
    bitmap: NonNull<Bitmap>,
}

impl IntegerTarget for AllegroCanvas {
    /// `x0, y0, x1, y1, ...` in whole pixels.
    type Input = Vec<c_int>;

    fn contour(polygon: &Polygon) -> Contour {
        whole_pixel_contour(polygon, REACH)
    }

    fn input(contour: &[(i32, i32)]) -> Vec<c_int> {
        contour.iter().flat_map(|&(x, y)| [x, y]).collect()
    }

    fn new() -> Result<Self, &'static str> {
        let _allegro = lock();
        install()?;
        // SAFETY: Allegro is installed; the arguments are a valid depth and size.
        let bitmap = NonNull::new(unsafe { create_bitmap_ex(8, SCREEN.width, SCREEN.height) })
            .ok_or("create_bitmap_ex(8, 320, 200) failed")?;
        // SAFETY: `bitmap` is the live bitmap just made.
        unsafe { clear_bitmap(bitmap.as_ptr()) };
        Ok(Self { bitmap })
    }

    /// Fills each of `polygons` (within [`REACH`], at least one vertex
    /// each) with `polygon()`, which returns nothing.
    fn fill(&mut self, polygons: &[Vec<c_int>]) -> Result<(), &'static str> {
        let _allegro = lock();
        for points in polygons {
            debug_assert!(points.len() >= 2 && points.len() % 2 == 0);
            // SAFETY: the bitmap is live; `points` holds `len / 2` (x, y)
            // pairs, at least one, which is all polygon() reads; within
            // REACH its arithmetic stays in int, and it clips every row to
            // the bitmap.
            unsafe { polygon(self.bitmap.as_ptr(), (points.len() / 2) as c_int, points.as_ptr(), INK) };
        }
        Ok(())
    }

    fn emit_runs(&self, color: u8, sink: &mut dyn SpanSink) {
        let _allegro = lock();
        for y in 0..SCREEN.height {
            // SAFETY: a memory bitmap of 320x200 at 8 bits has 200 rows of
            // at least 320 bytes, and `y` is one of them; nothing writes to
            // it while the slice lives (the lock is held).
            let row = unsafe { slice::from_raw_parts(lab_allegro_row(self.bitmap.as_ptr(), y), SCREEN.width as usize) };
            emit_row(y, row, color, sink);
        }
    }
}

impl Drop for AllegroCanvas {
    fn drop(&mut self) {
        let _allegro = lock();
        // SAFETY: the bitmap is live and dropped once.
        unsafe { destroy_bitmap(self.bitmap.as_ptr()) };
    }
}
