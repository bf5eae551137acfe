//! The canvas: the frame as the methods see it, the 64,000 bytes of the
//! 320x200 frame, one byte a pixel, row after row, as a span sink. Every access is
//! volatile: the compiler sees stores that nobody reads and would be free
//! to drop or merge them if they were plain writes. A span is written as
//! aligned 8-byte stores, with 4-, 2- and 1-byte ones only at its ends: on
//! a real card's bus that is an eighth of the byte writes. Spans that
//! break the sink contract are not drawn at all, only counted: nothing is
//! ever written outside the 64,000 bytes.

use core::mem::{align_of, size_of};
use core::ops::Range;
use core::ptr;

use protocol::FRAMEBUFFER_LEN;
use raster::{Size, SpanSink, SCREEN};
use volatile::VolatilePtr;

// The sink's bounds check against `SCREEN` is what keeps spans inside the
// 64,000 bytes.
const _: () = assert!((SCREEN.width * SCREEN.height) as usize == FRAMEBUFFER_LEN);

/// The frame's memory (video memory at 0xA0000 on the VGA path, the
/// kernel's own otherwise) and the spans dropped on their way to it.
pub struct Canvas {
    pixels: VolatilePtr<'static, [u8]>,
    stray_spans: usize,
}

impl Canvas {
    /// The frame in `pixels`, [`FRAMEBUFFER_LEN`] bytes.
    pub fn new(pixels: VolatilePtr<'static, [u8]>) -> Self {
        Self { pixels, stray_spans: 0 }
    }

    /// The frame's bytes, for what shows them (`vga`, `presenter`).
    pub fn pixels(&self) -> VolatilePtr<'static, [u8]> {
        self.pixels
    }

    /// Spans that broke the sink contract since the frame was made (a
    /// method bug; they were dropped), wrapping: a count to take
    /// differences of.
    pub fn stray_spans(&self) -> usize {
        self.stray_spans
    }

    /// Copies `frame` in with one volatile copy (a `memcpy` that may move
    /// many bytes per instruction); bytes past 64,000 are ignored, a
    /// shorter frame replaces only the top.
    pub fn copy_from(&mut self, frame: &[u8]) {
        let len = frame.len().min(FRAMEBUFFER_LEN);
        self.pixels.index(..len).copy_from_slice(&frame[..len]);
    }

    /// Reads the 64,000 bytes back into `out`.
    pub fn copy_into(&self, out: &mut [u8]) {
        self.pixels.copy_into_slice(out);
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
        // SAFETY: `bytes` is `len` bytes of the frame `Screen::open` took,
        // video memory or the kernel's own (`index` checked the range),
        // valid for volatile writes and aliased by no reference. The three runs cover bytes `0..head`,
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

impl SpanSink for Canvas {
    fn size(&self) -> Size {
        SCREEN
    }

    #[inline]
    fn span(&mut self, y: i32, x_start: i32, x_end: i32, color: u8) {
        if !SCREEN.holds_span(y, x_start, x_end) {
            self.stray_spans = self.stray_spans.wrapping_add(1);
            return;
        }
        // All three are non-negative and below 64,000 after the check above.
        let row = (y * SCREEN.width) as usize;
        self.fill(row + x_start as usize..row + x_end as usize, color);
    }
}
