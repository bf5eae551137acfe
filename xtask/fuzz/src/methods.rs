//! The `methods` target: every method on any polygon (any `i32` vertices,
//! any number of contours, both rules) into targets of odd sizes. No
//! method may panic or emit a span outside its target
//! (`docs/conventions.md#garbage-in-never-crashes`); `exact` (through
//! `Method`, [`fill_auto`] and each of its paths that takes the polygon)
//! may not refuse it and may not draw a pixel twice, as its docs promise.

use raster::{fill_auto, ExactPath, MethodId, Size, SpanSink, SCREEN};

use crate::polygon::{decode, Fill};

/// The targets: the screen, none, one pixel, narrow ones, a row, a column,
/// a negative height (no pixels and no row a span could be on), a small
/// screen.
pub const TARGETS: [Size; 8] = [
    SCREEN,
    Size { width: 0, height: 0 },
    Size { width: 1, height: 1 },
    Size { width: 7, height: 3 },
    Size { width: 3, height: -4 },
    Size { width: 320, height: 1 },
    Size { width: 1, height: 200 },
    Size { width: 40, height: 25 },
];

/// A sink that keeps the spans a fill emits, to check them afterwards in
/// time proportional to the spans, not to the target's pixels (a pixel
/// counter's per-pixel comparisons, instrumented by the fuzzer, took most
/// of this target's time).
struct SpanLog {
    size: Size,
    spans: Vec<(i32, i32, i32)>,
}

impl SpanLog {
    fn new(size: Size) -> Self {
        Self { size, spans: Vec::new() }
    }

    /// Spans outside the target or empty, which break the sink contract.
    fn strays(&self) -> usize {
        self.spans.iter().filter(|&&(y, start, end)| !self.size.holds_span(y, start, end)).count()
    }

    /// Whether two spans of one row share a pixel.
    fn overdraws(&mut self) -> bool {
        self.spans.sort_unstable();
        self.spans.windows(2).any(|pair| pair[0].0 == pair[1].0 && pair[1].1 < pair[0].2)
    }
}

impl SpanSink for SpanLog {
    fn size(&self) -> Size {
        self.size
    }

    fn span(&mut self, y: i32, x_start: i32, x_end: i32, _color: u8) {
        self.spans.push((y, x_start, x_end));
    }
}

/// Fails naming `what` if `log` has a span outside its target, or, when
/// `once`, two spans sharing a pixel.
fn assert_clean(log: &mut SpanLog, what: &dyn Fn() -> String, once: bool) {
    assert_eq!(log.strays(), 0, "{}: spans outside the target", what());
    if once {
        assert!(!log.overdraws(), "{}: pixels drawn twice", what());
    }
}

pub fn check(data: &[u8]) {
    let Fill { polygon, target } = decode(data);
    let size = TARGETS[target % TARGETS.len()];
    let what = |name: &str| format!("{name} on {polygon:?} into {size:?}");
    for id in MethodId::ALL {
        let mut log = SpanLog::new(size);
        let filled = id.method().fill(&polygon, &mut log);
        let exact = id == MethodId::Exact;
        assert_clean(&mut log, &|| what(id.name()), exact);
        if exact {
            assert_eq!(filled, Ok(()), "{}", what("exact"));
        }
    }
    let mut log = SpanLog::new(size);
    assert_eq!(fill_auto(&polygon, &mut log), Ok(()), "{}", what("fill_auto"));
    assert_clean(&mut log, &|| what("fill_auto"), true);
    for path in ExactPath::every(&polygon) {
        let mut log = SpanLog::new(size);
        assert_eq!(path.fill(&mut log), Ok(()), "{}", what(path.name()));
        assert_clean(&mut log, &|| what(path.name()), true);
    }
}

/// Every built-in polygon, on the screen.
pub fn seeds() -> Vec<(String, Vec<u8>)> {
    crate::polygon::builtin_seeds(0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_log_finds_strays_and_shared_pixels() {
        let mut log = SpanLog::new(Size { width: 10, height: 2 });
        for (y, start, end) in [(0, 0, 4), (1, 2, 5), (0, 4, 10)] {
            log.span(y, start, end, 1);
        }
        assert_eq!((log.strays(), log.overdraws()), (0, false));
        for (y, start, end) in [(1, 4, 6), (2, 0, 1), (0, 3, 3), (-1, 0, 1), (0, 9, 11)] {
            log.span(y, start, end, 1);
        }
        assert_eq!((log.strays(), log.overdraws()), (4, true));
    }
}
