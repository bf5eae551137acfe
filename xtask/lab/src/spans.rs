//! Spans as data: a sink that records them as they come, and the few
//! things the lab reads off a recorded fill.

use raster::{CoverageSink, Size, SpanSink, SCREEN};

/// One span as a method emitted it: row `y`, pixels `x_start..x_end`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Span {
    pub y: i32,
    pub x_start: i32,
    pub x_end: i32,
}

/// A 320x200 sink that keeps every span, unclipped, so one fill can be
/// replayed into as many sinks as the measures need.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Recorder {
    pub spans: Vec<Span>,
}

impl SpanSink for Recorder {
    fn size(&self) -> Size {
        SCREEN
    }

    fn span(&mut self, y: i32, x_start: i32, x_end: i32, _color: u8) {
        self.spans.push(Span { y, x_start, x_end });
    }
}

/// Sends `spans` to `sink` again, in order.
pub fn replay(spans: &[Span], color: u8, sink: &mut dyn SpanSink) {
    for s in spans {
        sink.span(s.y, s.x_start, s.x_end, color);
    }
}

/// The spans sorted by row and start, with spans that touch end to start
/// joined: two fills have the same normal form exactly when they write the
/// same pixels, each once. `None` when a span overlaps another, is empty
/// or leaves the screen (those need counting, not comparing).
pub fn normal_form(spans: &[Span]) -> Option<Vec<Span>> {
    let mut sorted = spans.to_vec();
    sorted.sort_unstable_by_key(|s| (s.y, s.x_start));
    let mut normal: Vec<Span> = Vec::with_capacity(sorted.len());
    for s in sorted {
        if !SCREEN.holds_span(s.y, s.x_start, s.x_end) {
            return None;
        }
        match normal.last_mut() {
            Some(last) if last.y == s.y && last.x_end > s.x_start => return None,
            Some(last) if last.y == s.y && last.x_end == s.x_start => last.x_end = s.x_end,
            _ => normal.push(s),
        }
    }
    Some(normal)
}

/// Every run of pixels of `coverage` (the screen's size) whose count is
/// `covered`, row by row, as spans into `sink`.
pub fn emit_covered(coverage: &CoverageSink, covered: impl Fn(u32) -> bool, color: u8, sink: &mut dyn SpanSink) {
    for y in 0..SCREEN.height {
        let mut run_start = None;
        for x in 0..=SCREEN.width {
            let inside = x < SCREEN.width && covered(coverage.count(x, y));
            match (run_start, inside) {
                (None, true) => run_start = Some(x),
                (Some(start), false) => {
                    sink.span(y, start, x, color);
                    run_start = None;
                }
                _ => {}
            }
        }
    }
}

/// The part of a span on the screen, if any.
fn visible(s: &Span) -> Option<(i64, i64, i64)> {
    let (x0, x1) = (s.x_start.max(0), s.x_end.min(SCREEN.width));
    ((0..SCREEN.height).contains(&s.y) && x0 < x1).then(|| (i64::from(s.y), i64::from(x0), i64::from(x1)))
}

/// The byte ranges the visible parts of the spans cover in a 320x200
/// buffer of rows, in order.
pub fn byte_ranges(spans: &[Span]) -> Vec<(usize, usize)> {
    let width = i64::from(SCREEN.width);
    spans.iter().filter_map(visible).map(|(y, x0, x1)| ((y * width + x0) as usize, (y * width + x1) as usize)).collect()
}

/// Pixels the spans write on the screen, counting overdraw.
pub fn pixel_count(spans: &[Span]) -> u64 {
    spans.iter().filter_map(visible).map(|(_, x0, x1)| (x1 - x0) as u64).sum()
}

/// Mean position of the pixel centres the spans write on the screen, in
/// pixels, or `None` when they write none.
pub fn centroid(spans: &[Span]) -> Option<(f64, f64)> {
    let (mut n, mut sx, mut sy) = (0i64, 0i64, 0i64);
    for (y, x0, x1) in spans.iter().filter_map(visible) {
        let w = x1 - x0;
        n += w;
        // Sum of x0..x1 (pixel indices), the centres add one half each.
        sx += (x0 + x1 - 1) * w / 2;
        sy += y * w;
    }
    (n > 0).then(|| (sx as f64 / n as f64 + 0.5, sy as f64 / n as f64 + 0.5))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn span(y: i32, x_start: i32, x_end: i32) -> Span {
        Span { y, x_start, x_end }
    }

    #[test]
    fn the_recorder_keeps_spans_unclipped_and_in_order() {
        let mut recorder = Recorder::default();
        recorder.span(-1, 5, 900, 3);
        recorder.span(2, 1, 2, 3);
        assert_eq!(recorder.spans, vec![span(-1, 5, 900), span(2, 1, 2)]);
    }

    #[test]
    fn normal_form_ignores_order_and_splitting() {
        let split = [span(3, 5, 7), span(1, 0, 2), span(3, 2, 5)];
        assert_eq!(normal_form(&split), Some(vec![span(1, 0, 2), span(3, 2, 7)]));
        assert_eq!(normal_form(&split), normal_form(&[span(1, 0, 2), span(3, 2, 7)]));
    }

    #[test]
    fn normal_form_refuses_what_must_be_counted() {
        assert_eq!(normal_form(&[span(0, 0, 5), span(0, 4, 6)]), None);
        assert_eq!(normal_form(&[span(0, 0, 5), span(0, 0, 5)]), None);
        assert_eq!(normal_form(&[span(0, 3, 3)]), None);
        assert_eq!(normal_form(&[span(0, 300, 321)]), None);
        assert_eq!(normal_form(&[span(-1, 0, 1)]), None);
    }

    #[test]
    fn byte_ranges_are_the_visible_parts_row_after_row() {
        let ranges = byte_ranges(&[span(0, -5, 3), span(2, 318, 400), span(200, 0, 9), span(1, 4, 4)]);
        assert_eq!(ranges, vec![(0, 3), (958, 960)]);
    }

    #[test]
    fn pixels_are_counted_on_screen_only() {
        assert_eq!(pixel_count(&[span(0, -5, 3), span(0, 318, 400), span(200, 0, 9), span(1, 4, 4)]), 5);
    }

    #[test]
    fn centroid_is_the_mean_pixel_centre() {
        // Pixels (0,0) (1,0) (2,0) and (1,2): centres average to (1.5, 1.0).
        assert_eq!(centroid(&[span(0, 0, 3), span(2, 1, 2)]), Some((1.5, 1.0)));
        assert_eq!(centroid(&[span(-3, 0, 3)]), None);
    }
}
