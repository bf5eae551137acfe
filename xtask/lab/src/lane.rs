//! The lanes of "what modelling costs" (`modelling.rs`): each a way
//! through a family's polygons that is timed beside the contenders.

use std::hint::black_box;

use raster::{classify, fill_auto_with, ExactPath, Polygon, Scratch, Size, SpanSink, SCREEN};

use crate::contender::Contender;

/// One way through a family's polygons. Every lane is timed in turn with
/// the family's contenders and bounds ([`crate::timing::time_family`]),
/// so its ratios to `exact` and to the store bound are paired within each
/// launch, each with its interval across launches.
///
/// Adding a lane (a candidate structure, say): a variant here, its name
/// in [`Lane::name`], its pass in [`Lane::pass`], and its place in
/// [`Lane::all`]; if it draws, its [`Contender`] in `Lane::contender`, so
/// that it is judged (and its pixels held to the reference: a drawing
/// lane that draws a pixel wrong fails the run) before it is timed. A
/// new path of `exact` (a name in [`ExactPath::NAMES`]) is a lane
/// already.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Lane {
    /// One of exact's paths alone, by its place in [`ExactPath::NAMES`].
    Path(usize),
    /// `fill_auto`: the classification, then the path it picks.
    Auto,
    /// `fill_auto`'s classification alone ([`ExactPath::choose`]).
    Dispatch,
    /// `raster::classify`: every class, simplicity included (quadratic).
    Classify,
    /// `fill_auto` into a sink that only adds up the spans' lengths:
    /// finding the spans without storing them.
    Walk,
}

impl Lane {
    /// Every lane, in the order the report and the charts give them:
    /// exact's paths, then the rest.
    pub fn all() -> Vec<Lane> {
        let paths = (0..ExactPath::NAMES.len()).map(Lane::Path);
        paths.chain([Lane::Auto, Lane::Dispatch, Lane::Classify, Lane::Walk]).collect()
    }

    pub const fn name(self) -> &'static str {
        match self {
            Lane::Path(which) => ExactPath::NAMES[which],
            Lane::Auto => "fill_auto",
            Lane::Dispatch => "dispatch",
            Lane::Classify => "classify",
            Lane::Walk => "spans unstored",
        }
    }

    /// The lane as a contender, for the lanes that draw.
    pub fn contender(self) -> Option<Contender> {
        match self {
            Lane::Path(which) => Some(Contender::Path(which)),
            Lane::Auto => Some(Contender::Auto),
            Lane::Dispatch | Lane::Classify | Lane::Walk => None,
        }
    }

    /// One timed pass: the lane's work on every one of `polygons`, once.
    pub fn pass<'a>(self, polygons: &[&'a Polygon]) -> Box<dyn FnMut() + 'a> {
        let polygons = polygons.to_vec();
        match self {
            Lane::Dispatch => Box::new(move || {
                for &polygon in &polygons {
                    black_box(ExactPath::choose(black_box(polygon)));
                }
            }),
            Lane::Classify => Box::new(move || {
                for polygon in &polygons {
                    black_box(classify(black_box(polygon)));
                }
            }),
            Lane::Walk => {
                let (mut lengths, mut scratch) = (SpanLengths(0), Scratch::new());
                Box::new(move || {
                    for &polygon in &polygons {
                        let _ = fill_auto_with(polygon, &mut lengths, &mut scratch);
                    }
                    black_box(&mut lengths);
                })
            }
            Lane::Path(_) | Lane::Auto => match self.contender() {
                Some(contender) => contender.pass(&polygons),
                None => Box::new(|| {}),
            },
        }
    }
}

/// A 320x200 sink that adds up the lengths of the spans it is given and
/// stores nothing.
struct SpanLengths(u64);

impl SpanSink for SpanLengths {
    fn size(&self) -> Size {
        SCREEN
    }

    #[inline(always)]
    fn span(&mut self, _y: i32, x_start: i32, x_end: i32, _color: u8) {
        self.0 = self.0.wrapping_add((x_end - x_start) as u64);
    }
}
