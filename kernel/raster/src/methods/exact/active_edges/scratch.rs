//! The heap's room for the general path's tables, for polygons with too
//! many edges for the tables it keeps on the stack: a [`Scratch`], which a
//! caller may keep from fill to fill
//! ([`fill_auto_with`](crate::fill_auto_with)), so that it allocates only
//! when a polygon needs more room than every one before it. Only such
//! polygons can have so many crossings on a row that they are better
//! counted per column than sorted ([`Wide`]). Feature `alloc`; a
//! [`FixedScratch`](super::FixedScratch) (`fixed.rs`) is the room without
//! a heap.

use alloc::vec::Vec;

use crate::methods::info::Refusal;

use super::super::edge::{EdgeStepper, ShortEdge};
use super::tables::{Active, Chain, Crossings, Edge, EdgeRoom, Run, Wide};

/// Room for `exact`'s general path, for polygons with too many edges for
/// the tables it keeps on the stack (over 256, or over 64 when their
/// edges may be 512 px or longer). A caller that keeps one from fill to
/// fill ([`fill_auto_with`](crate::fill_auto_with)) allocates only when a
/// polygon needs more room than every one before it; an empty one takes
/// nothing from the heap.
#[derive(Debug, Default)]
pub struct Scratch {
    pub(super) short: Room<ShortEdge>,
    pub(super) long: Room<EdgeStepper>,
    pub(super) shared: Shared,
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

/// Tables for `edges` edges of the kind `E` in its room `own` and the
/// `shared` tables of a scratch, grown to hold them if they must, with
/// room to sort or count their crossings on a target `width` wide.
#[allow(clippy::type_complexity)]
pub(super) fn tables<'s, E: Clone + Default>(
    own: &'s mut Room<E>,
    shared: &'s mut Shared,
    edges: usize,
    width: i32,
) -> Result<(EdgeRoom<'s, E>, Crossings<'s, E>), Refusal> {
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
    let table = EdgeRoom {
        edges: room(&mut own.edges, edges)?,
        chains: room(&mut shared.chains, edges)?,
        starts: room(&mut shared.starts, edges)?,
    };
    let crossings = Crossings {
        active: room(&mut own.active, edges)?,
        columns: room(&mut shared.columns, edges + 1)?,
        runs: room(&mut shared.runs, edges + 1)?,
        wide: Some(wide),
    };
    Ok((table, crossings))
}
