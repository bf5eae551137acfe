//! Where crossings become spans: the last stage of every path of `exact`,
//! and the only place they hand pixels to the sink.

use core::ops::Range;

use crate::target::SpanSink;

use super::clip::visible;
use super::edge::Crossing;

/// What every span of a fill shares: its colour, and the width of the
/// target its columns lie in (`0..=width`).
#[derive(Clone, Copy)]
pub(super) struct Target {
    pub color: u8,
    pub width: i32,
}

/// Emits the span `start..end` of `row` unless it is empty; `row` must be
/// a visible row (in `0..height`) and both columns in `0..=width`.
#[inline(always)]
pub(super) fn emit<S: SpanSink + ?Sized>(row: i64, start: i32, end: i32, target: Target, sink: &mut S) {
    if start < end {
        sink.span(row as i32, start, end, target.color);
    }
}

/// [`emit`] as an irregular span ([`SpanSink::irregular_span`]): for a
/// stage whose spans' lengths follow no pattern.
#[inline(always)]
pub(super) fn emit_irregular<S: SpanSink + ?Sized>(row: i64, start: i32, end: i32, target: Target, sink: &mut S) {
    if start < end {
        sink.irregular_span(row as i32, start, end, target.color);
    }
}

/// Emits the span between two crossings on each of `rows`, stepping both
/// edges after each row; the edges must meet every row of `rows`.
/// `ORDERED`: `a` is never right of `b`, so no comparison is needed.
/// `CLIP`: columns may lie outside `0..=width` and are clamped to it
/// ([`visible`]).
#[inline(always)]
pub(super) fn span_rows<const ORDERED: bool, const CLIP: bool, E: Crossing, S: SpanSink + ?Sized>(
    rows: Range<i64>,
    a: &mut E,
    b: &mut E,
    target: Target,
    sink: &mut S,
) {
    // Local copies: the steppers then need not be stored on every row.
    let (mut a_, mut b_) = (*a, *b);
    for row in rows {
        let (a_column, b_column) = (a_.column(), b_.column());
        let (start, end) =
            if ORDERED { (a_column, b_column) } else { (a_column.min(b_column), a_column.max(b_column)) };
        emit(row, visible::<CLIP>(start, target.width), visible::<CLIP>(end, target.width), target, sink);
        a_.step();
        b_.step();
    }
    (*a, *b) = (a_, b_);
}
