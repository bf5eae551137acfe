//! The host's target: a byte-per-pixel image in memory.

use alloc::vec;
use alloc::vec::Vec;

use crate::stores::{set_bytes, set_prefix};
use crate::target::{Size, SpanSink};

/// A byte-per-pixel image in memory: the host's (and the tests') target.
/// Spans outside it are clipped and counted in [`Framebuffer::stray_spans`]
/// instead of being written, so a faulty method cannot corrupt memory.
///
/// # Examples
///
/// ```
/// use raster::{Framebuffer, Size, SpanSink};
///
/// let mut image = Framebuffer::new(Size { width: 4, height: 2 });
/// image.span(1, 1, 3, 5);
/// assert_eq!(image.pixels(), &[0, 0, 0, 0, 0, 5, 5, 0]);
/// assert_eq!(image.get(2, 1), Some(5));
/// // Outside: clipped, counted, nothing written past the image.
/// image.span(0, -2, 9, 1);
/// assert_eq!((image.stray_spans(), image.get(3, 0)), (1, Some(1)));
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Framebuffer {
    size: Size,
    pixels: Vec<u8>,
    stray_spans: usize,
}

impl Framebuffer {
    /// A target of `size`, every pixel 0 (black), as after a mode set.
    pub fn new(size: Size) -> Self {
        let len = size.width.max(0) as usize * size.height.max(0) as usize;
        Self { size, pixels: vec![0; len], stray_spans: 0 }
    }

    /// Row-major pixels, `width` bytes a row.
    pub fn pixels(&self) -> &[u8] {
        &self.pixels
    }

    /// The pixel at (x, y), if inside.
    pub fn get(&self, x: i32, y: i32) -> Option<u8> {
        let inside = (0..self.size.width).contains(&x) && (0..self.size.height).contains(&y);
        inside.then(|| self.pixels[(y * self.size.width + x) as usize])
    }

    /// How many spans broke the sink contract (partly or wholly outside).
    pub fn stray_spans(&self) -> usize {
        self.stray_spans
    }

    /// Counts a span that broke the sink contract on its way here, for a
    /// sink standing in front of this one that clipped it itself.
    pub fn note_stray_span(&mut self) {
        self.stray_spans += 1;
    }
}

impl SpanSink for Framebuffer {
    fn size(&self) -> Size {
        self.size
    }

    /// A span inside the target is a few inline stores (see
    /// [`set_bytes`]); one outside it takes the cold path.
    #[inline(always)]
    fn span(&mut self, y: i32, x_start: i32, x_end: i32, color: u8) {
        if self.size.holds_span(y, x_start, x_end) {
            // All three are non-negative and inside the target.
            let row = y as usize * self.size.width as usize;
            set_bytes(&mut self.pixels[row + x_start as usize..row + x_end as usize], color);
        } else {
            self.stray_span(y, x_start, x_end, color);
        }
    }

    /// Where the build targets a CPU with AVX-512 (BW), a span of up to 64
    /// pixels with 64 bytes of the image from its start is one masked
    /// store ([`set_prefix`]), whatever its length; any other span is
    /// [`SpanSink::span`]'s.
    #[inline(always)]
    fn irregular_span(&mut self, y: i32, x_start: i32, x_end: i32, color: u8) {
        self.window_span::<{ cfg!(target_feature = "avx512bw") }>(y, x_start, x_end, color);
    }
}

impl Framebuffer {
    /// [`SpanSink::irregular_span`], storing spans of up to 64 pixels in a
    /// masked window where `WINDOW`, else by [`SpanSink::span`].
    #[inline(always)]
    fn window_span<const WINDOW: bool>(&mut self, y: i32, x_start: i32, x_end: i32, color: u8) {
        if WINDOW && self.size.holds_span(y, x_start, x_end) && x_end - x_start <= 64 {
            // All three are non-negative and inside the target; the window
            // may reach into the next rows, whose bytes it leaves as they
            // are, but not past the image.
            let start = y as usize * self.size.width as usize + x_start as usize;
            if let Some(window) = self.pixels[start..].first_chunk_mut::<64>() {
                set_prefix(window, (x_end - x_start) as usize, color);
                return;
            }
        }
        self.span(y, x_start, x_end, color);
    }
}

impl Framebuffer {
    /// Counts a span that broke the sink contract and draws its part inside.
    #[cold]
    #[inline(never)]
    fn stray_span(&mut self, y: i32, x_start: i32, x_end: i32, color: u8) {
        self.stray_spans += 1;
        let (x0, x1) = (x_start.max(0), x_end.min(self.size.width));
        if (0..self.size.height).contains(&y) && x0 < x1 {
            let row = y as usize * self.size.width as usize;
            self.pixels[row + x0 as usize..row + x1 as usize].fill(color);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stores::clear;

    #[test]
    fn clear_covers_every_pixel() {
        let mut fb = Framebuffer::new(Size { width: 3, height: 3 });
        clear(&mut fb, 9);
        assert!(fb.pixels().iter().all(|&p| p == 9));
    }

    #[test]
    fn spans_fill_their_half_open_range() {
        let mut fb = Framebuffer::new(Size { width: 4, height: 2 });
        fb.span(1, 1, 3, 7);
        assert_eq!(fb.pixels(), &[0, 0, 0, 0, 0, 7, 7, 0]);
        assert_eq!(fb.stray_spans(), 0);
    }

    /// With the window and without it, on every row end and near the
    /// image's end (where 64 bytes from the start do not fit): every
    /// span of up to 70 pixels sets exactly its pixels, and strays are
    /// clipped and counted as `span` does.
    #[test]
    fn irregular_spans_set_exactly_their_pixels() {
        type Store = fn(&mut Framebuffer, i32, i32, i32, u8);
        let ways: [(&str, Store); 2] =
            [("window", Framebuffer::window_span::<true>), ("span", Framebuffer::window_span::<false>)];
        let size = Size { width: 100, height: 3 };
        for (way, store) in ways {
            for y in 0..3 {
                for x_start in 0..100 {
                    for x_end in x_start..=(x_start + 70).min(100) {
                        let mut image = Framebuffer::new(size);
                        image.pixels.fill(3);
                        store(&mut image, y, x_start, x_end, 9);
                        let mut expected = alloc::vec![3u8; 300];
                        let row = y as usize * 100;
                        expected[row + x_start as usize..row + x_end as usize].fill(9);
                        assert_eq!(image.pixels, expected, "{way}: row {y}, {x_start}..{x_end}");
                        assert_eq!(image.stray_spans, usize::from(x_start == x_end), "{way}");
                    }
                }
            }
            let mut image = Framebuffer::new(size);
            store(&mut image, 2, 90, 101, 1);
            store(&mut image, 3, 0, 1, 1);
            assert_eq!((image.stray_spans, image.get(99, 2), image.get(89, 2)), (2, Some(1), Some(0)), "{way}");
        }
    }

    #[test]
    fn stray_spans_are_clipped_and_counted() {
        let mut fb = Framebuffer::new(Size { width: 4, height: 2 });
        fb.span(0, -2, 9, 1);
        fb.span(5, 0, 1, 1);
        fb.span(1, 3, 3, 1);
        assert_eq!(fb.pixels(), &[1, 1, 1, 1, 0, 0, 0, 0]);
        assert_eq!(fb.stray_spans(), 3);
    }
}
