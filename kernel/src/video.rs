//! The mode-13h framebuffer: 64,000 bytes at physical 0xA0000, one byte a
//! pixel, row after row, and the palette its bytes are shown in.
//!
//! Every access is volatile: the compiler sees stores that nobody reads and
//! would be free to drop or merge them if they were plain writes. A span is
//! written as aligned 8-byte stores, with 4-, 2- and 1-byte ones only at its
//! ends: on a real card's bus that is an eighth of the byte writes.

use alloc::vec::Vec;
use core::fmt;
use core::mem::{align_of, size_of};
use core::ops::Range;
use core::ptr::NonNull;

use bootloader_api::BootInfo;
use protocol::{DUMP_LEN, FRAMEBUFFER_LEN};
use raster::{sink, Method, Size, SpanSink, SCREEN};
use scenes::palette::VGA_DEFAULT;
use scenes::{DrawReport, Scene};
use volatile::VolatilePtr;

use crate::vga::{self, Palette};

/// Physical address of the mode-13h window.
const FRAMEBUFFER_PHYSICAL: u64 = 0xA0000;

// The sink's bounds check against `SCREEN` is what keeps spans inside the
// 64,000 bytes.
const _: () = assert!((SCREEN.width * SCREEN.height) as usize == FRAMEBUFFER_LEN);

/// The screen as a span sink. Spans that break the sink contract are not
/// drawn at all, only counted: nothing is ever written outside the 64,000
/// bytes.
pub struct Screen {
    pixels: VolatilePtr<'static, [u8]>,
    stray_spans: usize,
    /// The palette in the DAC, loaded by [`Screen::use_palette`].
    palette: &'static Palette,
}

impl Screen {
    /// The framebuffer through the bootloader's map of all physical memory
    /// (`mappings.physical_memory` in main.rs's config), where 0xA0000
    /// certainly is. `None` if the map is missing. Loads the VGA default
    /// palette: the BIOS's text mode leaves the DAC set up for text.
    pub fn new(boot_info: &BootInfo) -> Option<Self> {
        let offset = boot_info.physical_memory_offset.into_option()?;
        let start = offset.checked_add(FRAMEBUFFER_PHYSICAL)?;
        let start = NonNull::new(core::ptr::with_exposed_provenance_mut::<u8>(usize::try_from(start).ok()?))?;
        let pixels = NonNull::slice_from_raw_parts(start, FRAMEBUFFER_LEN);
        // SAFETY: the bootloader maps all physical memory at `offset`, so
        // these 64,000 bytes are the VGA window 0xA0000..0xAFA00: device
        // memory, valid for volatile reads and writes for the whole run and
        // never a Rust object, so nothing else holds a reference into it.
        let pixels = unsafe { VolatilePtr::new(pixels) };
        vga::load_dac(&VGA_DEFAULT);
        Some(Self { pixels, stray_spans: 0, palette: &VGA_DEFAULT })
    }

    /// Loads `palette` into the DAC, unless it is already there.
    pub fn use_palette(&mut self, palette: &'static Palette) {
        if self.palette != palette {
            vga::load_dac(palette);
            self.palette = palette;
        }
    }

    /// Spans that broke the sink contract since the last [`Screen::draw`]
    /// (a method bug; they were dropped).
    pub fn stray_spans(&self) -> usize {
        self.stray_spans
    }

    /// The palette in the DAC: what `vga::verify` must read back.
    pub fn palette(&self) -> &'static Palette {
        self.palette
    }

    /// Fills the screen with `color` of the VGA default palette.
    pub fn clear(&mut self, color: u8) {
        self.use_palette(&VGA_DEFAULT);
        sink::clear(self, color);
    }

    /// Draws `scene` with `method` in the VGA default palette and says how
    /// it went. The screen's type is known to the fill, so each span is
    /// stored by [`Screen::fill`] inline, with no call.
    pub fn draw(&mut self, scene: &Scene, method: &dyn Method) -> Drawn {
        self.use_palette(&VGA_DEFAULT);
        self.stray_spans = 0;
        let report = scene.draw(method, self);
        Drawn { report, stray_spans: self.stray_spans }
    }

    /// Puts a whole frame on the screen with one volatile copy (a `memcpy`
    /// that may move many bytes per instruction): `frame` is 320x200 bytes,
    /// row after row; bytes past 64,000 are ignored, a shorter frame
    /// replaces only the top of the screen.
    pub fn blit(&mut self, frame: &[u8]) {
        let len = frame.len().min(FRAMEBUFFER_LEN);
        self.pixels.index(..len).copy_from_slice(&frame[..len]);
    }

    /// A `DUMP` payload: the 64,000 bytes read back from video memory, then
    /// the 768 DAC bytes read back from the card.
    pub fn dump(&self) -> Vec<u8> {
        let mut dump = alloc::vec![0; DUMP_LEN];
        let (framebuffer, dac) = dump.split_at_mut(FRAMEBUFFER_LEN);
        self.pixels.copy_into_slice(framebuffer);
        dac.copy_from_slice(&vga::read_dac());
        dump
    }

    /// Sets the bytes `range` of video memory to `color`: whole aligned
    /// 8-byte stores where the span allows, and 4-, 2- or 1-byte stores,
    /// each aligned to its width, before and after them. Panics if `range`
    /// reaches past the 64,000 bytes (callers check the sink contract).
    #[inline]
    fn fill(&mut self, range: Range<usize>, color: u8) {
        let base = self.pixels.as_raw_ptr().cast::<u8>().as_ptr().addr();
        let pattern = u64::from(color) * 0x0101_0101_0101_0101;
        let mut at = range.start;
        while at < range.end {
            let (address, left) = (base + at, range.end - at);
            at += if address.is_multiple_of(8) && left >= 8 {
                self.store(at, pattern)
            } else if address.is_multiple_of(4) && left >= 4 {
                self.store(at, pattern as u32)
            } else if address.is_multiple_of(2) && left >= 2 {
                self.store(at, pattern as u16)
            } else {
                self.store(at, color)
            };
        }
    }

    /// One volatile store of `value` at byte `at` of video memory; returns
    /// its width. Panics unless the store lies within the 64,000 bytes and
    /// is aligned to its width.
    #[inline(always)]
    fn store<T: Copy>(&mut self, at: usize, value: T) -> usize {
        let bytes = self.pixels.index(at..at + size_of::<T>());
        assert!(bytes.as_raw_ptr().cast::<u8>().as_ptr().addr().is_multiple_of(align_of::<T>()));
        // SAFETY: `bytes` is `size_of::<T>()` bytes of the video memory
        // `Screen::new` took (index checked the range), and its address is
        // a multiple of `T`'s alignment (asserted), so it is valid for one
        // volatile write of a `T`; `T` is an integer, any bytes are valid.
        unsafe { bytes.map(|b| b.cast::<T>()) }.write(value);
        size_of::<T>()
    }
}

impl SpanSink for Screen {
    fn size(&self) -> Size {
        SCREEN
    }

    #[inline]
    fn span(&mut self, y: i32, x_start: i32, x_end: i32, color: u8) {
        if !SCREEN.holds_span(y, x_start, x_end) {
            self.stray_spans += 1;
            return;
        }
        // All three are non-negative and below 64,000 after the check above.
        let row = (y * SCREEN.width) as usize;
        self.fill(row + x_start as usize..row + x_end as usize, color);
    }
}

/// What [`Screen::draw`] did.
pub struct Drawn {
    pub report: DrawReport,
    /// Spans a method emitted outside the screen (a method bug), dropped.
    pub stray_spans: usize,
}

impl fmt::Display for Drawn {
    /// The `OK` text of `DRAW` and `POLY`: `polygons=N refused=M`, then
    /// ` strays=K` only if a method broke the sink contract.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "polygons={} refused={}", self.report.polygons, self.report.refused)?;
        if self.stray_spans > 0 {
            write!(f, " strays={}", self.stray_spans)?;
        }
        Ok(())
    }
}
