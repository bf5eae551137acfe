//! Room for the general path's tables without a heap: a [`FixedScratch`]
//! of a capacity chosen at compile time, which the caller keeps wherever
//! it likes and lends to a fill
//! ([`fill_auto_with`](crate::fill_auto_with)). A polygon of more edges
//! than it holds is refused ([`Refusal::TooManyVertices`]), never drawn in
//! part.

use crate::methods::info::Refusal;

use super::super::edge::{EdgeStepper, ShortEdge};
use super::tables::{Active, Chain, Crossings, Edge, EdgeRoom, Run};

/// Room for `exact`'s general path for polygons of up to `EDGES` edges
/// (vertices, over all contours), with no allocator: the tables on the
/// stack hold up to 256 edges (64 when they may be 512 px or longer), and
/// a polygon of more takes its tables from here. It holds both kinds of
/// edge's tables, so its size is fixed whatever the polygon;
/// [`FixedScratch::BYTES_PER_EDGE`] says how large it is.
///
/// ```
/// use raster::{fill_auto_with, FillRule, FixedScratch, Point, PolygonRef, Refusal, Size, SpanSink};
///
/// struct Count(i32);
/// impl SpanSink for Count {
///     fn size(&self) -> Size {
///         Size { width: 320, height: 200 }
///     }
///     fn span(&mut self, _y: i32, x_start: i32, x_end: i32, _color: u8) {
///         self.0 += x_end - x_start;
///     }
/// }
///
/// // A comb of 100 teeth 1 px wide under a bar 50 px deep: 400 edges,
/// // more than the stack's tables hold (and, under the non-zero rule, than
/// // the edge flags take).
/// let mut comb = [Point::default(); 400];
/// comb[..2].copy_from_slice(&[Point::from_pixels(0, 0), Point::from_pixels(199, 0)]);
/// let mut at = 2;
/// for tooth in (0..100).rev() {
///     let x = 2 * tooth;
///     comb[at..at + 2].copy_from_slice(&[Point::from_pixels(x + 1, 100), Point::from_pixels(x, 100)]);
///     at += 2;
///     if tooth > 0 {
///         comb[at..at + 2].copy_from_slice(&[Point::from_pixels(x, 50), Point::from_pixels(x - 1, 50)]);
///         at += 2;
///     }
/// }
/// let comb = PolygonRef { contours: &[comb], color: 1, rule: FillRule::NonZero };
/// let mut scratch = FixedScratch::<400>::new();
/// let mut drawn = Count(0);
/// fill_auto_with(comb, &mut drawn, &mut scratch).unwrap();
/// assert_eq!(drawn.0, 199 * 50 + 100 * 50);
/// // One edge too small for it: refused, nothing drawn.
/// let (mut small, mut refused) = (FixedScratch::<399>::new(), Count(0));
/// assert_eq!(fill_auto_with(comb, &mut refused, &mut small), Err(Refusal::TooManyVertices));
/// assert_eq!(refused.0, 0);
/// ```
pub struct FixedScratch<const EDGES: usize> {
    short_edges: [Edge<ShortEdge>; EDGES],
    short_active: [Active<ShortEdge>; EDGES],
    long_edges: [Edge<EdgeStepper>; EDGES],
    long_active: [Active<EdgeStepper>; EDGES],
    chains: [Chain; EDGES],
    starts: [u64; EDGES],
    // One place more than `EDGES` in these two, as two blocks of it.
    columns: [[i32; EDGES]; 2],
    runs: [[Run; EDGES]; 2],
}

impl<const EDGES: usize> FixedScratch<EDGES> {
    /// Its size for each edge it holds, in bytes, on the target it is
    /// built for.
    pub const BYTES_PER_EDGE: usize = core::mem::size_of::<FixedScratch<1>>();

    /// Cleared room for `EDGES` edges.
    pub fn new() -> Self {
        Self {
            short_edges: [Edge::default(); EDGES],
            short_active: [Active::default(); EDGES],
            long_edges: [Edge::default(); EDGES],
            long_active: [Active::default(); EDGES],
            chains: [Chain::default(); EDGES],
            starts: [0; EDGES],
            columns: [[0; EDGES]; 2],
            runs: [[Run::default(); EDGES]; 2],
        }
    }

    /// Its tables, lent for one fill.
    pub(super) fn room(&mut self) -> FixedRoom<'_> {
        FixedRoom {
            short: Slots { edges: &mut self.short_edges, active: &mut self.short_active },
            long: Slots { edges: &mut self.long_edges, active: &mut self.long_active },
            common: Common {
                chains: &mut self.chains,
                starts: &mut self.starts,
                columns: self.columns.as_flattened_mut(),
                runs: self.runs.as_flattened_mut(),
            },
        }
    }
}

impl<const EDGES: usize> Default for FixedScratch<EDGES> {
    fn default() -> Self {
        Self::new()
    }
}

/// A [`FixedScratch`]'s tables, borrowed for one fill, whatever its
/// capacity.
pub(super) struct FixedRoom<'s> {
    pub short: Slots<'s, ShortEdge>,
    pub long: Slots<'s, EdgeStepper>,
    pub common: Common<'s>,
}

/// The tables of one kind of edge.
pub(super) struct Slots<'s, E> {
    edges: &'s mut [Edge<E>],
    active: &'s mut [Active<E>],
}

/// The tables for either kind of edge.
pub(super) struct Common<'s> {
    chains: &'s mut [Chain],
    starts: &'s mut [u64],
    columns: &'s mut [i32],
    runs: &'s mut [Run],
}

/// Tables for `edges` edges of the kind `E` in its slots `own` and the
/// `common` tables of a fixed room, or a refusal when they hold fewer.
/// Sorted in place, as on the stack: no room for a wide sort.
#[allow(clippy::type_complexity)]
pub(super) fn tables<'s, E>(
    own: Slots<'s, E>,
    common: Common<'s>,
    edges: usize,
) -> Result<(EdgeRoom<'s, E>, Crossings<'s, E>), Refusal> {
    if edges > own.edges.len() {
        return Err(Refusal::TooManyVertices);
    }
    let table = EdgeRoom {
        edges: &mut own.edges[..edges],
        chains: &mut common.chains[..edges],
        starts: &mut common.starts[..edges],
    };
    let crossings = Crossings {
        active: &mut own.active[..edges],
        columns: &mut common.columns[..=edges],
        runs: &mut common.runs[..=edges],
        wide: None,
    };
    Ok((table, crossings))
}
