//! The output seam: methods emit spans, sinks store them. A target's
//! [`Size`], mode 13h's [`SCREEN`], and the [`SpanSink`] every method
//! fills into.

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
    /// [`SpanSink::span`], for a span from a stage whose spans' lengths
    /// follow no pattern from one to the next (the edge flags' runs under
    /// the even-odd rule, on self-intersecting and many-cornered
    /// polygons): a sink may store it without branching on its length,
    /// where such a branch would often be mispredicted. The contract is
    /// `span`'s, and so, unless a sink says otherwise, is the store.
    #[inline(always)]
    fn irregular_span(&mut self, y: i32, x_start: i32, x_end: i32, color: u8) {
        self.span(y, x_start, x_end, color);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_contract_check_takes_every_bound() {
        let size = Size { width: 4, height: 2 };
        assert!(size.holds_span(1, 0, 4));
        for (y, x0, x1) in [(-1, 0, 1), (2, 0, 1), (0, -1, 1), (0, 2, 2), (0, 3, 2), (0, 0, 5), (0, -3, -1)] {
            assert!(!size.holds_span(y, x0, x1), "{y} {x0} {x1}");
        }
        assert!(!Size { width: -1, height: 2 }.holds_span(0, 0, 1));
    }
}
