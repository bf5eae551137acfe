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
            (row, settled) = if let ([a, b], [Run { open: 0, close: 1 }]) = (&mut active[..k], &runs[..planned]) {
                two_chains::<CLIP, _, _>(row..end, [a, b], edges, target, sink);
                columns[0] = visible::<CLIP>(a.stepper.column(), target.width);
                columns[1] = visible::<CLIP>(b.stepper.column(), target.width);
                (end, columns[0] <= columns[1])
            } else {
                let tables = Tables {
                    edges: &mut [],
                    chains: &mut [],
                    starts: &mut [],
                    active: &mut active[..k],
                    columns: &mut columns[..=k],
                    runs,
                    wide: None,
                };
                rows_in_order::<NON_ZERO, CLIP, _, _>(row..end, tables, edges, &mut planned, target, sink)
            };
        }
    }
}

/// Two chains with the inside between them, outside right of both, over
/// `rows`: whatever their order (they may cross), the inside is the span
/// between them, as on the monotone path, and rows go in runs between
/// their vertices, where each chain takes its next edge.
#[inline(always)]
fn two_chains<const CLIP: bool, E: Crossing, S: SpanSink + ?Sized>(
    rows: core::ops::Range<i64>,
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

/// Emits the runs of `tables` on each of `rows` and steps the edges,
/// keeping them in order (and `planned`, the count of runs, with it) where
/// a few of them cross, until the rows end or until the order needs a
/// full sort; returns that row and whether the edges are in order there.
/// `tables.columns` are the edges' visible columns on the first row, and
/// the right border.
#[inline(always)]
fn rows_in_order<const NON_ZERO: bool, const CLIP: bool, E: Crossing, S: SpanSink + ?Sized>(
    rows: core::ops::Range<i64>,
    tables: Tables<'_, E>,
    edges: &[tables::Edge<E>],
    planned: &mut usize,
    target: Target,
    sink: &mut S,
) -> (i64, bool) {
    let Tables { active, columns, runs, .. } = tables;
    let (mut row, mut vertex_row) = (rows.start, next_vertex_row(active));
    loop {
        for run in &runs[..*planned] {
            let (start, end) = (columns[run.open as usize], columns[run.close as usize]);
            if start < end {
                // `row` is a visible row, in `0..height`; `0 <= start < end <= width`.
                sink.span(row as i32, start, end, target.color);
            }
        }
        row += 1;
        // Only a row where some edge ends needs the test for each edge.
        if row == vertex_row {
            for chain in active.iter_mut() {
                chain.advance(row, edges);
            }
            vertex_row = next_vertex_row(active);
        } else {
            for chain in active.iter_mut() {
                chain.stepper.step();
            }
        }
        // Visible columns are never negative.
        let (mut in_order, mut previous) = (true, 0);
        let columns_now = &mut columns[..active.len()];
        for (chain, column) in active.iter().zip(columns_now.iter_mut()) {
            *column = visible::<CLIP>(chain.stepper.column(), target.width);
            in_order &= previous <= *column;
            previous = *column;
        }
        if row == rows.end {
            return (row, in_order);
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
            vertex_row = next_vertex_row(active);
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
