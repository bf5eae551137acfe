//! The exact method's fast path: one contour that is monotone in y
//! (Abrash's "convex", Black Book ch. 41), triangles included.
//!
//! The boundary of such a contour is two sides (chains, in chapter 39's
//! words) from its top vertex down to its bottom one, each meeting every
//! scan line between them exactly once (half-open, horizontal edges never),
//! with opposite directions. So every row has exactly two crossings and the
//! inside is the span between them under either fill rule, even where the
//! sides cross each other. This is chapter 39's two-chain walk, done with
//! the exact steppers of [`super::edge`].
//!
//! Nothing here allocates. The rows are walked in runs between vertices:
//! within a run both sides keep their edge, so a row costs two steps and
//! the span, with no test for the next vertex; clamping to the target is
//! only done for polygons that reach outside it on x. Each fill goes one
//! way: the target's cut (`clip.rs`), the edges (`edge.rs`), the spans
//! (`spans.rs`).

use core::cmp::Ordering;
use core::ops::Range;

use crate::geometry::Point;
use crate::target::{Size, SpanSink};

use super::clip::{beside_target, columns_fit, split_rows, visible_rows};
use super::edge::{first_sample_at_or_after, Crossing, EdgeStepper, ShortEdge};
use super::spans::{span_rows, Target};

/// Fills the triangle `a b c` with one span per row. Any three points are
/// taken, so no test of the class is needed first: on every row the long
/// edge (top to bottom vertex) and the one short edge meeting the row are
/// the only crossings, and three points on one line enclose nothing.
pub(crate) fn fill_triangle<S: SpanSink + ?Sized>([a, b, c]: [Point; 3], color: u8, size: Size, sink: &mut S) {
    // Sorted by y: `top.y <= middle.y <= bottom.y`.
    let (a, b) = if b.y < a.y { (b, a) } else { (a, b) };
    let (b, c) = if c.y < b.y { (c, b) } else { (b, c) };
    let (top, middle, bottom) = if b.y < a.y { (b, a, c) } else { (a, b, c) };

    // The long edge meets exactly the rows of the triangle; the upper short
    // edge the ones above the middle vertex's first row, the lower one the
    // rest (`middle` is clamped into the visible rows, so each part is
    // visible and empty when it has no rows).
    let rows = visible_rows(top.y, bottom.y, size.height);
    let (min_x, max_x) = (a.x.min(b.x).min(c.x), a.x.max(b.x).max(c.x));
    if rows.is_empty() || beside_target(min_x, max_x, size.width) {
        return;
    }
    let short = ShortEdge::fits((min_x, max_x), (top.y, bottom.y));
    // Which side of the long edge the middle vertex is on: the sign of the
    // cross product, exact in `i64` for a triangle of short edges (18-bit
    // differences) and in `i128` for any (33-bit differences, 66-bit
    // products). Right of it, the long edge is the left one on every row,
    // as the triangle lies between the two crossings and a ceiling keeps
    // their order; on it, nothing is enclosed.
    let side = if short {
        let d = |p: Point, q: Point| (i64::from(q.x) - i64::from(p.x), i64::from(q.y) - i64::from(p.y));
        let ((lx, ly), (mx, my)) = (d(top, bottom), d(top, middle));
        (mx * ly).cmp(&(lx * my))
    } else {
        let d = |p: Point, q: Point| (i128::from(q.x) - i128::from(p.x), i128::from(q.y) - i128::from(p.y));
        let ((lx, ly), (mx, my)) = (d(top, bottom), d(top, middle));
        (mx * ly).cmp(&(lx * my))
    };
    let long_is_left = match side {
        Ordering::Greater => true,
        Ordering::Less => false,
        Ordering::Equal => return,
    };
    let clip = !columns_fit(min_x, max_x, size.width);
    let parts = split_rows(rows, middle.y);
    let target = Target { color, width: size.width };
    if short {
        triangle_rows::<ShortEdge, _>([top, middle, bottom], parts, long_is_left, clip, target, sink);
    } else {
        triangle_rows::<EdgeStepper, _>([top, middle, bottom], parts, long_is_left, clip, target, sink);
    }
}

/// The rows of the triangle `top middle bottom` (sorted by y) above the
/// middle vertex's first row, then the rest, with edges walked as `E`.
/// All three edges are set up before any row is walked, so that their
/// divisions overlap.
#[inline(always)]
fn triangle_rows<E: Crossing, S: SpanSink + ?Sized>(
    [top, middle, bottom]: [Point; 3],
    (upper_rows, lower_rows): (Range<i64>, Range<i64>),
    long_is_left: bool,
    clip: bool,
    target: Target,
    sink: &mut S,
) {
    let mut long = E::at_row(top, bottom, upper_rows.start);
    // A part without rows may have a horizontal edge: no setup.
    let upper = (!upper_rows.is_empty()).then(|| E::at_row(top, middle, upper_rows.start));
    let lower = (!lower_rows.is_empty()).then(|| E::at_row(middle, bottom, lower_rows.start));
    if let Some(mut upper) = upper {
        let (left, right) = if long_is_left { (&mut long, &mut upper) } else { (&mut upper, &mut long) };
        emit_ordered(upper_rows, left, right, clip, target, sink);
    }
    if let Some(mut lower) = lower {
        let (left, right) = if long_is_left { (&mut long, &mut lower) } else { (&mut lower, &mut long) };
        emit_ordered(lower_rows, left, right, clip, target, sink);
    }
}

/// Fills `contour`, which must be monotone in y, with one span per row.
pub(crate) fn fill_monotone<S: SpanSink + ?Sized>(contour: &[Point], color: u8, size: Size, sink: &mut S) {
    let Some(&first) = contour.first() else {
        return;
    };
    // The top vertex (the first of the highest), the bottom, the x range.
    let (mut top, mut top_y, mut bottom_y, mut min_x, mut max_x) = (0, first.y, first.y, first.x, first.x);
    for (i, p) in contour.iter().enumerate() {
        if p.y < top_y {
            (top, top_y) = (i, p.y);
        }
        (bottom_y, min_x, max_x) = (bottom_y.max(p.y), min_x.min(p.x), max_x.max(p.x));
    }
    let clip = !columns_fit(min_x, max_x, size.width);
    if clip && beside_target(min_x, max_x, size.width) {
        return;
    }
    let rows = visible_rows(top_y, bottom_y, size.height);
    let target = Target { color, width: size.width };
    if ShortEdge::fits((min_x, max_x), (top_y, bottom_y)) {
        side_rows::<ShortEdge, _>(contour, top, rows, clip, target, sink);
    } else {
        side_rows::<EdgeStepper, _>(contour, top, rows, clip, target, sink);
    }
}

/// The visible `rows` of the monotone `contour` whose top vertex is
/// `contour[top]`, down both sides at once, with edges walked as `E`.
#[inline(always)]
fn side_rows<E: Crossing, S: SpanSink + ?Sized>(
    contour: &[Point],
    top: usize,
    rows: Range<i64>,
    clip: bool,
    target: Target,
    sink: &mut S,
) {
    let mut forward = Side { contour, walk: Walk::Forward, vertex: top, edges_left: contour.len() };
    let mut backward = Side { contour, walk: Walk::Backward, vertex: top, edges_left: contour.len() };
    let mut row = rows.start;
    if row >= rows.end {
        return;
    }
    // A side that runs out of edges above the bottom row (which a monotone
    // contour never does) ends the fill.
    let (Some(mut a), Some(mut b)) = (forward.seek::<E>(row), backward.seek::<E>(row)) else {
        return;
    };
    // Each side's next edge is set up (its division issued) before the
    // rows of the current one are walked, so that it is ready when they
    // end: the same seeks at the same rows, one run early.
    let mut next_a = forward.seek_after::<E>(&a, rows.end);
    let mut next_b = backward.seek_after::<E>(&b, rows.end);
    loop {
        // Both edges meet every row up to the first one either leaves.
        let run_end = a.end_row.min(b.end_row).min(rows.end);
        // The sides may cross: the left crossing is the smaller column.
        if clip {
            span_rows::<false, true, _, _>(row..run_end, &mut a.stepper, &mut b.stepper, target, sink);
        } else {
            span_rows::<false, false, _, _>(row..run_end, &mut a.stepper, &mut b.stepper, target, sink);
        }
        row = run_end;
        if row >= rows.end {
            return;
        }
        if a.end_row == row {
            let Some(next) = next_a else { return };
            a = next;
            next_a = forward.seek_after(&a, rows.end);
        }
        if b.end_row == row {
            let Some(next) = next_b else { return };
            b = next;
            next_b = backward.seek_after(&b, rows.end);
        }
    }
}

/// [`span_rows`] for `left` never right of `right`.
#[inline(always)]
fn emit_ordered<E: Crossing, S: SpanSink + ?Sized>(
    rows: Range<i64>,
    left: &mut E,
    right: &mut E,
    clip: bool,
    target: Target,
    sink: &mut S,
) {
    if clip {
        span_rows::<true, true, _, _>(rows, left, right, target, sink);
    } else {
        span_rows::<true, false, _, _>(rows, left, right, target, sink);
    }
}

/// Which way round the contour a side goes from the top vertex.
#[derive(Clone, Copy)]
enum Walk {
    Forward,
    Backward,
}

/// One side of the contour (the vertices one way round from the top to
/// the bottom), walked down from the top vertex an edge at a time.
struct Side<'a> {
    contour: &'a [Point],
    walk: Walk,
    /// The upper vertex of the next edge to take.
    vertex: usize,
    /// Edges not taken yet: bounds the walk on any input.
    edges_left: usize,
}

/// A side's edge on the current row, and the row it ends before.
struct SideEdge<E> {
    stepper: E,
    end_row: i64,
}

impl Side<'_> {
    /// The edge [`Side::seek`] takes where `edge` ends, if that is above
    /// `end`; `None` otherwise, or if the side runs out of edges.
    #[inline(always)]
    fn seek_after<E: Crossing>(&mut self, edge: &SideEdge<E>, end: i64) -> Option<SideEdge<E>> {
        if edge.end_row < end {
            self.seek(edge.end_row)
        } else {
            None
        }
    }

    /// Takes edges until one meets `row`, and puts its stepper on that row.
    /// `None` only if the side runs out of edges.
    fn seek<E: Crossing>(&mut self, row: i64) -> Option<SideEdge<E>> {
        let last = self.contour.len() - 1;
        while self.edges_left > 0 {
            self.edges_left -= 1;
            let next = match self.walk {
                Walk::Forward if self.vertex == last => 0,
                Walk::Forward => self.vertex + 1,
                Walk::Backward if self.vertex == 0 => last,
                Walk::Backward => self.vertex - 1,
            };
            let (top, bottom) = (self.contour[self.vertex], self.contour[next]);
            self.vertex = next;
            let end_row = first_sample_at_or_after(bottom.y.into());
            if first_sample_at_or_after(top.y.into()) <= row && row < end_row {
                let stepper =
                    if end_row - row == 1 { E::at_last_row(top, bottom, row) } else { E::at_row(top, bottom, row) };
                return Some(SideEdge { stepper, end_row });
            }
        }
        None
    }
}
