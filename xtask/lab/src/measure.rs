//! Accuracy: every contender on every polygon of a family, judged against
//! `raster::reference` under our convention (pixel centres) and under the
//! contender's own convention (its sample point, or for a peer that
//! thresholds area coverage, [`crate::area_reference`]), with `raster::CoverageSink` counting
//! overdraw, gaps and stray spans.
//!
//! A polygon is drawn once into a [`Recorder`]. Spans equal to the
//! reference's up to order and splitting need no counting; others are
//! replayed into a fresh coverage sink (that polygon alone). On tiling
//! families they also go into the tiling's sink, where overdraw and gaps
//! between tiles show. Polygons are judged on every core; timing is not.

use std::cell::OnceCell;
use std::ops::Range;
use std::panic::{self, AssertUnwindSafe};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::thread;

use raster::reference::{self, SampleOffset};
use raster::{CoverageReport, CoverageSink, Polygon, SCREEN};

use crate::area_reference;
use crate::closed_reference;
use crate::contender::Contender;
use crate::convention::Own;
use crate::corpus::Family;
use crate::spans::{self, Recorder, Span};
use crate::stats::MeanVector;

/// What one contender did on a set of polygons.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Tally {
    pub polygons: u64,
    /// Polygons declined cleanly (nothing drawn).
    pub refusals: u64,
    /// Panics and fills that emitted spans outside the target.
    pub failures: u64,
    /// Pixels differing from the reference under our convention.
    pub wrong_pixels: u64,
    /// Pixels differing from the reference under the contender's own.
    pub wrong_pixels_own: u64,
    /// Of the wrong pixels, those the reference draws and the contender
    /// left out, under our convention and under its own.
    pub missing_pixels: u64,
    pub missing_pixels_own: u64,
    /// Pixels drawn more than once: within one fill, or within one tiling
    /// on tiling families.
    pub overdraw: u64,
    /// Pixels of a tiling's region (under the contender's own convention)
    /// that no tile drew; tiling families only.
    pub gaps: u64,
    /// Polygons failed, wrong under the contender's own convention, or
    /// overdrawn within their fill.
    pub faulty_polygons: u64,
    /// Pixels written on screen, overdraw included.
    pub drawn_pixels: u64,
    /// Centroid of the drawn pixels minus the reference's (our convention),
    /// in pixels, over polygons where both drew something.
    pub bias: MeanVector,
    pub first_failure: Option<String>,
    pub first_refusal: Option<String>,
}

/// How one fill went.
#[derive(Clone, Debug, PartialEq)]
enum Status {
    Drawn,
    Refused(&'static str),
    Failed(String),
}

/// One contender on one polygon.
struct Outcome {
    status: Status,
    wrong: u64,
    wrong_own: u64,
    missing: u64,
    missing_own: u64,
    overdraw: u64,
    drawn: u64,
    bias: Option<(f64, f64)>,
}

impl Tally {
    /// Adds `later`, a tally of the polygons after these.
    fn merge(&mut self, later: &Tally) {
        self.polygons += later.polygons;
        self.refusals += later.refusals;
        self.failures += later.failures;
        self.wrong_pixels += later.wrong_pixels;
        self.wrong_pixels_own += later.wrong_pixels_own;
        self.missing_pixels += later.missing_pixels;
        self.missing_pixels_own += later.missing_pixels_own;
        self.overdraw += later.overdraw;
        self.gaps += later.gaps;
        self.faulty_polygons += later.faulty_polygons;
        self.drawn_pixels += later.drawn_pixels;
        self.bias.merge(&later.bias);
        if self.first_failure.is_none() {
            self.first_failure.clone_from(&later.first_failure);
        }
        if self.first_refusal.is_none() {
            self.first_refusal.clone_from(&later.first_refusal);
        }
    }

    fn record(&mut self, index: usize, outcome: &Outcome, count_overdraw: bool) {
        self.polygons += 1;
        self.wrong_pixels += outcome.wrong;
        self.wrong_pixels_own += outcome.wrong_own;
        self.missing_pixels += outcome.missing;
        self.missing_pixels_own += outcome.missing_own;
        self.drawn_pixels += outcome.drawn;
        if count_overdraw {
            self.overdraw += outcome.overdraw;
        }
        if let Some(bias) = outcome.bias {
            self.bias.add(bias);
        }
        match &outcome.status {
            Status::Drawn => {}
            Status::Refused(reason) => {
                self.refusals += 1;
                self.first_refusal.get_or_insert_with(|| format!("polygon {index}: {reason}"));
            }
            Status::Failed(reason) => {
                self.failures += 1;
                self.first_failure.get_or_insert_with(|| format!("polygon {index}: {reason}"));
            }
        }
        let failed = matches!(outcome.status, Status::Failed(_));
        self.faulty_polygons += u64::from(failed || outcome.wrong_own > 0 || outcome.overdraw > 0);
    }
}

/// A family judged.
pub struct Judged {
    /// The reference's spans (our convention) of every polygon.
    pub exact: Vec<Vec<Span>>,
    /// Per contender, in the order given: its tally, or `None` where it
    /// does not take the family.
    pub tallies: Vec<Option<Tally>>,
    /// The family's sweep runs `(value, polygons)`, if it sweeps.
    pub runs: Vec<(f64, Range<usize>)>,
    /// Per contender, a tally for each sweep run (empty without a sweep or
    /// where it does not take the family).
    pub run_tallies: Vec<Vec<Tally>>,
    /// Per contender, the polygons its timing runs on: those a method drew
    /// or refused without failing, those a peer drew.
    pub timed: Vec<Vec<usize>>,
}

/// The reference's fill of one polygon under one convention.
struct ReferenceFill {
    own: Own,
    spans: Vec<Span>,
    /// The spans in normal form, to spot a fill that matches them exactly.
    normal: Option<Vec<Span>>,
    /// Built the first time a fill differs: most of `exact`'s never do.
    coverage: OnceCell<CoverageSink>,
}

impl ReferenceFill {
    fn of(polygon: &Polygon, own: Own) -> Self {
        let mut recorder = Recorder::default();
        match own {
            Own::Sample(sample) => reference::fill(polygon, sample, &mut recorder),
            Own::Coverage { threshold } => area_reference::fill(polygon, threshold, &mut recorder),
            Own::Closed { outline } => closed_reference::fill(polygon, outline, &mut recorder),
        }
        let normal = spans::normal_form(&recorder.spans);
        Self { own, spans: recorder.spans, normal, coverage: OnceCell::new() }
    }

    fn coverage(&self) -> &CoverageSink {
        self.coverage.get_or_init(|| coverage_of(&self.spans))
    }

    /// How `drawn` (with `normal`, its normal form, and `coverage`, its
    /// coverage) compares with this fill.
    fn compare(&self, normal: &Option<Vec<Span>>, coverage: &OnceCell<CoverageSink>, drawn: &[Span]) -> CoverageReport {
        // The same spans up to order and splitting: the same pixels, each
        // once, all inside (a normal form exists only for such spans).
        if normal.is_some() && *normal == self.normal {
            return CoverageReport::default();
        }
        coverage.get_or_init(|| coverage_of(drawn)).report(self.coverage())
    }
}

/// The reference's spans of `polygon` under our convention (pixel
/// centres), as [`Judged::exact`] holds them: what the bounds replay.
pub fn exact_spans(polygon: &Polygon) -> Vec<Span> {
    ReferenceFill::of(polygon, Own::Sample(SampleOffset::CENTRE)).spans
}

fn coverage_of(spans: &[Span]) -> CoverageSink {
    let mut coverage = CoverageSink::new(SCREEN);
    spans::replay(spans, 1, &mut coverage);
    coverage
}

/// Judges every contender on every polygon of `family`, on every core;
/// `progress` is told of each polygon done. Panics are caught and counted
/// as failures; the caller should silence the panic hook (see [`quietly`]).
pub fn judge(family: &Family, contenders: &[Contender], progress: &(dyn Fn() + Sync)) -> Judged {
    let plan = Plan::new(family, contenders);
    let canvases: Vec<Range<usize>> =
        if plan.tiled() { family.tilings.clone() } else { (0..family.polygons.len()).map(|i| i..i + 1).collect() };
    // Contiguous blocks of canvases, taken in turn by the workers and merged
    // back in order, so that "first failure" means the same on any machine.
    let workers = thread::available_parallelism().map_or(1, |n| n.get());
    let blocks: Vec<&[Range<usize>]> = canvases.chunks(canvases.len().div_ceil(workers * 8).max(1)).collect();
    let next = AtomicUsize::new(0);
    let mut parts: Vec<(usize, Judged)> = thread::scope(|scope| {
        let handles: Vec<_> = (0..workers)
            .map(|_| {
                scope.spawn(|| {
                    let mut done = Vec::new();
                    loop {
                        let b = next.fetch_add(1, Ordering::Relaxed);
                        let Some(block) = blocks.get(b) else { return done };
                        done.push((b, plan.judge(block, progress)));
                    }
                })
            })
            .collect();
        handles.into_iter().flat_map(|h| h.join().expect("judging catches every panic")).collect()
    });
    parts.sort_by_key(|(block, _)| *block);
    let mut judged = plan.empty();
    for (_, part) in parts {
        judged.merge(part);
    }
    judged
}

/// What judging a family needs besides its polygons.
struct Plan<'a> {
    family: &'a Family,
    contenders: &'a [Contender],
    /// Every convention in use, ours first.
    samples: Vec<Own>,
    /// Per contender: its own convention, as an index into `samples`.
    own: Vec<usize>,
    /// Per contender: whether it takes the family.
    takes: Vec<bool>,
    runs: Vec<(f64, Range<usize>)>,
    /// Per polygon: its sweep run (empty without a sweep).
    run_of: Vec<usize>,
}

impl<'a> Plan<'a> {
    fn new(family: &'a Family, contenders: &'a [Contender]) -> Self {
        let mut samples = vec![Own::Sample(SampleOffset::CENTRE)];
        for c in contenders {
            if !samples.contains(&c.own()) {
                samples.push(c.own());
            }
        }
        let own = contenders.iter().map(|c| samples.iter().position(|&s| s == c.own()).unwrap_or(0)).collect();
        let runs = family.sweep.as_ref().map(|s| s.runs()).unwrap_or_default();
        let run_of = runs.iter().enumerate().flat_map(|(r, (_, range))| range.clone().map(move |_| r)).collect();
        let takes = contenders.iter().map(|c| c.accepts(family)).collect();
        Self { family, contenders, samples, own, takes, runs, run_of }
    }

    fn tiled(&self) -> bool {
        !self.family.tilings.is_empty()
    }

    /// Nothing judged yet.
    fn empty(&self) -> Judged {
        Judged {
            exact: Vec::new(),
            tallies: self.takes.iter().map(|&t| t.then(Tally::default)).collect(),
            run_tallies: self
                .takes
                .iter()
                .map(|&t| if t { vec![Tally::default(); self.runs.len()] } else { vec![] })
                .collect(),
            runs: self.runs.clone(),
            timed: vec![Vec::new(); self.contenders.len()],
        }
    }

    /// Judges the polygons of `canvases`, consecutive runs of polygons.
    fn judge(&self, canvases: &[Range<usize>], progress: &(dyn Fn() + Sync)) -> Judged {
        let mut judged = self.empty();
        let tiled = self.tiled();
        for canvas in canvases {
            // On tiling families: what the tiles drew together, per
            // contender, and the region they tile, per convention.
            let mut drawn_together: Vec<CoverageSink> = Vec::new();
            let mut region: Vec<CoverageSink> = Vec::new();
            if tiled {
                drawn_together = self.contenders.iter().map(|_| CoverageSink::new(SCREEN)).collect();
                region = self.samples.iter().map(|_| CoverageSink::new(SCREEN)).collect();
            }
            for index in canvas.clone() {
                let polygon = &self.family.polygons[index];
                let exact: Vec<ReferenceFill> = self.samples.iter().map(|&s| ReferenceFill::of(polygon, s)).collect();
                for (sink, e) in region.iter_mut().zip(&exact) {
                    spans::replay(&e.spans, 1, sink);
                }
                for (c, contender) in self.contenders.iter().enumerate() {
                    if !self.takes[c] {
                        continue;
                    }
                    let (outcome, drawn) = judge_one(contender, polygon, &exact[0], &exact[self.own[c]]);
                    if tiled {
                        spans::replay(&drawn, 1, &mut drawn_together[c]);
                    }
                    if timed(contender, &outcome.status) {
                        judged.timed[c].push(index);
                    }
                    if let Some(tally) = &mut judged.tallies[c] {
                        tally.record(index, &outcome, !tiled);
                    }
                    if let Some(&run) = self.run_of.get(index) {
                        judged.run_tallies[c][run].record(index, &outcome, !tiled);
                    }
                }
                judged.exact.push(exact.into_iter().next().map(|e| e.spans).unwrap_or_default());
                progress();
            }
            for (c, together) in drawn_together.iter().enumerate() {
                let report = together.report(&region[self.own[c]]);
                if let Some(tally) = &mut judged.tallies[c] {
                    tally.overdraw += report.overdrawn as u64;
                    tally.gaps += report.gaps as u64;
                }
            }
        }
        judged
    }
}

impl Judged {
    /// Appends `later`, judged on the polygons right after these.
    fn merge(&mut self, later: Judged) {
        self.exact.extend(later.exact);
        for (mine, theirs) in self.tallies.iter_mut().zip(&later.tallies) {
            if let (Some(mine), Some(theirs)) = (mine, theirs) {
                mine.merge(theirs);
            }
        }
        for (mine, theirs) in self.run_tallies.iter_mut().zip(&later.run_tallies) {
            for (mine, theirs) in mine.iter_mut().zip(theirs) {
                mine.merge(theirs);
            }
        }
        for (mine, theirs) in self.timed.iter_mut().zip(later.timed) {
            mine.extend(theirs);
        }
    }
}

/// Draws `polygon` with `contender` and compares it with the reference
/// under our convention (`ours`) and the contender's (`own`). Returns the
/// spans it drew, for the tiling.
fn judge_one(
    contender: &Contender,
    polygon: &Polygon,
    ours: &ReferenceFill,
    own: &ReferenceFill,
) -> (Outcome, Vec<Span>) {
    let mut recorder = Recorder::default();
    let status = match panic::catch_unwind(AssertUnwindSafe(|| contender.draw(polygon, &mut recorder))) {
        Ok(Ok(())) => Status::Drawn,
        Ok(Err(reason)) => Status::Refused(reason),
        Err(payload) => Status::Failed(format!("panicked: {}", panic_message(payload.as_ref()))),
    };
    let drawn = recorder.spans;
    let (normal, coverage) = (spans::normal_form(&drawn), OnceCell::new());
    let against_ours = ours.compare(&normal, &coverage, &drawn);
    let against_own = if own.own == ours.own { against_ours } else { own.compare(&normal, &coverage, &drawn) };
    let status = match status {
        Status::Drawn | Status::Refused(_) if against_ours.out_of_bounds > 0 => {
            Status::Failed(format!("{} spans outside the 320x200 target", against_ours.out_of_bounds))
        }
        status => status,
    };
    let judged = matches!(status, Status::Drawn);
    let bias = match (spans::centroid(&drawn), spans::centroid(&ours.spans)) {
        (Some(d), Some(e)) if judged => Some((d.0 - e.0, d.1 - e.1)),
        _ => None,
    };
    let outcome = Outcome {
        wrong: if judged { (against_ours.gaps + against_ours.extras) as u64 } else { 0 },
        wrong_own: if judged { (against_own.gaps + against_own.extras) as u64 } else { 0 },
        missing: if judged { against_ours.gaps as u64 } else { 0 },
        missing_own: if judged { against_own.gaps as u64 } else { 0 },
        overdraw: against_ours.overdrawn as u64,
        drawn: spans::pixel_count(&drawn),
        bias,
        status,
    };
    (outcome, drawn)
}

/// Whether a fill is timed: not where it failed; a method on what it
/// refused too (deciding to refuse is its work), a peer only on what it
/// drew (what it declines it is never given).
fn timed(contender: &Contender, status: &Status) -> bool {
    match status {
        Status::Drawn => true,
        Status::Refused(_) => !contender.is_peer(),
        Status::Failed(_) => false,
    }
}

fn panic_message(payload: &(dyn std::any::Any + Send)) -> String {
    payload
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "a non-text panic".to_string())
}

/// Runs `f` with the panic hook silenced, so that the panics the judging
/// catches do not print; the previous hook is back afterwards.
pub fn quietly<T>(f: impl FnOnce() -> T) -> T {
    let previous = panic::take_hook();
    panic::set_hook(Box::new(|_| {}));
    let result = f();
    panic::set_hook(previous);
    result
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::corpus::Group;
    use crate::peers::{Clock, Peer, PeerInfo};
    use raster::{MethodId, Point, SpanSink};

    /// A peer that misbehaves on purpose, by colour: 1 draws the exact
    /// fill, 2 panics, 3 declines, 4 draws everything twice, 5 writes off
    /// the target.
    struct Misfit;

    static MISFIT: PeerInfo = PeerInfo {
        name: "misfit",
        source: "test",
        summary: "test",
        own: Own::Sample(SampleOffset::CENTRE),
        clock: Clock {
            before: "test",
            setup: "test",
            fill: "test",
            surface: "test",
            pixel_format: "test",
            anti_aliasing: "test",
        },
        variant_of: None,
    };

    impl Peer for Misfit {
        fn info(&self) -> &PeerInfo {
            &MISFIT
        }

        fn draw(&self, polygon: &Polygon, sink: &mut dyn SpanSink) -> Result<(), &'static str> {
            match polygon.color {
                2 => panic!("misfit"),
                3 => return Err("coordinates out of the method's range"),
                5 => sink.span(-1, 0, 1, 1),
                _ => {}
            }
            for _ in 0..if polygon.color == 4 { 2 } else { 1 } {
                reference::fill(polygon, SampleOffset::CENTRE, sink);
            }
            Ok(())
        }

        fn pass<'a>(&self, _polygons: &[&'a Polygon]) -> Box<dyn FnMut() + 'a> {
            Box::new(|| {})
        }
    }

    fn square(color: u8) -> Polygon {
        Polygon::new(vec![Point::new(0, 0), Point::new(2560, 0), Point::new(2560, 2560), Point::new(0, 2560)], color)
    }

    fn family(polygons: Vec<Polygon>, tilings: Vec<Range<usize>>) -> Family {
        Family { name: "test", group: Group::Stress, description: "", polygons, tilings, sweep: None }
    }

    fn tally(family: &Family) -> Tally {
        let judged = quietly(|| judge(family, &[Contender::Peer(&Misfit)], &|| {}));
        judged.tallies[0].clone().unwrap()
    }

    #[test]
    fn an_exact_fill_has_nothing_wrong() {
        let t = tally(&family(vec![square(1)], vec![]));
        assert_eq!((t.wrong_pixels, t.overdraw, t.failures, t.faulty_polygons), (0, 0, 0, 0));
        assert_eq!(t.drawn_pixels, 100);
        assert_eq!(t.bias.mean(), Some((0.0, 0.0)));
    }

    #[test]
    fn panics_and_stray_spans_are_failures_and_refusals_are_not() {
        let t = tally(&family(vec![square(2), square(3), square(5)], vec![]));
        assert_eq!((t.failures, t.refusals, t.faulty_polygons), (2, 1, 2));
        assert_eq!(t.first_failure.as_deref(), Some("polygon 0: panicked: misfit"));
        assert_eq!(t.first_refusal.as_deref(), Some("polygon 1: coordinates out of the method's range"));
    }

    #[test]
    fn drawing_twice_is_overdraw_not_wrong() {
        let t = tally(&family(vec![square(4)], vec![]));
        assert_eq!((t.wrong_pixels, t.overdraw, t.faulty_polygons), (0, 100, 1));
    }

    #[test]
    fn tilings_count_overdraw_and_gaps_between_tiles() {
        // Two copies of one square overlap everywhere; a declined tile
        // leaves its region as a gap.
        let one_tiling = |n| std::iter::once(0..n).collect();
        let t = tally(&family(vec![square(1), square(1), square(3)], one_tiling(3)));
        assert_eq!((t.overdraw, t.gaps, t.wrong_pixels), (100, 0, 0));
        let t = tally(&family(vec![square(3)], one_tiling(1)));
        assert_eq!((t.overdraw, t.gaps), (0, 100));
    }

    #[test]
    fn failed_polygons_and_what_a_peer_declines_are_not_timed() {
        let judged = quietly(|| {
            judge(&family(vec![square(1), square(2), square(3)], vec![]), &[Contender::Peer(&Misfit)], &|| {})
        });
        assert_eq!(judged.timed[0], vec![0]);
        assert_eq!(judged.exact.len(), 3);
    }

    #[test]
    fn what_a_method_declines_is_timed() {
        // Two squares in one polygon: `abrash_int` declines more than one
        // contour, and deciding so is its work.
        let mut two = square(1);
        two.contours.push(square(1).contours.remove(0).into_iter().map(|p| Point::new(p.x + 5120, p.y)).collect());
        let judged =
            quietly(|| judge(&family(vec![square(1), two], vec![]), &[Contender::Method(MethodId::AbrashInt)], &|| {}));
        assert_eq!(judged.tallies[0].as_ref().map(|t| t.refusals), Some(1));
        assert_eq!(judged.timed[0], vec![0, 1]);
    }
}
