//! What a method's pixels are judged against, and the counts of how they
//! differ: `exact` (our convention) or the reference sampling at the
//! method's own point (its convention), per polygon, kept per polygon so
//! that dragging one vertex recomputes one polygon.

use std::ops::Add;

use raster::reference::{self, SampleOffset};
use raster::{CoverageSink, MethodId, Polygon, Refusal, SCREEN};

/// What a method is judged against.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Judge {
    /// Our convention: the `exact` method (pixel centres, top-left rule).
    Exact,
    /// The reference sampling at the method's own sample point, so that
    /// only the method's arithmetic is judged, not its convention.
    OwnConvention,
}

/// A method against a judge on one polygon.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Counts {
    /// Pixels the method draws that the judge does not.
    pub added: usize,
    /// Pixels the judge draws that the method does not.
    pub missed: usize,
    /// Pixels the method draws more than once.
    pub overdrawn: usize,
    /// Spans the method emitted outside the screen.
    pub strays: usize,
    /// Why the method declined the polygon, if it did.
    pub refusal: Option<Refusal>,
}

/// Counts summed over polygons; the refusal kept is the first.
impl Add for Counts {
    type Output = Counts;

    fn add(self, other: Counts) -> Counts {
        Counts {
            added: self.added + other.added,
            missed: self.missed + other.missed,
            overdrawn: self.overdrawn + other.overdrawn,
            strays: self.strays + other.strays,
            refusal: self.refusal.or(other.refusal),
        }
    }
}

/// Per polygon, the counts already worked out for each method and judge:
/// dragging one vertex recomputes one polygon, not the whole scene.
#[derive(Clone, Debug, Default)]
pub struct CountCache {
    polygons: Vec<Vec<(MethodId, Judge, Counts)>>,
}

impl CountCache {
    pub fn new(polygons: usize) -> Self {
        Self { polygons: vec![Vec::new(); polygons] }
    }

    /// What is known of `method` against `judge` on polygon `index`.
    pub fn get(&self, index: usize, method: MethodId, judge: Judge) -> Option<Counts> {
        let known = self.polygons.get(index)?;
        known.iter().find(|(m, j, _)| (*m, *j) == (method, judge)).map(|&(_, _, counts)| counts)
    }

    /// Keeps `counts` for `method` against `judge` on polygon `index`.
    pub fn insert(&mut self, index: usize, method: MethodId, judge: Judge, counts: Counts) {
        if let Some(known) = self.polygons.get_mut(index) {
            known.push((method, judge, counts));
        }
    }

    /// Drops what was known about polygon `index` (it changed).
    pub fn forget(&mut self, index: usize) {
        if let Some(known) = self.polygons.get_mut(index) {
            known.clear();
        }
    }
}

/// The pixels `exact` draws for `polygon`.
pub fn exact_coverage(polygon: &Polygon) -> CoverageSink {
    let mut wanted = CoverageSink::new(SCREEN);
    // `exact` takes any polygon; were it ever to decline one, the judge
    // would want no pixels, and every pixel drawn would count as added.
    let _ = MethodId::Exact.method().fill(polygon, &mut wanted);
    wanted
}

/// The pixels `judge` wants of `polygon` when `method` is judged.
fn judge_coverage(polygon: &Polygon, method: MethodId, judge: Judge) -> CoverageSink {
    match judge {
        Judge::Exact => exact_coverage(polygon),
        Judge::OwnConvention => {
            let mut wanted = CoverageSink::new(SCREEN);
            reference::fill(polygon, SampleOffset::of(&method.method().info().convention), &mut wanted);
            wanted
        }
    }
}

/// `method` against `judge` on `polygon`, with both coverages.
pub fn compare(polygon: &Polygon, method: MethodId, judge: Judge) -> (Counts, CoverageSink, CoverageSink) {
    let mut drawn = CoverageSink::new(SCREEN);
    let refusal = method.method().fill(polygon, &mut drawn).err();
    let wanted = judge_coverage(polygon, method, judge);
    let report = drawn.report(&wanted);
    let counts = Counts {
        added: report.extras,
        missed: report.gaps,
        overdrawn: report.overdrawn,
        strays: report.out_of_bounds,
        refusal,
    };
    (counts, drawn, wanted)
}
