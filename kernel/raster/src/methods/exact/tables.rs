//! Where the general path keeps its tables, and how it builds and sorts
//! them.
//!
//! A polygon of up to 256 edges (64 when its edges may be 512 px or
//! longer) keeps them on the stack, in arrays sized to its class of 8, 16,
//! 32, 64, 128 or 256 edges, so that filling it takes nothing from the heap
//! and clears no more than twice the room it needs. A larger polygon takes
//! them from a [`Scratch`], which a caller may keep from fill to fill
//! ([`fill_auto_with`](super::fill_auto_with)): it allocates only when a
//! polygon needs more room than every one before it. Only such polygons
//! can have so many crossings on a row that they are better counted per
//! column than sorted ([`Wide`]).

use alloc::vec::Vec;
use core::mem::size_of;
use core::ops::Range;

use crate::geometry::Polygon;
use crate::method::Refusal;
use crate::sink::Size;

use super::edge::{first_sample_at_or_after, visible_column, visible_rows, Crossing, EdgeStepper, ShortEdge};

/// An edge of the table: its stepper on its first visible row, and the
/// row below its last (visible rows are in `0..height`, an `i32`).
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Edge<E> {
    stepper: E,
    end_row: i32,
}

/// A chain: edges of one contour, one after the other, going one way in y
/// and meeting one run of rows between them, each the next one's
/// successor on the row where it ends. Its edges are `first..end` of the
/// table, top to bottom.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Chain {
    first: u32,
    end: u32,
    /// The chain's first row and the row below its last.
    start_row: i32,
    end_row: i32,
    /// +1 where the contour runs down the chain, -1 where it runs up.
    winding: i8,
}

/// A chain crossing the current row, at one of its edges.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Active<E> {
    /// The current edge's stepper, on the current row.
    pub stepper: E,
    /// The row below the current edge.
    end_row: i32,
    /// The row below the chain.
    pub chain_end_row: i32,
    /// The next edge of the chain in the table, and the end of its edges.
    next: u32,
    end: u32,
    pub winding: i8,
}

impl<E: Crossing> Active<E> {
    /// Moves to scan line `row`, the one after the current: steps the
    /// current edge, or takes the chain's next edge where the current one
    /// ends. At the chain's end it stays as it is, to leave.
    #[inline(always)]
    pub fn advance(&mut self, row: i64, edges: &[Edge<E>]) {
        if i64::from(self.end_row) != row {
            self.stepper.step();
        } else if self.next < self.end {
            let edge = edges[self.next as usize];
            (self.stepper, self.end_row, self.next) = (edge.stepper, edge.end_row, self.next + 1);
        }
    }

    /// After a run of steps that reached `row`: takes the chain's next
    /// edge if the current one ended there (the last step went past it).
    #[inline(always)]
    pub fn resume(&mut self, row: i64, edges: &[Edge<E>]) {
        if i64::from(self.end_row) == row && self.next < self.end {
            let edge = edges[self.next as usize];
            (self.stepper, self.end_row, self.next) = (edge.stepper, edge.end_row, self.next + 1);
        }
    }

    /// The row where the current edge ends and the chain goes on with its
    /// next, or the chain ends.
    #[inline(always)]
    pub fn edge_end_row(&self) -> i64 {
        self.end_row.into()
    }
}

/// An inside run of a row, by places in the sorted active chains: its
/// pixels start at the column of the crossing at `open` and end before the
/// one at `close`; a `close` of the active chain count stands for the
/// right border.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(super) struct Run {
    pub open: u32,
    pub close: u32,
}

/// The tables of one fill, each with room for every edge of the polygon
/// (and one more place in `columns` and `runs`).
pub(super) struct Tables<'a, E> {
    /// The edge table, chain by chain.
    pub edges: &'a mut [Edge<E>],
    pub chains: &'a mut [Chain],
    /// The order chains join in: per chain, its first row above its index
    /// ([`start_key`]), sorted.
    pub starts: &'a mut [u64],
    /// The chains crossing the current row.
    pub active: &'a mut [Active<E>],
    /// Their visible columns on the current row, and one more place for
    /// the right border.
    pub columns: &'a mut [i32],
    /// The inside runs of the current order, and one more place.
    pub runs: &'a mut [Run],
    /// Room to sort or count very many crossings, for large polygons.
    pub wide: Option<Wide<'a, E>>,
}

/// A sort key: a first visible row (in `0..height`, so below 2^31) above
/// an index.
fn start_key(row: i32, index: usize) -> u64 {
    (row as u64) << 32 | index as u64
}

/// The first row in the [`start_key`] `key`.
pub(super) fn start_row(key: u64) -> i64 {
    (key >> 32) as i64
}

/// The index in the [`start_key`] `key`.
fn start_index(key: u64) -> usize {
    (key & u64::from(u32::MAX)) as usize
}

/// The chain `key` names ([`start_key`]), at its first edge.
pub(super) fn join<E: Crossing>(key: u64, chains: &[Chain], edges: &[Edge<E>]) -> Active<E> {
    let chain = chains[start_index(key)];
    let first = edges[chain.first as usize];
    Active {
        stepper: first.stepper,
        end_row: first.end_row,
        chain_end_row: chain.end_row,
        next: chain.first + 1,
        end: chain.end,
        winding: chain.winding,
    }
}

/// Builds the edge table of `polygon` into `tables`, and returns how many
/// chains it makes: every edge that meets a visible row and can lie left
/// of a visible pixel centre (horizontal edges never meet a row; an edge
/// whose leftmost point is right of the last centre counts for no visible
/// pixel), its stepper set up on its first visible row, so that the
/// setups' divisions do not wait for each other; the chains they make;
/// and the order the chains join in.
///
/// A chain breaks where the direction changes or the rows do not follow
/// on. Each contour is walked from its top vertex, where a chain breaks,
/// so that no chain runs over the contour's end (breaking a chain
/// anywhere else too would only cost the walk an event).
pub(super) fn build<E: Crossing>(polygon: &Polygon, size: Size, tables: &mut Tables<'_, E>) -> usize {
    let (mut edges, mut chains) = (0, 0);
    for contour in &polygon.contours {
        let Some(top) = contour.iter().enumerate().min_by_key(|(_, p)| p.y).map(|(i, _)| i) else { continue };
        let (mut from, mut last) = (contour[top], None::<(i8, Range<i64>)>);
        for &to in contour[top + 1..].iter().chain(&contour[..=top]) {
            let (upper, lower, winding) = if from.y <= to.y { (from, to, 1) } else { (to, from, -1) };
            from = to;
            let rows = visible_rows(upper.y, lower.y, size.height);
            if rows.is_empty() || first_sample_at_or_after(upper.x.min(lower.x).into()) >= i64::from(size.width) {
                continue;
            }
            let stepper = if rows.end - rows.start == 1 {
                E::at_last_row(upper, lower, rows.start)
            } else {
                E::at_row(upper, lower, rows.start)
            };
            // Visible rows are in `0..height`, `i32`s.
            let (start_row, end_row) = (rows.start as i32, rows.end as i32);
            tables.edges[edges] = Edge { stepper, end_row };
            // Down a chain each edge starts where the last ended; up one
            // (built bottom up) each ends where the last started.
            let follows = last.as_ref().is_some_and(|(w, last)| {
                *w == winding && if winding > 0 { last.end == rows.start } else { rows.end == last.start }
            });
            if follows {
                let chain = &mut tables.chains[chains - 1];
                chain.end += 1;
                (chain.start_row, chain.end_row) = (chain.start_row.min(start_row), chain.end_row.max(end_row));
            } else {
                if last.is_some() {
                    close_chain(tables, chains);
                }
                tables.chains[chains] =
                    Chain { first: edges as u32, end: edges as u32 + 1, start_row, end_row, winding };
                chains += 1;
            }
            last = Some((winding, rows));
            edges += 1;
        }
        if last.is_some() {
            close_chain(tables, chains);
        }
    }
    for (i, (start, chain)) in tables.starts.iter_mut().zip(&tables.chains[..chains]).enumerate() {
        *start = start_key(chain.start_row, i);
    }
    tables.starts[..chains].sort_unstable();
    chains
}

/// Puts the edges of the last of the first `chains` chains, which is
/// complete, top to bottom: an upward chain is built bottom up.
fn close_chain<E>(tables: &mut Tables<'_, E>, chains: usize) {
    let chain = tables.chains[chains - 1];
    if chain.winding < 0 {
        tables.edges[chain.first as usize..chain.end as usize].reverse();
    }
}

/// Runs `fill` on tables for `edges` edges: on the stack when they fit
/// ([`on_stack`]), else in `scratch` (a new one when there is none).
pub(super) fn with_tables<E: Stepper, R>(
    edges: usize,
    width: i32,
    scratch: Option<&mut Scratch>,
    fill: impl FnOnce(Tables<'_, E>) -> R,
) -> Result<R, Refusal> {
    // The wide stepper's tables are three times the size: fewer fit.
    let most = if size_of::<E>() <= size_of::<ShortEdge>() { 256 } else { 64 };
    Ok(match edges {
        0..=8 => on_stack::<8, E, _>(fill),
        9..=16 => on_stack::<16, E, _>(fill),
        17..=32 => on_stack::<32, E, _>(fill),
        33..=64 => on_stack::<64, E, _>(fill),
        _ if edges <= most.min(128) => on_stack::<128, E, _>(fill),
        _ if edges <= most => on_stack::<256, E, _>(fill),
        _ => E::in_scratch(scratch.unwrap_or(&mut Scratch::new()), edges, width, fill)?,
    })
}

/// Runs `fill` on cleared tables for up to `N` edges, on the stack (one
/// more place in the last two). Each is a local of its own, cleared in
/// place: built as fields of one value, the tables of the larger classes
/// were cleared, then copied into it. Never inlined, so that the caller's
/// frame holds only the class of tables it uses.
#[inline(never)]
fn on_stack<const N: usize, E: Crossing, R>(fill: impl FnOnce(Tables<'_, E>) -> R) -> R {
    let mut edges = [Edge::<E>::default(); N];
    let mut chains = [Chain::default(); N];
    let mut starts = [0; N];
    let mut active = [Active::<E>::default(); N];
    let mut runs = [[Run::default(); N]; 2];
    let mut columns = [[0; N]; 2];
    fill(Tables {
        edges: &mut edges,
        chains: &mut chains,
        starts: &mut starts,
        active: &mut active,
        columns: &mut columns.as_flattened_mut()[..=N],
        runs: &mut runs.as_flattened_mut()[..=N],
        wide: None,
    })
}

/// Room for `exact`'s general path, for polygons with too many edges for
/// the tables it keeps on the stack (over 256, or over 64 when their
/// edges may be 512 px or longer). A caller that keeps one from fill to
/// fill ([`fill_auto_with`](super::fill_auto_with)) allocates only when a
/// polygon needs more room than every one before it; an empty one takes
/// nothing from the heap.
#[derive(Debug, Default)]
pub struct Scratch {
    short: Room<ShortEdge>,
    long: Room<EdgeStepper>,
    shared: Shared,
}

impl Scratch {
    /// An empty scratch, which takes nothing from the heap until it is used.
    pub const fn new() -> Self {
        Self { short: Room::new(), long: Room::new(), shared: Shared::new() }
    }
}

/// A [`Scratch`]'s tables of one kind of edge.
#[derive(Debug, Default)]
pub(super) struct Room<E> {
    edges: Vec<Edge<E>>,
    active: Vec<Active<E>>,
    spare: Vec<Active<E>>,
}

impl<E> Room<E> {
    const fn new() -> Self {
        Self { edges: Vec::new(), active: Vec::new(), spare: Vec::new() }
    }
}

/// A [`Scratch`]'s tables for either kind of edge.
#[derive(Debug, Default)]
pub(super) struct Shared {
    chains: Vec<Chain>,
    starts: Vec<u64>,
    columns: Vec<i32>,
    runs: Vec<Run>,
    counts: Vec<u32>,
    windings: Vec<i32>,
    keys: Vec<u64>,
}

impl Shared {
    const fn new() -> Self {
        Self {
            chains: Vec::new(),
            starts: Vec::new(),
            columns: Vec::new(),
            runs: Vec::new(),
            counts: Vec::new(),
            windings: Vec::new(),
            keys: Vec::new(),
        }
    }
}

/// The first `len` places of `table`, grown to hold them if it must; a
/// refusal when memory cannot be had.
fn room<T: Clone + Default>(table: &mut Vec<T>, len: usize) -> Result<&mut [T], Refusal> {
    if table.len() < len {
        table.try_reserve(len - table.len()).map_err(|_| Refusal::OutOfMemory)?;
        table.resize(len, T::default());
    }
    Ok(&mut table[..len])
}

/// Insertion sorts may move edges past each other four times this often
/// however few they are.
const SHORT: usize = 16;

/// An edge stepper with its own room in a [`Scratch`].
pub(super) trait Stepper: Crossing {
    fn room(scratch: &mut Scratch) -> (&mut Room<Self>, &mut Shared);

    /// Runs `fill` on tables for `edges` edges in `scratch`, with room to
    /// sort or count their crossings on a target `width` wide.
    fn in_scratch<R>(
        scratch: &mut Scratch,
        edges: usize,
        width: i32,
        fill: impl FnOnce(Tables<'_, Self>) -> R,
    ) -> Result<R, Refusal> {
        let (own, shared) = Self::room(scratch);
        // Counted per column when there are at most four columns per edge;
        // every winding sum stays within `±edges`, an `i32`.
        let columns = width.max(0) as usize + 1;
        let per_column = columns / 4 <= edges && i32::try_from(edges).is_ok();
        let wide = Wide {
            counts: room(&mut shared.counts, if per_column { columns } else { 0 })?,
            windings: room(&mut shared.windings, if per_column { columns } else { 0 })?,
            keys: room(&mut shared.keys, if per_column { 0 } else { edges })?,
            spare: room(&mut own.spare, edges)?,
        };
        Ok(fill(Tables {
            edges: room(&mut own.edges, edges)?,
            chains: room(&mut shared.chains, edges)?,
            starts: room(&mut shared.starts, edges)?,
            active: room(&mut own.active, edges)?,
            columns: room(&mut shared.columns, edges + 1)?,
            runs: room(&mut shared.runs, edges + 1)?,
            wide: Some(wide),
        }))
    }
}

impl Stepper for ShortEdge {
    fn room(scratch: &mut Scratch) -> (&mut Room<Self>, &mut Shared) {
        (&mut scratch.short, &mut scratch.shared)
    }
}

impl Stepper for EdgeStepper {
    fn room(scratch: &mut Scratch) -> (&mut Room<Self>, &mut Shared) {
        (&mut scratch.long, &mut scratch.shared)
    }
}

/// Room to sort very many active edges in linear time, or to count their
/// windings per column.
pub(super) struct Wide<'a, E> {
    /// Per visible column, edges at it, then where the next of them goes.
    counts: &'a mut [u32],
    /// Per visible column, the windings of the crossings at it, for rows
    /// with so many crossings that they are summed rather than sorted.
    pub windings: &'a mut [i32],
    keys: &'a mut [u64],
    spare: &'a mut [Active<E>],
}

impl<E: Crossing> Wide<'_, E> {
    /// Whether a row of `active` crossings is cheaper summed per column
    /// than kept sorted: where there are per-column tables and at least a
    /// crossing for every four columns.
    pub fn tallies(&self, active: usize) -> bool {
        !self.windings.is_empty() && self.windings.len() / 4 <= active
    }

    /// Sorts `active` by visible column, in `O(n + width)` by counting
    /// where the target is narrow next to the edge count, else in
    /// `O(n log n)` by 64-bit keys (visible column above index), then
    /// moved into that order once: cheaper than sorting the edges
    /// themselves, which are larger.
    fn sort(&mut self, active: &mut [Active<E>], width: i32) {
        let column = |edge: &Active<E>| visible_column(edge.stepper.column(), width) as usize;
        let spare = &mut self.spare[..active.len()];
        if !self.counts.is_empty() {
            self.counts.fill(0);
            for edge in active.iter() {
                self.counts[column(edge)] += 1;
            }
            let mut next = 0;
            for count in self.counts.iter_mut() {
                (*count, next) = (next, next + *count);
            }
            for edge in active.iter() {
                let slot = &mut self.counts[column(edge)];
                spare[*slot as usize] = *edge;
                *slot += 1;
            }
        } else {
            // Visible columns are below 2^31 and indices below 2^32.
            let keys = &mut self.keys[..active.len()];
            for (i, (key, edge)) in keys.iter_mut().zip(active.iter()).enumerate() {
                *key = (column(edge) as u64) << 32 | i as u64;
            }
            keys.sort_unstable();
            for (edge, &key) in spare.iter_mut().zip(keys.iter()) {
                *edge = active[start_index(key)];
            }
        }
        active.copy_from_slice(spare);
    }
}

/// Sorts `active` by visible column and sets `columns` to them: by
/// insertion when the list is short or out of order in a few places (it
/// comes sorted but for edges that just joined or crossed), else in
/// `wide` when there is one, else by the library's in-place sort. That is
/// the order the inside test needs: the crossings at or left of a visible
/// pixel are a prefix of it.
pub(super) fn sort<E: Crossing>(
    active: &mut [Active<E>],
    columns: &mut [i32],
    width: i32,
    wide: Option<&mut Wide<'_, E>>,
) {
    let column = |edge: &Active<E>| visible_column(edge.stepper.column(), width);
    for (slot, edge) in columns.iter_mut().zip(active.iter()) {
        *slot = column(edge);
    }
    if !insertion_sort(active, columns) {
        match wide {
            Some(wide) => wide.sort(active, width),
            None => active.sort_unstable_by_key(column),
        }
        for (slot, edge) in columns.iter_mut().zip(active.iter()) {
            *slot = column(edge);
        }
    }
}

/// Sorts `active` by `columns` (moving both), then by position
/// ([`Crossing::position_in`]), by insertion, unless that
/// takes moving edges past each other more often than four times per edge
/// (quadratic is near when many cross): then it stops, with both in some
/// order, and returns `false`.
#[inline(always)]
pub(super) fn insertion_sort<E: Crossing>(active: &mut [Active<E>], columns: &mut [i32]) -> bool {
    // Crossings in one column go by position where the stepper has one, so
    // that the order is the positions' (`active_edges::pairs_hold`).
    let key = |chain: &Active<E>, column: i32| (column, chain.stepper.position_in(0));
    let mut budget = 4 * active.len().max(SHORT);
    for i in 1..active.len().min(columns.len()) {
        let mut j = i;
        while j > 0 && key(&active[j - 1], columns[j - 1]) > key(&active[j], columns[j]) {
            if budget == 0 {
                return false;
            }
            columns.swap(j - 1, j);
            active.swap(j - 1, j);
            (j, budget) = (j - 1, budget - 1);
        }
    }
    true
}
