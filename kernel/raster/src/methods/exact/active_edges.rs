//! The exact method's general path: any number of contours, crossing or
//! not, under either fill rule. An edge table sorted by first scan line
//! feeds an active edge table (Black Book ch. 40's global and active edge
//! tables), kept sorted by visible column; the directions summed from the
//! left decide which crossings open and close the runs the fill rule calls
//! inside.
//!
//! The rows go in stretches between events (an edge starting or ending):
//! within one the active edges stay the same, and unless two of them cross
//! their order does too, and so do the inside runs, worked out once as
//! pairs of places in that order ([`Run`]). A row then costs its spans and
//! one pass over the active edges that steps them and checks their order;
//! only a row where the order changed sorts again and works the runs out
//! again. Where one edge ends on the row another of the same direction
//! starts (a vertex the boundary passes through: most vertices of most
//! polygons), the new edge takes the old one's place and the runs stay, if
//! the order holds. Two edges with the inside between them take the
//! monotone path's two-edge loop. Where there is a crossing for every four
//! columns or more (scribbles of thousands of edges), keeping them sorted
//! costs more than summing their windings per column, which a row then
//! does instead ([`emit_by_columns`]). Where the tables live is
//! [`tables`](super::tables)' business: nothing here allocates.

use core::ops::Range;

use crate::geometry::{FillRule, Polygon};
use crate::method::Refusal;
use crate::sink::{Size, SpanSink};

use super::edge::{visible_column, Crossing, EdgeStepper, ShortEdge};
use super::monotone::{columns_fit, span_rows};
use super::tables::{self, start_row, Active, Run, Scratch, Stepper, Tables};

/// Fills `polygon` by its fill rule, with tables on the stack or in
/// `scratch` (a new one when there is none). Refuses only when the
/// scratch must grow and memory cannot be had.
pub(crate) fn fill_active_edges<S: SpanSink + ?Sized>(
    polygon: &Polygon,
    size: Size,
    sink: &mut S,
    scratch: Option<&mut Scratch>,
) -> Result<(), Refusal> {
    // The box of every vertex: whether columns may leave the target, and
    // whether every edge may be a `ShortEdge`.
    let mut vertices = polygon.contours.iter().flatten();
    let Some(&first) = vertices.next() else { return Ok(()) };
    let (mut min_x, mut max_x, mut min_y, mut max_y) = (first.x, first.x, first.y, first.y);
    for p in vertices {
        (min_x, max_x, min_y, max_y) = (min_x.min(p.x), max_x.max(p.x), min_y.min(p.y), max_y.max(p.y));
    }
    let clip = !columns_fit(min_x, max_x, size.width);
    let target = Target { color: polygon.color, width: size.width };
    let edges = polygon.vertex_count();
    if ShortEdge::fits((min_x, max_x), (min_y, max_y)) {
        tables::with_tables::<ShortEdge, _>(edges, size.width, scratch, |tables| {
            fill_table(tables, polygon, clip, size, target, sink)
        })
    } else {
        tables::with_tables::<EdgeStepper, _>(edges, size.width, scratch, |tables| {
            fill_table(tables, polygon, clip, size, target, sink)
        })
    }
}

/// Builds the edge table of `polygon` in `tables` and walks it.
fn fill_table<E: Stepper, S: SpanSink + ?Sized>(
    mut tables: Tables<'_, E>,
    polygon: &Polygon,
    clip: bool,
    size: Size,
    target: Target,
    sink: &mut S,
) {
    let count = tables::build(polygon, size, &mut tables);
    let walk = match (polygon.rule, clip) {
        (FillRule::EvenOdd, false) => walk::<false, false, E, S>,
        (FillRule::EvenOdd, true) => walk::<false, true, E, S>,
        (FillRule::NonZero, false) => walk::<true, false, E, S>,
        (FillRule::NonZero, true) => walk::<true, true, E, S>,
    };
    walk(count, tables, target, sink);
}

/// What every span shares.
#[derive(Clone, Copy)]
struct Target {
    color: u8,
    width: i32,
}

/// A visible column (in `0..=width`): clamped under `CLIP`, else already
/// in range.
#[inline(always)]
fn visible<const CLIP: bool>(column: i64, width: i32) -> i32 {
    if CLIP {
        visible_column(column, width)
    } else {
        column as i32
    }
}

/// Walks the rows of the `count` chains of `tables`, top down. `NON_ZERO`
/// picks the rule; without `CLIP` every crossing column lies in the
/// target's `0..=width`.
fn walk<const NON_ZERO: bool, const CLIP: bool, E: Crossing, S: SpanSink + ?Sized>(
    count: usize,
    tables: Tables<'_, E>,
    target: Target,
    sink: &mut S,
) {
    let Tables { edges, chains, starts, active, columns, runs, mut wide } = tables;
    let (edges, chains, starts) = (&*edges, &*chains, &starts[..count]);
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
            active[kept] = tables::join(key, chains, edges);
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
                tables::sort(&mut active[..k], &mut columns[..k], target.width, wide.as_mut());
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
                    span_rows::<true, CLIP, _, _>(rows.clone(), a, b, target.color, target.width, sink);
                }
                row = rows.end;
            } else {
                let tables =
                    Tables { edges: &mut [], chains: &mut [], starts: &mut [], active, columns, runs, wide: None };
                let sorted;
                (row, sorted) =
                    rows_in_order::<NON_ZERO, CLIP, _, _>(segment.clone(), tables, &mut planned, target, sink);
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
    edges: &[tables::Edge<E>],
    target: Target,
    sink: &mut S,
) {
    let mut row = rows.start;
    while row < rows.end {
        let run_end = a.edge_end_row().min(b.edge_end_row()).min(rows.end);
        span_rows::<false, CLIP, _, _>(row..run_end, &mut a.stepper, &mut b.stepper, target.color, target.width, sink);
        row = run_end;
        a.resume(row, edges);
        b.resume(row, edges);
    }
}

/// Works out the inside runs of `active`, in order, into `runs`, and
/// returns how many: each crossing's winding sum (of the crossings before
/// it and up to it) under the rule says whether it opens a run, closes one
/// or neither. A pixel's inside test sums every crossing at or left of
/// it; where several share a column, the states between them cover no
/// pixel, so any order of theirs gives the same pixels. A run still open
/// after the last crossing reaches the right border (edges right of the
/// target are not in the table, so the sum need not come back to zero).
/// `runs` has a place per active edge and one more.
fn plan<const NON_ZERO: bool, E>(active: &[Active<E>], runs: &mut [Run]) -> usize {
    // Each crossing adds +1 or -1: no `i64` overflow for any edge count.
    // Without a branch per crossing (which way each goes is anyone's
    // guess): every crossing writes a run, which only a closing one keeps.
    let (mut winding, mut open, mut count) = (0i64, 0, 0);
    for (i, edge) in active.iter().enumerate() {
        let was_inside = is_inside::<NON_ZERO>(winding);
        winding += i64::from(edge.winding);
        let inside = is_inside::<NON_ZERO>(winding);
        open = if inside && !was_inside { i as u32 } else { open };
        runs[count] = Run { open, close: i as u32 };
        count += usize::from(was_inside && !inside);
    }
    runs[count] = Run { open, close: active.len() as u32 };
    count + usize::from(is_inside::<NON_ZERO>(winding))
}

/// Emits the runs of `tables` on each of `rows` (rows up to a vertex, so
/// every edge goes on over them) and steps the edges to the row after,
/// keeping them in order (and `planned`, the count of runs, with it) where
/// a few of them cross; returns that row, or an earlier one where the
/// order needs a full sort, and whether the edges are sorted there.
/// `tables.columns` are the edges' visible columns on the first row, and
/// the right border.
#[inline(always)]
fn rows_in_order<const NON_ZERO: bool, const CLIP: bool, E: Crossing, S: SpanSink + ?Sized>(
    rows: Range<i64>,
    tables: Tables<'_, E>,
    planned: &mut usize,
    target: Target,
    sink: &mut S,
) -> (i64, bool) {
    let Tables { active, columns, runs, .. } = tables;
    let mut row = rows.start;
    loop {
        for run in &runs[..*planned] {
            let (start, end) = (columns[run.open as usize], columns[run.close as usize]);
            if start < end {
                // `row` is a visible row, in `0..height`; `0 <= start < end <= width`.
                sink.span(row as i32, start, end, target.color);
            }
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
            if !tables::insertion_sort(active, columns) {
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

/// Emits the inside runs of `row` without sorting the crossings and steps
/// every edge to the next row: each crossing's winding is added at its
/// visible column in `windings` (`width + 1` of them), and the running sum
/// from the left is each pixel's winding number. `O(edges + width)` a
/// row; the runs are the maximal ones, left to right.
fn emit_by_columns<const NON_ZERO: bool, E: Crossing, S: SpanSink + ?Sized>(
    row: i64,
    active: &mut [Active<E>],
    edges: &[tables::Edge<E>],
    windings: &mut [i32],
    target: Target,
    sink: &mut S,
) {
    windings.fill(0);
    for chain in active {
        windings[visible_column(chain.stepper.column(), target.width) as usize] += i32::from(chain.winding);
        chain.advance(row + 1, edges);
    }
    // Which pixels are inside, 64 a word, without a branch per pixel; then
    // one step per change of state, where a run opens or closes.
    let (mut sum, mut inside, mut start) = (0i32, false, 0i64);
    for (word, chunk) in windings[..target.width as usize].chunks(64).enumerate() {
        let mut bits = 0u64;
        for (i, &winding) in chunk.iter().enumerate() {
            sum += winding;
            bits |= u64::from(is_inside::<NON_ZERO>(i64::from(sum))) << i;
        }
        // Bit `i` set where pixel `i` differs from the one before it.
        let mut changes = bits ^ (bits << 1 | u64::from(inside));
        if chunk.len() < 64 {
            changes &= (1 << chunk.len()) - 1;
        }
        while changes != 0 {
            let x = (word * 64) as i64 + i64::from(changes.trailing_zeros());
            if inside {
                emit(row, (start, x), target, sink);
            } else {
                start = x;
            }
            inside = !inside;
            changes &= changes - 1;
        }
    }
    if inside {
        emit(row, (start, i64::from(target.width)), target, sink);
    }
}

/// Emits a run of `row`, columns in `0..=width`, unless it is empty.
#[inline(always)]
fn emit<S: SpanSink + ?Sized>(row: i64, (start, end): (i64, i64), target: Target, sink: &mut S) {
    if start < end {
        // `row` is a visible row, in `0..height`; `0 <= start < end <= width`.
        sink.span(row as i32, start as i32, end as i32, target.color);
    }
}

/// Whether a winding sum (signed crossings left of a centre) means inside.
/// Every crossing is +1 or -1, so the sum's parity is the crossing count's.
#[inline(always)]
fn is_inside<const NON_ZERO: bool>(winding: i64) -> bool {
    if NON_ZERO {
        winding != 0
    } else {
        winding & 1 != 0
    }
}
