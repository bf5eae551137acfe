//! The general path's tables, as data: the edge table that `build.rs`
//! fills and `walk.rs` reads, and the crossing tables the walk works in.
//! Where they live (the stack or a [`Scratch`](super::Scratch)) is the
//! driver's choice (`mod.rs`, `scratch.rs`); nothing here allocates, sorts
//! or emits.

use super::super::edge::Crossing;

/// An edge of the table: its stepper on its first visible row, and the
/// row below its last (visible rows are in `0..height`, an `i32`).
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Edge<E> {
    pub stepper: E,
    pub end_row: i32,
}

/// A chain: edges of one contour, one after the other, going one way in y
/// and meeting one run of rows between them, each the next one's
/// successor on the row where it ends. Its edges are `first..end` of the
/// table, top to bottom.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Chain {
    pub first: u32,
    pub end: u32,
    /// The chain's first row and the row below its last.
    pub start_row: i32,
    pub end_row: i32,
    /// +1 where the contour runs down the chain, -1 where it runs up.
    pub winding: i8,
}

/// Room for the edge table of one fill: a place for every edge of the
/// polygon in each.
pub(super) struct EdgeRoom<'a, E> {
    pub edges: &'a mut [Edge<E>],
    pub chains: &'a mut [Chain],
    pub starts: &'a mut [u64],
}

/// The edge table, built: every visible edge, chain by chain, and the
/// order the chains join the walk in.
pub(super) struct EdgeTable<'a, E> {
    pub edges: &'a [Edge<E>],
    pub chains: &'a [Chain],
    /// Per chain, its first row above its index ([`start_key`]), sorted.
    pub starts: &'a [u64],
}

impl<E: Copy> EdgeTable<'_, E> {
    /// The chain `key` names ([`start_key`]), at its first edge.
    pub fn join(&self, key: u64) -> Active<E> {
        let chain = self.chains[start_index(key)];
        let first = self.edges[chain.first as usize];
        Active {
            stepper: first.stepper,
            end_row: first.end_row,
            chain_end_row: chain.end_row,
            next: chain.first + 1,
            end: chain.end,
            winding: chain.winding,
        }
    }
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

/// The walk's working tables, a place for every edge in each (and one
/// more in `columns` and `runs`).
pub(super) struct Crossings<'a, E> {
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

/// Room to sort very many active edges in linear time, or to count their
/// windings per column (`order.rs`, `columns.rs`).
pub(super) struct Wide<'a, E> {
    /// Per visible column, edges at it, then where the next of them goes;
    /// empty where the target is too wide for the edge count.
    pub counts: &'a mut [u32],
    /// Per visible column, the windings of the crossings at it, for rows
    /// with so many crossings that they are summed rather than sorted;
    /// empty with `counts`.
    pub windings: &'a mut [i32],
    /// Sort keys, where there are no per-column tables.
    pub keys: &'a mut [u64],
    /// Where the sorted edges are put before they are copied back.
    pub spare: &'a mut [Active<E>],
}

impl<E> Wide<'_, E> {
    /// Whether a row of `active` crossings is cheaper summed per column
    /// than kept sorted: where there are per-column tables and at least a
    /// crossing for every four columns.
    pub fn tallies(&self, active: usize) -> bool {
        !self.windings.is_empty() && self.windings.len() / 4 <= active
    }
}

/// A sort key: a row or column (in `0..=height` or `0..=width`, so below
/// 2^31) above an index.
pub(super) fn start_key(row: i32, index: usize) -> u64 {
    (row as u64) << 32 | index as u64
}

/// The row (or column) in the [`start_key`] `key`.
pub(super) fn start_row(key: u64) -> i64 {
    (key >> 32) as i64
}

/// The index in the [`start_key`] `key`.
pub(super) fn start_index(key: u64) -> usize {
    (key & u64::from(u32::MAX)) as usize
}
