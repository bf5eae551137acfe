//! A sink that counts instead of drawing, for the tests and the lab: how
//! often each pixel was drawn, which spans broke the [`SpanSink`] contract,
//! and how the drawn set compares with a target set. The checking mock
//! display of embedded-graphics, as a report rather than a panic.

use alloc::string::String;
use alloc::vec;
use alloc::vec::Vec;

use crate::target::{Size, SpanSink};

/// Counts draws per pixel. Spans outside the target are counted in
/// [`CoverageReport::out_of_bounds`] and their inside part is still counted,
/// so one faulty span does not hide the rest of a picture.
///
/// # Examples
///
/// Two triangles sharing a diagonal tile their square exactly once:
///
/// ```
/// use raster::{fill_auto, CoverageSink, Polygon, Size};
///
/// let mut drawn = CoverageSink::new(Size { width: 4, height: 4 });
/// for half in [[(0, 0), (4, 0), (4, 4)], [(0, 0), (4, 4), (0, 4)]] {
///     fill_auto(&Polygon::from_pixels(&half, (0, 0), 1), &mut drawn).unwrap();
/// }
/// assert_eq!(drawn.ascii(), "####\n####\n####\n####\n");
/// assert_eq!(drawn.report(&drawn).overdrawn, 0);
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CoverageSink {
    size: Size,
    counts: Vec<u32>,
    /// Where pixels were drawn: every count outside `drawn_from..drawn_to`
    /// (indices into `counts`) is 0, so comparisons skip it.
    drawn_from: usize,
    drawn_to: usize,
    out_of_bounds: usize,
}

/// What a [`CoverageSink`] saw, against a target set of pixels. All zero
/// (the [`Default`]) means the target was drawn exactly once and nothing
/// else was drawn.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CoverageReport {
    /// Pixels drawn more than once.
    pub overdrawn: usize,
    /// Spans outside the target or empty (`x_start >= x_end`).
    pub out_of_bounds: usize,
    /// Pixels of the target set never drawn.
    pub gaps: usize,
    /// Pixels drawn that are not in the target set.
    pub extras: usize,
}

impl CoverageSink {
    /// A target of `size` with nothing drawn.
    pub fn new(size: Size) -> Self {
        let len = size.width.max(0) as usize * size.height.max(0) as usize;
        Self { size, counts: vec![0; len], drawn_from: len, drawn_to: 0, out_of_bounds: 0 }
    }

    /// How often pixel (x, y) was drawn; 0 outside the target.
    pub fn count(&self, x: i32, y: i32) -> u32 {
        let inside = (0..self.size.width).contains(&x) && (0..self.size.height).contains(&y);
        if inside {
            self.counts[(y * self.size.width + x) as usize]
        } else {
            0
        }
    }

    /// Spans so far that broke the [`SpanSink`] contract: outside the
    /// target, or empty.
    pub fn out_of_bounds(&self) -> usize {
        self.out_of_bounds
    }

    /// Compares what was drawn here with the pixels drawn at least once
    /// into `target` (a sink of the same size, e.g. the reference's).
    pub fn report(&self, target: &CoverageSink) -> CoverageReport {
        let mut report = CoverageReport { out_of_bounds: self.out_of_bounds, ..CoverageReport::default() };
        // Outside both sinks' drawn ranges every count is 0 on both sides.
        let from = self.drawn_from.min(target.drawn_from);
        let to = self.drawn_to.max(target.drawn_to).min(self.counts.len());
        for (index, &count) in self.counts.iter().enumerate().take(to).skip(from) {
            let wanted = target.counts.get(index).is_some_and(|&c| c > 0);
            report.overdrawn += usize::from(count > 1);
            report.gaps += usize::from(wanted && count == 0);
            report.extras += usize::from(!wanted && count > 0);
        }
        report
    }

    /// One line per row: `.` for pixels never drawn, `#` for pixels drawn
    /// once, the count for the rest (`+` past 9). Small targets only: for
    /// pictures in tests and readable test failures.
    pub fn ascii(&self) -> String {
        self.picture(|count, _| match count {
            0 => '.',
            1 => '#',
            2..=9 => char::from_digit(count, 10).unwrap_or('+'),
            _ => '+',
        })
    }

    /// Like [`CoverageSink::ascii`], marking differences from `target`:
    /// `-` a gap, `x` an extra, `2`-`9` or `+` overdraw, `#` drawn once
    /// where wanted, `.` neither.
    pub fn ascii_against(&self, target: &CoverageSink) -> String {
        self.picture(|count, index| {
            let wanted = target.counts.get(index).is_some_and(|&c| c > 0);
            match (wanted, count) {
                (false, 0) => '.',
                (true, 0) => '-',
                (false, _) => 'x',
                (true, 1) => '#',
                (true, 2..=9) => char::from_digit(count, 10).unwrap_or('+'),
                (true, _) => '+',
            }
        })
    }

    /// The counts as text, one character per pixel from `mark(count, index)`.
    fn picture(&self, mark: impl Fn(u32, usize) -> char) -> String {
        let width = self.size.width.max(1) as usize;
        let mut text = String::new();
        for (row, counts) in self.counts.chunks(width).enumerate() {
            text.extend(counts.iter().enumerate().map(|(x, &count)| mark(count, row * width + x)));
            text.push('\n');
        }
        text
    }
}

impl SpanSink for CoverageSink {
    fn size(&self) -> Size {
        self.size
    }

    fn span(&mut self, y: i32, x_start: i32, x_end: i32, _color: u8) {
        let Size { width, height } = self.size;
        let row_inside = (0..height).contains(&y);
        if !self.size.holds_span(y, x_start, x_end) {
            self.out_of_bounds += 1;
        }
        let (start, end) = (x_start.clamp(0, width), x_end.clamp(0, width));
        if row_inside && start < end {
            let row = (y * width) as usize;
            let (from, to) = (row + start as usize, row + end as usize);
            self.drawn_from = self.drawn_from.min(from);
            self.drawn_to = self.drawn_to.max(to);
            for count in &mut self.counts[from..to] {
                *count = count.saturating_add(1);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const SIZE: Size = Size { width: 4, height: 2 };

    #[test]
    fn counts_every_draw_and_reports_overdraw() {
        let mut sink = CoverageSink::new(SIZE);
        sink.span(0, 0, 3, 1);
        sink.span(0, 2, 4, 1);
        assert_eq!(sink.ascii(), "##2#\n....\n");
        assert_eq!(sink.count(2, 0), 2);
        assert_eq!(sink.report(&sink.clone()).overdrawn, 1);
    }

    #[test]
    fn spans_breaking_the_contract_are_counted_and_clipped() {
        let mut sink = CoverageSink::new(SIZE);
        sink.span(1, -3, 2, 1);
        sink.span(2, 0, 1, 1);
        sink.span(0, 3, 3, 1);
        sink.span(0, 3, 1, 1);
        sink.span(0, 3, 9, 1);
        assert_eq!(sink.ascii(), "...#\n##..\n");
        assert_eq!(sink.out_of_bounds(), 5);
        assert_eq!(sink.report(&sink.clone()).out_of_bounds, 5);
    }

    #[test]
    fn gaps_and_extras_are_measured_against_the_target() {
        let mut target = CoverageSink::new(SIZE);
        target.span(0, 0, 4, 1);
        let mut drawn = CoverageSink::new(SIZE);
        drawn.span(0, 1, 3, 1);
        drawn.span(1, 0, 1, 1);
        assert_eq!(drawn.report(&target), CoverageReport { overdrawn: 0, out_of_bounds: 0, gaps: 2, extras: 1 });
        assert_eq!(drawn.ascii_against(&target), "-##-\nx...\n");
        assert_eq!(target.report(&target), CoverageReport::default());
    }

    #[test]
    fn the_report_sees_pixels_drawn_on_either_side_far_apart() {
        let size = Size { width: 50, height: 40 };
        let mut target = CoverageSink::new(size);
        target.span(0, 0, 2, 1);
        target.span(39, 48, 50, 1);
        let mut drawn = CoverageSink::new(size);
        drawn.span(20, 10, 13, 1);
        drawn.span(20, 12, 14, 1);
        let report = drawn.report(&target);
        assert_eq!(report, CoverageReport { overdrawn: 1, out_of_bounds: 0, gaps: 4, extras: 4 });
        assert_eq!(target.report(&drawn), CoverageReport { overdrawn: 0, out_of_bounds: 0, gaps: 4, extras: 4 });
        assert_eq!(CoverageSink::new(size).report(&CoverageSink::new(size)), CoverageReport::default());
    }
}
