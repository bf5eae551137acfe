//! What a fill method is, as data: the metadata the kernel, the host
//! renderer, the tests and the lab list and compare methods by, and why a
//! method declines a polygon. The classes it may handle are `classify.rs`'s
//! ([`Class`]), the sample point of its convention the reference's
//! ([`Convention`]). The interface itself, [`Method`], is in
//! [`methods`](crate::methods) with the methods.
//!
//! [`Method`]: crate::methods::Method

#[cfg(feature = "alloc")]
use crate::classify::Class;
#[cfg(feature = "alloc")]
use crate::geometry::FillRule;
#[cfg(feature = "alloc")]
use crate::reference::Convention;

#[cfg(feature = "alloc")]
/// When a method takes memory from the heap while it fills.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Heap {
    /// Never: its state is a fixed size and lives on the stack.
    Never,
    /// Only for polygons of very many edges, whose tables do not fit on
    /// the stack (`exact`: over 256 edges, or over 64 that may be 512 px
    /// or longer), and then not at all from a caller's scratch that has
    /// grown to them (`exact::fill_auto_with`).
    ManyEdges,
    /// For every polygon: the port keeps its per-polygon tables in `Vec`s,
    /// where the original called `malloc` or used static arrays.
    EveryPolygon,
}

#[cfg(feature = "alloc")]
impl Heap {
    pub const fn name(self) -> &'static str {
        match self {
            Heap::Never => "never",
            Heap::ManyEdges => "only polygons of over 256 edges, or over 64 that may be 512 px or longer",
            Heap::EveryPolygon => "every polygon",
        }
    }
}

#[cfg(feature = "alloc")]
/// What a method is, where it comes from and what it accepts.
#[derive(Clone, Copy, Debug)]
pub struct MethodInfo {
    /// Short name used on the command line and in the protocol.
    pub name: &'static str,
    /// What it follows: author, book or article, chapter and listing
    /// (`docs/methods.md`), or "ours".
    pub source: &'static str,
    pub convention: Convention,
    /// Arithmetic, e.g. "f64 inverse slope, ceil".
    pub numeric: &'static str,
    /// The most general class it fills correctly; see [`Class`].
    pub handles: Class,
    /// Fill rules it honours. Methods for one-span-per-line polygons have
    /// no choice of rule and list both.
    pub rules: &'static [FillRule],
    /// When it allocates (the kernel's show counts allocations per frame).
    pub heap: Heap,
}

/// Why a method declined a polygon. Declining draws nothing.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Refusal {
    /// The polygon has several contours and the method takes one list.
    MultipleContours,
    /// Coordinates beyond the range where the method's arithmetic is exact
    /// or safe.
    OutOfRange,
    /// More vertices than the method's fixed tables hold (for `exact`,
    /// than the tables on the stack and a caller's
    /// [`FixedScratch`](crate::FixedScratch) hold, or without the `alloc`
    /// feature the stack's alone).
    TooManyVertices,
    /// Memory for the method's tables could not be had (Abrash's `malloc`
    /// failure path).
    OutOfMemory,
    /// The polygon is not of the class a path of a method fills (one of
    /// `exact`'s [`ExactPath`](crate::ExactPath)s asked for alone).
    OutsideClass,
}

impl Refusal {
    pub const ALL: [Refusal; 5] = [
        Refusal::MultipleContours,
        Refusal::OutOfRange,
        Refusal::TooManyVertices,
        Refusal::OutOfMemory,
        Refusal::OutsideClass,
    ];

    /// One word for it, in the protocol's replies.
    pub const fn name(self) -> &'static str {
        match self {
            Refusal::MultipleContours => "multiple-contours",
            Refusal::OutOfRange => "out-of-range",
            Refusal::TooManyVertices => "too-many-vertices",
            Refusal::OutOfMemory => "out-of-memory",
            Refusal::OutsideClass => "outside-class",
        }
    }

    /// The refusal [`Refusal::name`] gives `name`.
    pub fn from_name(name: &str) -> Option<Self> {
        Refusal::ALL.into_iter().find(|refusal| refusal.name() == name)
    }

    pub const fn describe(self) -> &'static str {
        match self {
            Refusal::MultipleContours => "several contours, method takes one",
            Refusal::OutOfRange => "coordinates out of the method's range",
            Refusal::TooManyVertices => "too many vertices",
            Refusal::OutOfMemory => "out of memory",
            Refusal::OutsideClass => "outside the path's class",
        }
    }
}

impl core::fmt::Display for Refusal {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(self.describe())
    }
}

impl core::error::Error for Refusal {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_refusal_has_a_name_of_its_own_that_parses_back() {
        for refusal in Refusal::ALL {
            assert_eq!(Refusal::from_name(refusal.name()), Some(refusal));
            assert!(!refusal.name().contains(' '), "{}", refusal.name());
        }
        assert_eq!(Refusal::from_name("refused"), None);
    }
}
