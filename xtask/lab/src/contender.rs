//! Everything the lab judges: the methods of `raster` and the peers, behind
//! one face, so measuring never asks which is which.

use std::hint::black_box;

use raster::reference::SampleOffset;
use raster::{fill_auto, fill_auto_with, ExactPath, Framebuffer, MethodId, Polygon, Scratch, SpanSink, SCREEN};

use crate::convention::Own;
use crate::corpus::Family;
use crate::peers::{self, Clock, Peer};

/// A method of `raster`, a peer library, or, only in "what modelling
/// costs" (not one of [`Contender::all`]), one of `exact`'s paths asked
/// for alone (by its place in [`ExactPath::NAMES`]) or `fill_auto`; those two fill with a [`Scratch`] kept from
/// polygon to polygon, as a program drawing frame after frame would.
#[derive(Clone, Copy)]
pub enum Contender {
    Method(MethodId),
    Peer(&'static dyn Peer),
    Path(usize),
    Auto,
}

/// What every method of `raster` does inside the clock (and `exact`'s
/// paths and `fill_auto` in "what modelling costs").
pub const METHODS_CLOCK: Clock = Clock {
    before: "nothing: the corpus's `Polygon` (vertices in 1/256 px)",
    setup: "its own: edges from the vertices, each method its way",
    fill: "its spans stored into the framebuffer, the fill compiled for it (`MethodId::fill`)",
    surface: "320x200 `Framebuffer`",
    pixel_format: "8-bit index",
    anti_aliasing: "none; a pixel is in by its sample point (`exact`'s: its centre)",
};

impl Contender {
    /// Every method of `raster::MethodId::ALL`, then the peers.
    pub fn all() -> Vec<Contender> {
        let methods = MethodId::ALL.into_iter().map(Contender::Method);
        methods.chain(peers::ALL.iter().map(|&p| Contender::Peer(p))).collect()
    }

    pub fn name(&self) -> &'static str {
        match self {
            Contender::Method(id) => id.name(),
            Contender::Peer(p) => p.info().name,
            Contender::Path(which) => ExactPath::NAMES[*which],
            Contender::Auto => "fill_auto",
        }
    }

    pub fn is_peer(&self) -> bool {
        matches!(self, Contender::Peer(_))
    }

    /// What a method follows (book, chapter and listing, or article), or the
    /// peer's crate and call.
    pub fn source(&self) -> &'static str {
        match self {
            Contender::Method(id) => id.method().info().source,
            Contender::Peer(p) => p.info().source,
            Contender::Path(_) => "ours: one of exact's paths alone",
            Contender::Auto => "ours: exact's classification, then the path it picks",
        }
    }

    /// Arithmetic and convention, in words.
    pub fn summary(&self) -> String {
        match self {
            Contender::Method(id) => {
                let info = id.method().info();
                format!("{}; {}", info.numeric, info.convention.summary)
            }
            Contender::Peer(p) => p.info().summary.to_string(),
            Contender::Path(which) => {
                format!("exact's {} path; refuses polygons outside its class", ExactPath::NAMES[*which])
            }
            Contender::Auto => "exact's fill_auto, with a scratch kept between polygons".to_string(),
        }
    }

    /// What it does inside the timed pass and what before it.
    pub fn clock(&self) -> Clock {
        match self {
            Contender::Peer(p) => p.info().clock,
            Contender::Method(_) | Contender::Path(_) | Contender::Auto => METHODS_CLOCK,
        }
    }

    /// How it decides which pixels are in: its own convention, for the
    /// reference.
    pub fn own(&self) -> Own {
        match self {
            Contender::Method(id) => Own::Sample(SampleOffset::of(&id.method().info().convention)),
            Contender::Peer(p) => p.info().own,
            Contender::Path(_) | Contender::Auto => Own::Sample(SampleOffset::CENTRE),
        }
    }

    /// Whether it runs on `family` at all ([`Peer::takes`]).
    pub fn accepts(&self, family: &Family) -> bool {
        match self {
            // A path is given every polygon: it must refuse what it cannot fill.
            Contender::Method(_) | Contender::Path(_) | Contender::Auto => true,
            Contender::Peer(p) => p.takes(family),
        }
    }

    /// Draws `polygon` into `sink`, or says why it declined.
    pub fn draw(&self, polygon: &Polygon, sink: &mut dyn SpanSink) -> Result<(), &'static str> {
        match self {
            Contender::Method(id) => id.fill(polygon, sink).map_err(|refusal| refusal.describe()),
            Contender::Peer(p) => p.draw(polygon, sink),
            Contender::Path(which) => {
                ExactPath::alone(*which, polygon).and_then(|path| path.fill(sink)).map_err(|refusal| refusal.describe())
            }
            Contender::Auto => fill_auto(polygon, sink).map_err(|refusal| refusal.describe()),
        }
    }

    /// One timed pass over `polygons` into a 320x200 target of its own
    /// (for a peer, its own kind of target).
    pub fn pass<'a>(&self, polygons: &[&'a Polygon]) -> Box<dyn FnMut() + 'a> {
        match *self {
            Contender::Peer(p) => p.pass(polygons),
            ours => {
                let polygons = polygons.to_vec();
                let (mut screen, mut scratch) = (Framebuffer::new(SCREEN), Scratch::new());
                Box::new(move || ours.fill_all(&polygons, &mut screen, &mut scratch))
            }
        }
    }

    /// For ours (a method, one of `exact`'s paths or `fill_auto`): the same
    /// pass as [`Contender::pass`], into `screen`, which the caller reads
    /// once the pass is dropped (the timed pixels); `None` for a peer,
    /// whose target is its own kind.
    pub fn pass_into<'a>(
        &self,
        polygons: &[&'a Polygon],
        screen: &'a mut Framebuffer,
    ) -> Option<Box<dyn FnMut() + 'a>> {
        if self.is_peer() {
            return None;
        }
        let (ours, polygons, mut scratch) = (*self, polygons.to_vec(), Scratch::new());
        Some(Box::new(move || ours.fill_all(&polygons, screen, &mut scratch)))
    }

    /// Fills `polygons` into `screen` as the timed passes of ours do: each
    /// fill compiled for the framebuffer (its store inlined into the fill),
    /// the paths and `fill_auto` with a scratch kept from polygon to
    /// polygon. A refusal costs what it costs; it draws nothing. A peer
    /// draws nothing here.
    fn fill_all(self, polygons: &[&Polygon], screen: &mut Framebuffer, scratch: &mut Scratch) {
        match self {
            Contender::Method(id) => {
                for polygon in polygons {
                    let _ = id.fill(polygon, screen);
                }
            }
            Contender::Path(which) => {
                for polygon in polygons {
                    let _ = ExactPath::alone(which, *polygon).and_then(|path| path.fill_with(screen, &mut *scratch));
                }
            }
            Contender::Auto => {
                for polygon in polygons {
                    let _ = fill_auto_with(*polygon, screen, &mut *scratch);
                }
            }
            Contender::Peer(_) => {}
        }
        black_box(screen);
    }
}
