//! What a peer is to the lab: [`PeerInfo`], its description as data, and
//! [`Peer`], the one trait every peer's file implements.

use raster::{Polygon, SpanSink};

use crate::convention::Own;
use crate::corpus::Family;

/// What a peer is, as data: the peers' counterpart of a method's
/// `raster::MethodInfo`.
#[derive(Clone, Copy, Debug)]
pub struct PeerInfo {
    /// Its name in the results and the charts.
    pub name: &'static str,
    /// The library, its version and the call made.
    pub source: &'static str,
    /// Arithmetic and convention, in words.
    pub summary: &'static str,
    /// How it decides which pixels are in: what it is judged against
    /// "under its own convention".
    pub own: Own,
}

/// A peer library, as the lab runs it.
pub trait Peer: Sync {
    fn info(&self) -> &PeerInfo;

    /// Whether it runs on `family` at all; every family, unless it says
    /// otherwise.
    fn takes(&self, _family: &Family) -> bool {
        true
    }

    /// Draws `polygon` into `sink`, or says why nothing could be drawn.
    fn draw(&self, polygon: &Polygon, sink: &mut dyn SpanSink) -> Result<(), &'static str>;

    /// One timed pass: fills every polygon it accepts of `polygons`, in
    /// order, into its own target. Inputs are converted before the pass.
    fn pass<'a>(&self, polygons: &[&'a Polygon]) -> Box<dyn FnMut() + 'a>;
}
