//! The exact method's general path: any number of contours, crossing or
//! not, under either fill rule. An edge table sorted by first scan line
//! feeds an active edge table (Black Book ch. 40's global and active edge
//! tables); each row sorts the active crossings, sums their directions from
//! the left and emits the runs the fill rule calls inside as whole spans.

use alloc::vec::Vec;

use crate::geometry::{FillRule, Point, Polygon};
use crate::method::Refusal;
use crate::sink::{Size, SpanSink};

use super::edge::{first_sample_at_or_after, visible_column, visible_rows, EdgeStepper};

/// Fills `polygon` by its fill rule. Refuses only when memory for the edge
/// tables cannot be had.
pub(crate) fn fill_active_edges(polygon: &Polygon, size: Size, sink: &mut dyn SpanSink) -> Result<(), Refusal> {
    let mut edges = edge_table(polygon, size)?;
    edges.sort_unstable_by_key(|edge| edge.rows.start);
    let mut active: Vec<ActiveEdge> = Vec::new();
    active.try_reserve_exact(edges.len()).map_err(|_| Refusal::OutOfMemory)?;

    let mut pending = edges.iter().peekable();
    let mut row = 0;
    loop {
        if active.is_empty() {
            // Nothing crosses the rows in between: go to the next edge's first.
            match pending.peek() {
                Some(edge) => row = edge.rows.start,
                None => return Ok(()),
            }
        }
        while let Some(edge) = pending.next_if(|edge| edge.rows.start <= row) {
            active.push(ActiveEdge {
                stepper: EdgeStepper::at_row(edge.top, edge.bottom, row),
                winding: edge.winding,
                end_row: edge.rows.end,
            });
        }
        // The list comes sorted from the previous row except where edges
        // started or crossed. The book bubble-sorts it (ch. 40), which goes
        // quadratic when many edges cross; this sort stays O(n log n) and
        // sees an already sorted list in one pass.
        active.sort_unstable_by_key(|edge| edge.stepper.column);
        emit_row(row, &active, polygon.rule, polygon.color, size.width, sink);
        active.retain_mut(|edge| {
            let continues = row + 1 < edge.end_row;
            if continues {
                edge.stepper.step();
            }
            continues
        });
        row += 1;
    }
}

/// An edge of the polygon, top to bottom, with the visible rows it meets.
struct TableEdge {
    top: Point,
    bottom: Point,
    /// +1 where the contour runs down the edge, -1 where it runs up.
    winding: i64,
    rows: core::ops::Range<i64>,
}

/// An edge crossing the current row.
struct ActiveEdge {
    stepper: EdgeStepper,
    winding: i64,
    end_row: i64,
}

/// Every edge that meets a visible row and can lie left of a visible pixel
/// centre. Horizontal edges never meet a row; an edge whose leftmost point
/// is right of the last centre counts for no visible pixel.
fn edge_table(polygon: &Polygon, size: Size) -> Result<Vec<TableEdge>, Refusal> {
    let mut edges = Vec::new();
    edges.try_reserve_exact(polygon.vertex_count()).map_err(|_| Refusal::OutOfMemory)?;
    for contour in &polygon.contours {
        let following = contour.iter().cycle().skip(1);
        for (&from, &to) in contour.iter().zip(following) {
            let (top, bottom, winding) = if from.y <= to.y { (from, to, 1) } else { (to, from, -1) };
            let rows = visible_rows(top.y, bottom.y, size.height);
            let leftmost_column = first_sample_at_or_after(top.x.min(bottom.x).into());
            if !rows.is_empty() && leftmost_column < i64::from(size.width) {
                edges.push(TableEdge { top, bottom, winding, rows });
            }
        }
    }
    Ok(edges)
}

/// Emits the inside runs of one row. `active` is sorted by column; all
/// crossings at one column are summed before the rule is asked, so runs
/// that touch are emitted as one span and no pixel is emitted twice. Edges
/// right of the target are not in the table, so a run may still be open at
/// the end: it reaches the right border.
fn emit_row(row: i64, active: &[ActiveEdge], rule: FillRule, color: u8, width: i32, sink: &mut dyn SpanSink) {
    let mut emit = |start: i64, end: i64| {
        let (start, end) = (visible_column(start, width), visible_column(end, width));
        if start < end {
            sink.span(row as i32, start, end, color);
        }
    };
    let mut winding = 0i64;
    let mut span_start = 0;
    let mut i = 0;
    while i < active.len() {
        let column = active[i].stepper.column;
        let was_inside = is_inside(rule, winding);
        while i < active.len() && active[i].stepper.column == column {
            winding += active[i].winding;
            i += 1;
        }
        match (was_inside, is_inside(rule, winding)) {
            (false, true) => span_start = column,
            (true, false) => emit(span_start, column),
            _ => {}
        }
    }
    if is_inside(rule, winding) {
        emit(span_start, width.into());
    }
}

/// Whether a winding sum (signed crossings left of a centre) means inside.
/// Every crossing is +1 or -1, so the sum's parity is the crossing count's.
fn is_inside(rule: FillRule, winding: i64) -> bool {
    match rule {
        FillRule::EvenOdd => winding & 1 != 0,
        FillRule::NonZero => winding != 0,
    }
}
