//! The general path's walk, from the edge table to the spans: the rows top
//! down, in stretches between events (a chain starting or ending), the
//! active chains' crossings kept in order (`order.rs`), paired into inside
//! runs by the fill rule (`runs.rs`) or, on rows with a crossing for every
//! four columns, summed per column instead (`columns.rs`), and handed to
//! the spans stage (`spans.rs`).
//!
//! Within a stretch the active chains stay the same, and unless two of
//! them cross their order does too, and so do the inside runs, worked out
//! once as pairs of places in that order ([`Run`]). A row then costs its
//! spans and one pass over the active chains that steps them and checks
//! their order; only a row where the order changed sorts again and works
//! the runs out again. Where a chain's edge ends, its next edge takes its
//! place and the runs stay, if the order holds. Two chains with the inside
//! between them take the monotone path's two-edge loop; so do the runs of
//! any stretch up to a vertex where each crossing opens or closes a run
//! and no two of them swap.

use core::ops::Range;

use crate::target::SpanSink;

use super::super::clip::visible;
use super::super::edge::Crossing;
use super::super::spans::{emit, span_rows, Target};
use super::columns::emit_by_columns;
use super::order::{insertion_sort, sort};
use super::runs::plan;
use super::tables::{start_row, Active, Crossings, Edge, EdgeTable, Run};

/// Walks the rows of the chains of `table` in `crossings`, top down.
/// `NON_ZERO` picks the rule; without `CLIP` every crossing column lies in
/// the target's `0..=width`.
pub(super) fn walk<const NON_ZERO: bool, const CLIP: bool, E: Crossing, S: SpanSink + ?Sized>(
    table: EdgeTable<'_, E>,
    crossings: Crossings<'_, E>,
    target: Target,
    sink: &mut S,
) {
    let EdgeTable { edges, starts, .. } = table;
    let Crossings { active, columns, runs, mut wide } = crossings;
    // Active chains, chains joined, inside runs.
    let (mut k, mut next, mut planned) = (0, 0, 0);
    let mut row = 0;
    loop {
        if k == 0 {
            // Nothing crosses the rows in between: go to the next chain's first.
            match starts.get(next) {
                Some(&key) => row = start_row(key),
                None => return,
            }
        }
        // The chains that end above `row` leave; the ones that start on it join.
        let mut kept = 0;
        for i in 0..k {
            if i64::from(active[i].chain_end_row) != row {
                active[kept] = active[i];
                kept += 1;
            }
        }
        let joining = starts[next..].iter().take_while(|&&key| start_row(key) == row).count();
        for &key in &starts[next..next + joining] {
            active[kept] = table.join(key);
            kept += 1;
        }
        (k, next) = (kept, next + joining);
        if k == 0 {
            continue;
        }
        if let Some(wide) = wide.as_mut().filter(|wide| wide.tallies(k)) {
            // So many crossings for the width that summing them per column
            // is cheaper than keeping them sorted; and chains start and end
            // on most rows, so this goes a row at a time.
            emit_by_columns::<NON_ZERO, _, _>(row, &mut active[..k], edges, wide.windings, target, sink);
            row += 1;
            continue;
        }
        // Every active chain meets `row` and every pending one starts below
        // it, so the stretch has at least this row.
        let starting = starts.get(next).map_or(i64::MAX, |&key| start_row(key));
        let end = active[..k].iter().map(|chain| i64::from(chain.chain_end_row)).fold(starting, i64::min);
        let mut settled = false;
        while row < end {
            if !settled {
                sort(&mut active[..k], &mut columns[..k], target.width, wide.as_mut());
                columns[k] = target.width;
                planned = plan::<NON_ZERO, _>(&active[..k], runs);
            }
            if let ([a, b], [Run { open: 0, close: 1 }]) = (&mut active[..k], &runs[..planned]) {
                two_chains::<CLIP, _, _>(row..end, [a, b], edges, target, sink);
                row = end;
                columns[0] = visible::<CLIP>(a.stepper.column(), target.width);
                columns[1] = visible::<CLIP>(b.stepper.column(), target.width);
                settled = columns[0] <= columns[1];
                continue;
            }
            // Up to the next vertex every edge stays the same straight line.
            let segment = row..next_vertex_row(&active[..k]).min(end);
            let (active, columns) = (&mut active[..k], &mut columns[..=k]);
            // Fewer rows than this walk faster by rows.
            const FEW: i64 = 3;
            let paired = rows_in_pairs(segment.clone(), active, &runs[..planned]);
            if paired > FEW {
                let rows = row..row + paired;
                for run in &runs[..planned] {
                    let (left, right) = active.split_at_mut(run.close as usize);
                    let (a, b) = (&mut left[run.open as usize].stepper, &mut right[0].stepper);
                    span_rows::<true, CLIP, _, _>(rows.clone(), a, b, target, sink);
                }
                row = rows.end;
            } else {
                let sorted;
                (row, sorted) = rows_in_order::<NON_ZERO, CLIP, _, _>(
                    segment.clone(),
                    (active, columns, runs),
                    &mut planned,
                    target,
                    sink,
                );
                if !sorted {
                    settled = false;
                    continue;
                }
            }
            // At the vertex, chains whose edge ended go on with their next.
            let (mut in_order, mut previous) = (true, 0);
            for (chain, column) in active.iter_mut().zip(columns.iter_mut()) {
                chain.resume(row, edges);
                *column = visible::<CLIP>(chain.stepper.column(), target.width);
                in_order &= previous <= *column;
                previous = *column;
            }
            settled = in_order;
        }
    }
}

/// For how many of `rows` (the rows up to the next vertex, so every edge
/// is one straight line over them) the runs of `active` can be walked one
/// after the other, each as two edges: none where some crossing opens or
/// closes no run (or one reaches the right border), or where the
/// crossings' positions ([`Crossing::position_in`]) are not in order on
/// the first row; else up to the first row where two neighbours' positions
/// swap, if they do. Positions are linear in the row, so they stay in
/// order until then, and so do the columns: each run's opening crossing is
/// never right of its closing one. (Finding where two neighbours swap is
/// one division, for those that do.)
#[inline(always)]
fn rows_in_pairs<E: Crossing>(rows: Range<i64>, active: &[Active<E>], runs: &[Run]) -> i64 {
    if 2 * runs.len() != active.len() || runs.iter().any(|run| run.close as usize == active.len()) {
        return 0;
    }
    let (count, last) = (rows.end - rows.start, rows.end - rows.start - 1);
    let mut hold = count;
    // The previous crossing's position on the first row and its step.
    let mut previous: Option<(i64, i64)> = None;
    for chain in active {
        let (Some(first), Some(next)) = (chain.stepper.position_in(0), chain.stepper.position_in(1)) else {
            return 0;
        };
        let step = next - first;
        if let Some((previous_first, previous_step)) = previous {
            let (gap, closing) = (first - previous_first, previous_step - step);
            if gap < 0 {
                return 0;
            }
            // The gap closes by `closing` a row: it is below zero first on
            // row `gap / closing + 1`, if that is not past the last.
            if closing > 0 && gap / closing < last {
                hold = hold.min(gap / closing + 1);
            }
        }
        previous = Some((first, step));
    }
    hold
}

/// Two chains with the inside between them, outside right of both, over
/// `rows`: whatever their order (they may cross), the inside is the span
/// between them, as on the monotone path, and rows go in runs between
/// their vertices, where each chain takes its next edge.
#[inline(always)]
fn two_chains<const CLIP: bool, E: Crossing, S: SpanSink + ?Sized>(
    rows: Range<i64>,
    [a, b]: [&mut Active<E>; 2],
    edges: &[Edge<E>],
    target: Target,
    sink: &mut S,
) {
    let mut row = rows.start;
    while row < rows.end {
        let run_end = a.edge_end_row().min(b.edge_end_row()).min(rows.end);
        span_rows::<false, CLIP, _, _>(row..run_end, &mut a.stepper, &mut b.stepper, target, sink);
        row = run_end;
        a.resume(row, edges);
        b.resume(row, edges);
    }
}

/// Emits the runs of `active` on each of `rows` (rows up to a vertex, so
/// every edge goes on over them) and steps the edges to the row after,
/// keeping them in order (and `planned`, the count of runs, with it) where
/// a few of them cross; returns that row, or an earlier one where the
/// order needs a full sort, and whether the edges are sorted there.
/// `columns` are the edges' visible columns on the first row, and the
/// right border; `runs` has room for every run.
#[inline(always)]
fn rows_in_order<const NON_ZERO: bool, const CLIP: bool, E: Crossing, S: SpanSink + ?Sized>(
    rows: Range<i64>,
    (active, columns, runs): (&mut [Active<E>], &mut [i32], &mut [Run]),
    planned: &mut usize,
    target: Target,
    sink: &mut S,
) -> (i64, bool) {
    let mut row = rows.start;
    loop {
        for run in &runs[..*planned] {
            emit(row, columns[run.open as usize], columns[run.close as usize], target, sink);
        }
        row += 1;
        if row == rows.end {
            // The caller takes each chain past the vertex, then its column.
            for chain in active.iter_mut() {
                chain.stepper.step();
            }
            return (row, true);
        }
        // Visible columns are never negative.
        let (mut in_order, mut previous) = (true, 0);
        for (chain, column) in active.iter_mut().zip(columns.iter_mut()) {
            chain.stepper.step();
            *column = visible::<CLIP>(chain.stepper.column(), target.width);
            in_order &= previous <= *column;
            previous = *column;
        }
        if !in_order {
            // Under the even-odd rule the runs pair the crossings in order
            // whatever their directions; under the non-zero rule they
            // follow the directions.
            if !insertion_sort(active, columns) {
                return (row, false);
            }
            if NON_ZERO {
                *planned = plan::<NON_ZERO, _>(active, runs);
            }
        }
    }
}

/// The first row below the current where one of `active`'s edges ends.
#[inline(always)]
fn next_vertex_row<E: Crossing>(active: &[Active<E>]) -> i64 {
    active.iter().map(Active::edge_end_row).min().unwrap_or(i64::MAX)
}
