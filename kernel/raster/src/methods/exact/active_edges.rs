//! The exact method's general path: any number of contours, crossing or
//! not, under either fill rule. An edge table sorted by first scan line
//! feeds an active edge table (Black Book ch. 40's global and active edge
//! tables), kept sorted by crossing column; the directions summed from the
//! left decide which crossings open and close the runs the fill rule calls
//! inside, and each run is emitted as one whole span.
//!
//! The rows go in runs between events (an edge starting or ending): within
//! a run the active edges stay the same, and unless two of them cross their
//! order does too, and so does the part each plays (opening a run, closing
//! one, or neither). A row then costs one pass over the active edges that
//! emits, steps and checks the order at once; only a row where the order
//! changed sorts again and works the parts out again. A run of two edges
//! with the inside between them (most rows of most simple polygons) takes
//! the monotone path's two-edge loop instead. Where there is a crossing for
//! every four columns or more (scribbles of thousands of edges), keeping
//! them sorted costs more than summing their windings per column, which a
//! row then does instead (`emit_by_columns`).

use alloc::vec::Vec;

use crate::geometry::{FillRule, Point, Polygon};
use crate::method::Refusal;
use crate::sink::{Size, SpanSink};

use super::edge::{first_sample_at_or_after, visible_column, visible_rows, Crossing, EdgeStepper, ShortEdge};
use super::monotone::{columns_fit, span_rows};

/// Fills `polygon` by its fill rule. Refuses only when memory for the edge
/// tables cannot be had.
pub(crate) fn fill_active_edges<S: SpanSink + ?Sized>(
    polygon: &Polygon,
    size: Size,
    sink: &mut S,
) -> Result<(), Refusal> {
    let (mut edges, clip, short) = edge_table(polygon, size)?;
    edges.sort_unstable_by_key(|edge| edge.rows.start);
    if short {
        fill_table::<ShortEdge, _>(&edges, clip, polygon, size, sink)
    } else {
        fill_table::<EdgeStepper, _>(&edges, clip, polygon, size, sink)
    }
}

/// Fills the sorted edge table `edges` of `polygon`, its edges walked as `E`.
fn fill_table<E: Crossing, S: SpanSink + ?Sized>(
    edges: &[TableEdge],
    clip: bool,
    polygon: &Polygon,
    size: Size,
    sink: &mut S,
) -> Result<(), Refusal> {
    let mut active: Vec<ActiveEdge<E>> = Vec::new();
    active.try_reserve_exact(edges.len()).map_err(|_| Refusal::OutOfMemory)?;
    let mut sorter = Sorter::for_edges(edges.len(), size.width)?;
    let target = Target { color: polygon.color, width: size.width };
    let (active, sorter) = (&mut active, &mut sorter);
    match (polygon.rule, clip) {
        (FillRule::EvenOdd, false) => walk::<false, false, _, _>(edges, active, sorter, target, sink),
        (FillRule::EvenOdd, true) => walk::<false, true, _, _>(edges, active, sorter, target, sink),
        (FillRule::NonZero, false) => walk::<true, false, _, _>(edges, active, sorter, target, sink),
        (FillRule::NonZero, true) => walk::<true, true, _, _>(edges, active, sorter, target, sink),
    }
    Ok(())
}

/// What every span shares.
#[derive(Clone, Copy)]
struct Target {
    color: u8,
    width: i32,
}

/// Walks the rows of the edge table, top down. `NON_ZERO` picks the rule;
/// without `CLIP` every crossing column lies in the target's `0..=width`.
fn walk<const NON_ZERO: bool, const CLIP: bool, E: Crossing, S: SpanSink + ?Sized>(
    edges: &[TableEdge],
    active: &mut Vec<ActiveEdge<E>>,
    sorter: &mut Sorter<E>,
    target: Target,
    sink: &mut S,
) {
    let mut next = 0;
    let mut row = 0;
    loop {
        if active.is_empty() {
            // Nothing crosses the rows in between: go to the next edge's first.
            match edges.get(next) {
                Some(edge) => row = edge.rows.start,
                None => return,
            }
        }
        while let Some(edge) = edges.get(next).filter(|edge| edge.rows.start <= row) {
            let stepper = if edge.rows.end - row == 1 {
                E::at_last_row(edge.top, edge.bottom, row)
            } else {
                E::at_row(edge.top, edge.bottom, row)
            };
            active.push(ActiveEdge {
                stepper,
                // Visible rows end at the target's height, an `i32`.
                end_row: edge.rows.end as i32,
                winding: edge.winding,
                part: Part::Neither,
            });
            next += 1;
        }
        if sorter.tallies(active.len()) {
            // So many crossings for the width that summing them per column
            // is cheaper than keeping them sorted; and edges start and end
            // on most rows, so this goes a row at a time.
            emit_by_columns::<NON_ZERO, _, _>(row, active, &mut sorter.windings, target, sink);
            row += 1;
            continue;
        }
        // Every active edge meets `row` and every pending one starts below
        // it, so the run has at least this row.
        let starts = edges.get(next).map_or(i64::MAX, |edge| edge.rows.start);
        let run_end = active.iter().map(|edge| i64::from(edge.end_row)).fold(starts, i64::min);
        row = sorted_run::<NON_ZERO, CLIP, _, _>(row, run_end, active, sorter, target, sink);
        // Drop the edges that ended, keeping the order of the rest.
        let mut kept = 0;
        for i in 0..active.len() {
            if i64::from(active[i].end_row) > row {
                active[kept] = active[i];
                kept += 1;
            }
        }
        active.truncate(kept);
    }
}

/// Fills the rows `row..run_end`, over which no edge starts or ends, with
/// the crossings kept sorted; returns `run_end`.
fn sorted_run<const NON_ZERO: bool, const CLIP: bool, E: Crossing, S: SpanSink + ?Sized>(
    mut row: i64,
    run_end: i64,
    active: &mut Vec<ActiveEdge<E>>,
    sorter: &mut Sorter<E>,
    target: Target,
    sink: &mut S,
) -> i64 {
    sorter.sort(active, target.width);
    let mut open_at_end = assign_parts::<NON_ZERO, _>(active);
    if let ([a, b], false) = (active.as_mut_slice(), open_at_end) {
        // Two crossings, outside right of both: whatever their order
        // (they may cross), the inside is the span between them, as on
        // the monotone path.
        span_rows::<false, CLIP, _, _>(row..run_end, &mut a.stepper, &mut b.stepper, target.color, target.width, sink);
        row = run_end;
    }
    let mut sorted = true;
    while row < run_end {
        if !sorted {
            sorter.sort(active, target.width);
            open_at_end = assign_parts::<NON_ZERO, _>(active);
        }
        sorted = emit_and_step::<CLIP, _, _>(row, active, open_at_end, target, sink);
        row += 1;
    }
    row
}

/// Emits the inside runs of `row` without sorting the crossings, steps
/// every edge to the next row and drops the ones that end (out of order:
/// the sorted path sorts whatever it is given): each crossing's winding is
/// added at its visible column in `windings` (`width + 1` of them), and the
/// running sum from the left is each pixel's winding number.
/// `O(edges + width)` a row; the runs are the maximal ones, left to right,
/// as [`emit_and_step`]'s.
fn emit_by_columns<const NON_ZERO: bool, E: Crossing, S: SpanSink + ?Sized>(
    row: i64,
    active: &mut Vec<ActiveEdge<E>>,
    windings: &mut [i32],
    target: Target,
    sink: &mut S,
) {
    windings.fill(0);
    let mut i = 0;
    while let Some(edge) = active.get_mut(i) {
        windings[visible_column(edge.stepper.column(), target.width) as usize] += i32::from(edge.winding);
        if i64::from(edge.end_row) > row + 1 {
            edge.stepper.step();
            i += 1;
        } else {
            // The last edge takes its place and is seen next.
            active.swap_remove(i);
        }
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

/// An edge of the polygon, top to bottom, with the visible rows it meets.
struct TableEdge {
    top: Point,
    bottom: Point,
    /// +1 where the contour runs down the edge, -1 where it runs up.
    winding: i8,
    rows: core::ops::Range<i64>,
}

/// An edge crossing the current row.
#[derive(Clone, Copy)]
struct ActiveEdge<E> {
    stepper: E,
    end_row: i32,
    /// +1 or -1, as [`TableEdge::winding`].
    winding: i8,
    part: Part,
}

/// What a crossing does to the run of inside pixels, in the current order.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Part {
    /// Outside on its left, inside from it on.
    Opens,
    /// Inside on its left, outside from it on.
    Closes,
    /// Leaves the pixels on both sides alike.
    Neither,
}

/// Every edge that meets a visible row and can lie left of a visible pixel
/// centre, and whether some crossing column may lie outside the target's
/// `0..=width` (then columns are clamped), and whether every edge in it
/// may be a [`ShortEdge`]. Horizontal edges never meet a row; an edge whose
/// leftmost point is right of the last centre counts for no visible pixel.
fn edge_table(polygon: &Polygon, size: Size) -> Result<(Vec<TableEdge>, bool, bool), Refusal> {
    let mut edges = Vec::new();
    edges.try_reserve_exact(polygon.vertex_count()).map_err(|_| Refusal::OutOfMemory)?;
    let (mut min_x, mut max_x, mut min_y, mut max_y) = (i32::MAX, i32::MIN, i32::MAX, i32::MIN);
    for contour in &polygon.contours {
        let following = contour.iter().cycle().skip(1);
        for (&from, &to) in contour.iter().zip(following) {
            let (top, bottom, winding) = if from.y <= to.y { (from, to, 1) } else { (to, from, -1) };
            let rows = visible_rows(top.y, bottom.y, size.height);
            let leftmost_column = first_sample_at_or_after(top.x.min(bottom.x).into());
            if !rows.is_empty() && leftmost_column < i64::from(size.width) {
                edges.push(TableEdge { top, bottom, winding, rows });
                (min_x, max_x) = (min_x.min(top.x.min(bottom.x)), max_x.max(top.x.max(bottom.x)));
                (min_y, max_y) = (min_y.min(top.y), max_y.max(bottom.y));
            }
        }
    }
    Ok((edges, !columns_fit(min_x, max_x, size.width), ShortEdge::fits((min_x, max_x), (min_y, max_y))))
}

/// Sorts the active edges by visible column (the column clamped to the
/// target, see [`visible_column`]). That is the order the inside test
/// needs: the crossings at or left of a visible pixel are a prefix of it.
///
/// The list comes sorted but for edges that just started or crossed, so a
/// short one takes an insertion sort, about one pass and no call. A long
/// one, where many edges may cross at once (insertion sort would go
/// quadratic, as the book's bubble sort does in ch. 40), is counted into
/// place when the target is narrow next to the edge count (`O(n + width)`),
/// and otherwise sorted in `O(n log n)` by 64-bit keys, visible column
/// above index, then moved into that order once: cheaper than sorting the
/// edges themselves, three to six times larger.
struct Sorter<E> {
    /// Per visible column, edges at it, then where the next of them goes.
    counts: Vec<u32>,
    /// Per visible column, the windings of the crossings at it, for rows
    /// with so many crossings that they are summed rather than sorted.
    windings: Vec<i32>,
    keys: Vec<u64>,
    scratch: Vec<ActiveEdge<E>>,
}

/// A table of `columns` zeros, or a refusal when memory cannot be had.
fn per_column<T: Default + Clone>(columns: usize) -> Result<Vec<T>, Refusal> {
    let mut table = Vec::new();
    table.try_reserve_exact(columns).map_err(|_| Refusal::OutOfMemory)?;
    table.resize(columns, T::default());
    Ok(table)
}

/// The longest active list sorted by insertion.
const SHORT: usize = 16;

impl<E: Crossing> Sorter<E> {
    /// Room for `edges` active edges on a target `width` wide, so that
    /// sorting never allocates: a count per visible column when there are
    /// at most four per edge, or a key per edge.
    fn for_edges(edges: usize, width: i32) -> Result<Self, Refusal> {
        let (mut counts, mut windings, mut keys, mut scratch) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        // Every winding sum stays within `±edges`, an `i32`.
        if edges > SHORT && i32::try_from(edges).is_ok() {
            scratch.try_reserve_exact(edges).map_err(|_| Refusal::OutOfMemory)?;
            let columns = width.max(0) as usize + 1;
            if columns / 4 <= edges {
                (counts, windings) = (per_column(columns)?, per_column(columns)?);
            } else {
                keys.try_reserve_exact(edges).map_err(|_| Refusal::OutOfMemory)?;
            }
        }
        Ok(Self { counts, windings, keys, scratch })
    }

    /// Whether a run of `active` crossings is cheaper summed per column
    /// ([`emit_by_columns`]) than kept sorted: where there are per-column
    /// tables and at least a crossing for every four columns.
    fn tallies(&self, active: usize) -> bool {
        !self.windings.is_empty() && self.windings.len() / 4 <= active
    }

    fn sort(&mut self, active: &mut Vec<ActiveEdge<E>>, width: i32) {
        let column = |edge: &ActiveEdge<E>| visible_column(edge.stepper.column(), width) as usize;
        if active.len() <= SHORT {
            // By the unclamped column: that order is also by the clamped one.
            for i in 1..active.len() {
                let mut j = i;
                while j > 0 && active[j - 1].stepper.column() > active[j].stepper.column() {
                    active.swap(j - 1, j);
                    j -= 1;
                }
            }
            return;
        }
        // Room was made for every edge and fewer than 2^32 of them (else
        // neither buffer has room and the library sort takes over), so
        // nothing below allocates and every count and index fits a `u32`.
        if active.len() > self.scratch.capacity() {
            active.sort_unstable_by_key(column);
        } else if !self.counts.is_empty() {
            self.counts.fill(0);
            for edge in active.iter() {
                self.counts[column(edge)] += 1;
            }
            let mut next = 0;
            for count in &mut self.counts {
                (*count, next) = (next, next + *count);
            }
            self.scratch.clear();
            self.scratch.extend_from_slice(active);
            for edge in active.iter() {
                let slot = &mut self.counts[column(edge)];
                self.scratch[*slot as usize] = *edge;
                *slot += 1;
            }
            core::mem::swap(active, &mut self.scratch);
        } else {
            // Visible columns are below 2^31 and indices below 2^32.
            self.keys.clear();
            self.keys.extend(active.iter().enumerate().map(|(i, edge)| (column(edge) as u64) << 32 | i as u64));
            self.keys.sort_unstable();
            self.scratch.clear();
            self.scratch.extend(self.keys.iter().map(|&key| active[(key & u64::from(u32::MAX)) as usize]));
            core::mem::swap(active, &mut self.scratch);
        }
    }
}

/// Works out each crossing's [`Part`] in the current order: the winding
/// sum of the crossings before it and up to it, under the rule. A pixel's
/// inside test sums every crossing at or left of it; where several share
/// a column, the states between them cover no pixel, so any order of
/// theirs gives the same pixels. Returns whether the pixels right of the
/// last crossing are inside (edges right of the target are not in the
/// table, so the sum need not come back to zero).
fn assign_parts<const NON_ZERO: bool, E>(active: &mut [ActiveEdge<E>]) -> bool {
    // Each crossing adds +1 or -1: no `i64` overflow for any edge count.
    let mut winding = 0i64;
    for edge in active {
        let was_inside = is_inside::<NON_ZERO>(winding);
        winding += i64::from(edge.winding);
        edge.part = match (was_inside, is_inside::<NON_ZERO>(winding)) {
            (false, true) => Part::Opens,
            (true, false) => Part::Closes,
            _ => Part::Neither,
        };
    }
    is_inside::<NON_ZERO>(winding)
}

/// Emits the inside runs of `row` and steps every edge to the next row.
/// Returns whether the visible columns are still in order there.
///
/// Runs that touch (one closes at the column where the next opens) are
/// emitted as one span, so no pixel is emitted twice and the spans are the
/// maximal runs. A run still open after the last crossing (`open_at_end`)
/// reaches the right border. Columns are clamped to the target, which
/// changes no visible pixel's inside test.
#[inline(always)]
fn emit_and_step<const CLIP: bool, E: Crossing, S: SpanSink + ?Sized>(
    row: i64,
    active: &mut [ActiveEdge<E>],
    open_at_end: bool,
    target: Target,
    sink: &mut S,
) -> bool {
    let width = i64::from(target.width);
    // The open run's start, and the run waiting to be emitted: the next one
    // may touch it. `-1`, left of every visible column, stands for none.
    let (mut start, mut pending) = (0, (-1, -1));
    let (mut sorted, mut previous) = (true, 0);
    // Without `CLIP`, columns lie in `0..=width` already.
    let visible = |column: i64| if CLIP { column.clamp(0, width) } else { column };
    for edge in active.iter_mut() {
        let column = visible(edge.stepper.column());
        match edge.part {
            Part::Opens => start = column,
            Part::Closes if pending.1 == start => pending.1 = column,
            Part::Closes => {
                emit(row, pending, target, sink);
                pending = (start, column);
            }
            Part::Neither => {}
        }
        edge.stepper.step();
        let next = visible(edge.stepper.column());
        sorted &= previous <= next;
        previous = next;
    }
    if open_at_end {
        if pending.1 == start {
            pending.1 = width;
        } else {
            emit(row, pending, target, sink);
            pending = (start, width);
        }
    }
    emit(row, pending, target, sink);
    sorted
}

/// Emits a run of `row`, columns in `-1..=width`, unless it is empty.
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
