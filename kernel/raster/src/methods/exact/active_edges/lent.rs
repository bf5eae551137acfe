//! The room a caller lends the general path for a fill
//! ([`ScratchMut`]): a [`Scratch`](super::Scratch) on the heap or a
//! [`FixedScratch`], and where each kind of edge finds its tables in it
//! ([`Stepper`]).

use crate::methods::info::Refusal;

use super::super::edge::{Crossing, EdgeStepper, ShortEdge};
use super::fixed::{self, Common, FixedRoom, FixedScratch, Slots};
#[cfg(feature = "alloc")]
use super::scratch::{self, Room, Scratch, Shared};
use super::tables::{Crossings, EdgeRoom};

/// A caller's room for `exact`'s tables, lent for one fill: a
/// [`FixedScratch`], or with the `alloc` feature a
/// [`Scratch`](crate::Scratch), borrowed. [`fill_auto_with`] and
/// [`ExactPath::fill_with`](crate::ExactPath::fill_with) take either as
/// `&mut scratch`.
///
/// [`fill_auto_with`]: crate::fill_auto_with
pub struct ScratchMut<'s>(Lent<'s>);

enum Lent<'s> {
    #[cfg(feature = "alloc")]
    Heap(&'s mut Scratch),
    Fixed(FixedRoom<'s>),
}

#[cfg(feature = "alloc")]
impl<'s> From<&'s mut Scratch> for ScratchMut<'s> {
    fn from(scratch: &'s mut Scratch) -> Self {
        ScratchMut(Lent::Heap(scratch))
    }
}

impl<'s, const EDGES: usize> From<&'s mut FixedScratch<EDGES>> for ScratchMut<'s> {
    fn from(scratch: &'s mut FixedScratch<EDGES>) -> Self {
        ScratchMut(Lent::Fixed(scratch.room()))
    }
}

/// An edge stepper with its own room in a [`Scratch`](super::Scratch) and
/// a [`FixedScratch`].
pub(super) trait Stepper: Crossing {
    #[cfg(feature = "alloc")]
    fn room(scratch: &mut Scratch) -> (&mut Room<Self>, &mut Shared);

    fn fixed(room: FixedRoom<'_>) -> (Slots<'_, Self>, Common<'_>);

    /// Tables for `edges` edges in `scratch`, with room to sort or count
    /// their crossings on a target `width` wide where it is on the heap;
    /// a refusal when they cannot be had.
    #[allow(clippy::type_complexity)]
    #[cfg_attr(not(feature = "alloc"), allow(unused_variables))]
    fn lent(
        scratch: ScratchMut<'_>,
        edges: usize,
        width: i32,
    ) -> Result<(EdgeRoom<'_, Self>, Crossings<'_, Self>), Refusal> {
        match scratch.0 {
            #[cfg(feature = "alloc")]
            Lent::Heap(scratch) => {
                let (own, shared) = Self::room(scratch);
                scratch::tables(own, shared, edges, width)
            }
            Lent::Fixed(room) => {
                let (own, common) = Self::fixed(room);
                fixed::tables(own, common, edges)
            }
        }
    }
}

impl Stepper for ShortEdge {
    #[cfg(feature = "alloc")]
    fn room(scratch: &mut Scratch) -> (&mut Room<Self>, &mut Shared) {
        (&mut scratch.short, &mut scratch.shared)
    }

    fn fixed(room: FixedRoom<'_>) -> (Slots<'_, Self>, Common<'_>) {
        (room.short, room.common)
    }
}

impl Stepper for EdgeStepper {
    #[cfg(feature = "alloc")]
    fn room(scratch: &mut Scratch) -> (&mut Room<Self>, &mut Shared) {
        (&mut scratch.long, &mut scratch.shared)
    }

    fn fixed(room: FixedRoom<'_>) -> (Slots<'_, Self>, Common<'_>) {
        (room.long, room.common)
    }
}
