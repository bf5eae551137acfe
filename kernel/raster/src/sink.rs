//! The output seam: methods emit spans, sinks store them.

use alloc::vec;
use alloc::vec::Vec;

/// Width and height of a target in pixels.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Size {
    pub width: i32,
    pub height: i32,
}

impl Size {
    /// Whether the span `x_start..x_end` of row `y` keeps the sink
    /// contract: inside the target and not empty.
    #[inline(always)]
    pub fn holds_span(self, y: i32, x_start: i32, x_end: i32) -> bool {
        // As unsigned, a negative `y` is larger than any height.
        (y as u32) < (self.height as u32) && 0 <= x_start && x_start < x_end && x_end <= self.width
    }
}

/// Mode 13h: 320x200.
pub const SCREEN: Size = Size { width: 320, height: 200 };

/// Where spans go. A method must only emit spans inside the target:
/// `0 <= y < height` and `0 <= x_start < x_end <= width` (`x_end` exclusive).
///
/// # Examples
///
/// A sink of one's own: here one that only counts the pixels of each row,
/// for a polygon's area without a picture.
///
/// ```
/// use raster::{fill_auto, Polygon, Size, SpanSink};
///
/// struct RowLengths(Vec<i32>);
///
/// impl SpanSink for RowLengths {
///     fn size(&self) -> Size {
///         Size { width: 100, height: self.0.len() as i32 }
///     }
///     fn span(&mut self, y: i32, x_start: i32, x_end: i32, _color: u8) {
///         self.0[y as usize] += x_end - x_start;
///     }
/// }
///
/// let diamond = Polygon::from_pixels(&[(50, 0), (60, 10), (50, 20), (40, 10)], (0, 0), 1);
/// let mut lengths = RowLengths(vec![0; 20]);
/// fill_auto(&diamond, &mut lengths).unwrap();
/// assert_eq!(lengths.0[0], 1);
/// assert_eq!(lengths.0[9], 19);
/// assert_eq!(lengths.0.iter().sum::<i32>(), 200);
/// ```
pub trait SpanSink {
    /// The target's size; methods clip to it.
    fn size(&self) -> Size;
    /// Sets pixels `x_start..x_end` of row `y` to `color`.
    fn span(&mut self, y: i32, x_start: i32, x_end: i32, color: u8);
}

/// Fills the whole target with one colour through its span interface.
pub fn clear<S: SpanSink + ?Sized>(sink: &mut S, color: u8) {
    let size = sink.size();
    for y in 0..size.height {
        sink.span(y, 0, size.width, color);
    }
}

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

/// Sets every byte of `bytes` to `color`, as a span store: a span of up
/// to 64 bytes is two stores of its width class (1, 4, 8, 16 or 32 bytes;
/// the wide ones may be split into 16-byte stores on the baseline target),
/// overlapping in the middle, with no loop and no call. A longer one is,
/// where the build targets a CPU with AVX2 (`-C target-cpu=native` on a
/// recent x86-64, as `cargo xtask lab` builds), a loop of 64-byte blocks
/// and one last block ending where the span does, all inline; elsewhere
/// one `memset`, whose library version picks the widest stores the
/// machine has. A `memset` call costs more than the whole store on the
/// short spans that most polygons are made of, and more than inline
/// 32-byte stores on rows a few hundred bytes long (`docs/lab.md`); with
/// 16-byte stores only, the call is the cheaper.
#[inline(always)]
pub fn set_bytes(bytes: &mut [u8], color: u8) {
    let n = bytes.len();
    if n <= 16 {
        if n >= 8 {
            bytes[..8].copy_from_slice(&[color; 8]);
            bytes[n - 8..].copy_from_slice(&[color; 8]);
        } else if n >= 4 {
            bytes[..4].copy_from_slice(&[color; 4]);
            bytes[n - 4..].copy_from_slice(&[color; 4]);
        } else if n > 0 {
            // Bytes 0, n / 2 and n - 1 cover one to three bytes.
            bytes[0] = color;
            bytes[n / 2] = color;
            bytes[n - 1] = color;
        }
    } else if n <= 32 {
        bytes[..16].copy_from_slice(&[color; 16]);
        bytes[n - 16..].copy_from_slice(&[color; 16]);
    } else if n <= 64 {
        bytes[..32].copy_from_slice(&[color; 32]);
        bytes[n - 32..].copy_from_slice(&[color; 32]);
    } else if cfg!(target_feature = "avx2") {
        for block in bytes.as_chunks_mut::<64>().0 {
            *block = [color; 64];
        }
        bytes[n - 64..].copy_from_slice(&[color; 64]);
    } else {
        bytes.fill(color);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spans_fill_their_half_open_range() {
        let mut fb = Framebuffer::new(Size { width: 4, height: 2 });
        fb.span(1, 1, 3, 7);
        assert_eq!(fb.pixels(), &[0, 0, 0, 0, 0, 7, 7, 0]);
        assert_eq!(fb.stray_spans(), 0);
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

    /// Every length up to 160 at every offset below 24, against
    /// a plain slice fill: the overlapping stores set exactly the span.
    #[test]
    fn set_bytes_sets_exactly_the_span() {
        for start in 0..24 {
            for len in 0..=160 {
                let mut row = [0u8; 192];
                set_bytes(&mut row[start..start + len], 9);
                let mut expected = [0u8; 192];
                expected[start..start + len].fill(9);
                assert_eq!(row, expected, "start {start}, length {len}");
            }
        }
    }

    #[test]
    fn the_contract_check_takes_every_bound() {
        let size = Size { width: 4, height: 2 };
        assert!(size.holds_span(1, 0, 4));
        for (y, x0, x1) in [(-1, 0, 1), (2, 0, 1), (0, -1, 1), (0, 2, 2), (0, 3, 2), (0, 0, 5), (0, -3, -1)] {
            assert!(!size.holds_span(y, x0, x1), "{y} {x0} {x1}");
        }
        assert!(!Size { width: -1, height: 2 }.holds_span(0, 0, 1));
    }

    #[test]
    fn clear_covers_every_pixel() {
        let mut fb = Framebuffer::new(Size { width: 3, height: 3 });
        clear(&mut fb, 9);
        assert!(fb.pixels().iter().all(|&p| p == 9));
    }
}
