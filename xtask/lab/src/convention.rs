//! How a contender decides which pixels are in, which is what the lab
//! judges it against "under its own convention": the peers name theirs
//! (`PeerInfo::own`, in `peers/peer.rs`), measuring judges by it, and the results
//! record it.

use raster::reference::SampleOffset;

/// How a contender decides which pixels are in: what the lab judges it
/// against "under its own convention".
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Own {
    /// At one sample point a pixel, in subpixels from its corner.
    Sample(SampleOffset),
    /// By the part of the pixel covered: in where it is above
    /// `threshold / 255` ([`crate::area_reference`]).
    Coverage { threshold: u8 },
    /// At whole-pixel points of the polygon with its vertices rounded to
    /// whole pixels, by the even-odd rule, points on its edges in (spans
    /// take both their ends); with `outline`, every edge drawn as a line
    /// besides ([`crate::closed_reference`]).
    Closed { outline: bool },
}
