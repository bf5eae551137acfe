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
    pub fn holds_span(self, y: i32, x_start: i32, x_end: i32) -> bool {
        (0..self.height).contains(&y) && 0 <= x_start && x_start < x_end && x_end <= self.width
    }
}

/// Mode 13h: 320x200.
pub const SCREEN: Size = Size { width: 320, height: 200 };

/// Where spans go. A method must only emit spans inside the target:
/// `0 <= y < height` and `0 <= x_start < x_end <= width` (`x_end` exclusive).
pub trait SpanSink {
    /// The target's size; methods clip to it.
    fn size(&self) -> Size;
    /// Sets pixels `x_start..x_end` of row `y` to `color`.
    fn span(&mut self, y: i32, x_start: i32, x_end: i32, color: u8);
}

/// Fills the whole target with one colour through its span interface.
pub fn clear(sink: &mut dyn SpanSink, color: u8) {
    let size = sink.size();
    for y in 0..size.height {
        sink.span(y, 0, size.width, color);
    }
}

/// A byte-per-pixel image in memory: the host's (and the tests') target.
/// Spans outside it are clipped and counted in [`Framebuffer::stray_spans`]
/// instead of being written, so a faulty method cannot corrupt memory.
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

    fn span(&mut self, y: i32, x_start: i32, x_end: i32, color: u8) {
        if !self.size.holds_span(y, x_start, x_end) {
            self.stray_spans += 1;
        }
        if !(0..self.size.height).contains(&y) {
            return;
        }
        let (x0, x1) = (x_start.max(0), x_end.min(self.size.width));
        if x0 < x1 {
            let row = (y * self.size.width) as usize;
            self.pixels[row + x0 as usize..row + x1 as usize].fill(color);
        }
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

    #[test]
    fn clear_covers_every_pixel() {
        let mut fb = Framebuffer::new(Size { width: 3, height: 3 });
        clear(&mut fb, 9);
        assert!(fb.pixels().iter().all(|&p| p == 9));
    }
}
