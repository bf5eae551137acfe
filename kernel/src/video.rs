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
use core::ptr::{self, NonNull};

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

    /// Sets the bytes `range` of video memory to `color`: the bytes up to
    /// the first 8-byte boundary one at a time, then whole aligned 8-byte
    /// stores, then the last few bytes one at a time, so the card's bus
    /// sees an eighth of the writes a byte loop makes. Panics if `range`
    /// reaches past the 64,000 bytes (callers check the sink contract).
    #[inline]
    fn fill(&mut self, range: Range<usize>, color: u8) {
        let bytes = self.pixels.index(range);
        let (start, len) = (bytes.as_raw_ptr().cast::<u8>().as_ptr(), bytes.len());
        let head = start.align_offset(align_of::<u64>()).min(len);
        let words = (len - head) / size_of::<u64>();
        let tail = len - head - words * size_of::<u64>();
        let pattern = u64::from(color) * 0x0101_0101_0101_0101;
        // SAFETY: `bytes` is `len` bytes of the video memory `Screen::new`
        // took (`index` checked the range), valid for volatile writes and
        // aliased by no reference. The three runs cover bytes `0..head`,
        // `head..head + 8 * words` and the `tail` after them, `len` in all,
        // each write inside `bytes`; the words start at the first 8-byte
        // boundary (`align_offset`), so each `u64` write is aligned; any
        // bytes are a valid `u8` or `u64`.
        unsafe {
            for i in 0..head {
                ptr::write_volatile(start.add(i), color);
            }
            let body = start.add(head).cast::<u64>();
            for i in 0..words {
                ptr::write_volatile(body.add(i), pattern);
            }
            let end = start.add(head + words * size_of::<u64>());
            for i in 0..tail {
                ptr::write_volatile(end.add(i), color);
            }
        }
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
