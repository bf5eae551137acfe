//! The exact method's general path: any number of contours, crossing or
//! not, under either fill rule. An edge table sorted by first scan line
//! feeds an active edge table (Black Book ch. 40's global and active edge
//! tables), kept sorted by visible column; the directions summed from the
//! left decide which crossings open and close the runs the fill rule calls
//! inside.
//!
//! A fill goes one way through its stages, each handing its data to the
//! next and none calling back: this driver finds the polygon's box, the
//! kind of edge that steps it exactly and where its tables live (on the
//! stack for up to 256 edges, else in the room a caller lends, a
//! [`Scratch`] or a [`FixedScratch`], `lent.rs`); `build.rs` turns the
//! polygon into the edge table (`tables.rs`); `walk.rs` walks it row by
//! row, with the crossings kept in order (`order.rs`), paired into runs
//! (`runs.rs`) or summed per column (`columns.rs`), into spans
//! (`../spans.rs`).

mod build;
mod columns;
mod fixed;
mod lent;
mod order;
mod runs;
#[cfg(feature = "alloc")]
mod scratch;
mod tables;
mod walk;

use core::mem::size_of;

pub use fixed::FixedScratch;
pub use lent::ScratchMut;
#[cfg(feature = "alloc")]
pub use scratch::Scratch;

use crate::geometry::{FillRule, Point, PolygonRef};
use crate::methods::info::Refusal;
use crate::target::{Size, SpanSink};

use super::bounds::Bounds;
use super::clip::columns_fit;
use super::edge::{Crossing, EdgeStepper, ShortEdge};
use super::spans::Target;
use build::build;
use lent::Stepper;
use tables::{Active, Chain, Crossings, Edge, EdgeRoom, Run};
use walk::walk;

/// Fills `polygon`, whose vertices lie in `bounds`, by its fill rule,
/// with tables on the stack or in `scratch` (with `alloc`, a new
/// [`Scratch`] when there is none). Refuses only when the scratch must
/// grow and memory cannot be had, or holds too few edges.
pub(super) fn fill<C: AsRef<[Point]>, S: SpanSink + ?Sized>(
    polygon: PolygonRef<'_, C>,
    bounds: Bounds,
    size: Size,
    sink: &mut S,
    scratch: Option<ScratchMut<'_>>,
) -> Result<(), Refusal> {
    // The box says whether columns may leave the target, and whether
    // every edge may be a `ShortEdge`.
    let Bounds { min, max } = bounds;
    let fill = Fill { polygon, clip: !columns_fit(min.x, max.x, size.width), size };
    if ShortEdge::fits((min.x, max.x), (min.y, max.y)) {
        fill.with_tables::<ShortEdge, _>(sink, scratch)
    } else {
        fill.with_tables::<EdgeStepper, _>(sink, scratch)
    }
}

/// One fill of the general path: the polygon, whether its columns need
/// clamping, and the target's size.
struct Fill<'a, C> {
    polygon: PolygonRef<'a, C>,
    clip: bool,
    size: Size,
}

// By hand, for every `C`, as the polygon's.
impl<C> Clone for Fill<'_, C> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<C> Copy for Fill<'_, C> {}

impl<C: AsRef<[Point]>> Fill<'_, C> {
    /// Fills on tables for the polygon's edges: on the stack when they
    /// fit ([`Fill::on_stack`]), else in `scratch` (with `alloc`, a new
    /// [`Scratch`] when there is none; without, a refusal).
    fn with_tables<E: Stepper, S: SpanSink + ?Sized>(
        self,
        sink: &mut S,
        scratch: Option<ScratchMut<'_>>,
    ) -> Result<(), Refusal> {
        let edges = self.polygon.vertex_count();
        // The wide stepper's tables are three times the size: fewer fit.
        let most = if size_of::<E>() <= size_of::<ShortEdge>() { 256 } else { 64 };
        match edges {
            0..=8 => self.on_stack::<8, E, S>(sink),
            9..=16 => self.on_stack::<16, E, S>(sink),
            17..=32 => self.on_stack::<32, E, S>(sink),
            33..=64 => self.on_stack::<64, E, S>(sink),
            _ if edges <= most.min(128) => self.on_stack::<128, E, S>(sink),
            _ if edges <= most => self.on_stack::<256, E, S>(sink),
            _ => {
                #[cfg(feature = "alloc")]
                let mut fresh = Scratch::new();
                #[cfg(feature = "alloc")]
                let scratch = Some(scratch.unwrap_or_else(|| ScratchMut::from(&mut fresh)));
                let Some(scratch) = scratch else { return Err(Refusal::TooManyVertices) };
                let (room, crossings) = E::lent(scratch, edges, self.size.width)?;
                self.run(room, crossings, sink);
            }
        }
        Ok(())
    }

    /// Fills on cleared tables for up to `N` edges, on the stack (one more
    /// place in the last two). Each is a local of its own, cleared in
    /// place: built as fields of one value, the tables of the larger
    /// classes were cleared, then copied into it. Never inlined, so that
    /// the caller's frame holds only the class of tables it uses.
    #[inline(never)]
    fn on_stack<const N: usize, E: Crossing, S: SpanSink + ?Sized>(self, sink: &mut S) {
        let mut edges = [Edge::<E>::default(); N];
        let mut chains = [Chain::default(); N];
        let mut starts = [0; N];
        let mut active = [Active::<E>::default(); N];
        let mut runs = [[Run::default(); N]; 2];
        let mut columns = [[0; N]; 2];
        let room = EdgeRoom { edges: &mut edges, chains: &mut chains, starts: &mut starts };
        let crossings = Crossings {
            active: &mut active,
            columns: &mut columns.as_flattened_mut()[..=N],
            runs: &mut runs.as_flattened_mut()[..=N],
            wide: None,
        };
        self.run(room, crossings, sink);
    }

    /// Builds the edge table in `room`, then walks it in `crossings`.
    fn run<E: Crossing, S: SpanSink + ?Sized>(self, room: EdgeRoom<'_, E>, crossings: Crossings<'_, E>, sink: &mut S) {
        let table = build(self.polygon, self.size, room);
        let target = Target { color: self.polygon.color, width: self.size.width };
        let walk = match (self.polygon.rule, self.clip) {
            (FillRule::EvenOdd, false) => walk::<false, false, E, S>,
            (FillRule::EvenOdd, true) => walk::<false, true, E, S>,
            (FillRule::NonZero, false) => walk::<true, false, E, S>,
            (FillRule::NonZero, true) => walk::<true, true, E, S>,
        };
        walk(table, crossings, target, sink);
    }
}
