//! What a peer is to the lab: [`PeerInfo`], its description as data (with
//! [`Clock`], what it does inside the clock), and [`Peer`], the one trait
//! every peer's file implements.

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
    /// What it does inside the timed pass and what before it.
    pub clock: Clock,
    /// For a second way of timing a peer (its paths built inside the
    /// clock or before it), the peer it times otherwise: the same library
    /// drawing the same pixels, left out of the charts of accuracy.
    pub variant_of: Option<&'static str>,
}

/// What a contender does inside the clock and what it is given before it
/// starts: the rows of docs/lab.md's table of what each contender does
/// inside the clock, generated from these (`crate::report::clock_table`)
/// so that the table cannot drift from the code.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Clock {
    /// What is made of each polygon before the clock starts.
    pub before: &'static str,
    /// Path or vertex set-up inside the clock, per polygon.
    pub setup: &'static str,
    /// The fill inside the clock, per polygon (and per pass, where some of
    /// it is done once a pass).
    pub fill: &'static str,
    /// What it fills into.
    pub surface: &'static str,
    pub pixel_format: &'static str,
    /// Anti-aliasing, and the threshold that makes a pixel in or out.
    pub anti_aliasing: &'static str,
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
