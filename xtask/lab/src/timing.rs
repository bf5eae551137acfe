//! Wall-clock timing of fill passes, and the bounds every fill is compared
//! with. Nothing here is ever asserted: speed is reported only.

use std::hint::black_box;
use std::ops::Range;
use std::time::{Duration, Instant};

use raster::stores::set_bytes;
use raster::{Framebuffer, Polygon, SpanSink, SCREEN};
use serde::Serialize;

use crate::contender::Contender;
use crate::corpus::Family;
use crate::lane::Lane;
use crate::measure::Judged;
use crate::peers::Clock;
use crate::spans::{self, Span};
use crate::stats::{median, Ratio, Spread};

/// How hard to time.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Timing {
    /// Repeats of every lane, timed in turn: the samples of its spread.
    pub repeats: usize,
    /// Each repeat runs the pass as often as it takes to last this long.
    pub min_repeat: Duration,
}

/// Nanoseconds per polygon of one lane, one figure a repeat; empty where
/// nothing was timed (no polygons).
pub type Samples = Vec<f64>;

impl Timing {
    pub const FULL: Timing = Timing { repeats: 7, min_repeat: Duration::from_millis(20) };
    pub const QUICK: Timing = Timing { repeats: 3, min_repeat: Duration::from_millis(2) };

    /// Nanoseconds per polygon of each of `passes` (a pass and the
    /// polygons it fills) in every repeat, after one warm-up pass each:
    /// within a repeat every pass is timed in turn, so that a change in the
    /// machine's load falls on all of them alike and the ratios between
    /// them, repeat by repeat, hold ([`crate::stats::Ratio::paired`]).
    pub fn samples_each(&self, mut passes: Vec<(&mut dyn FnMut(), usize)>) -> Vec<Samples> {
        // Each pass runs as often as it takes to last `min_repeat`.
        let counts: Vec<u32> = passes
            .iter_mut()
            .map(|(pass, _)| {
                let start = Instant::now();
                pass();
                let once = start.elapsed().max(Duration::from_nanos(1));
                (self.min_repeat.as_nanos() / once.as_nanos()).clamp(1, 1 << 20) as u32
            })
            .collect();
        let mut samples = vec![Vec::with_capacity(self.repeats); passes.len()];
        for _ in 0..self.repeats {
            for (((pass, polygons), &count), samples) in passes.iter_mut().zip(&counts).zip(&mut samples) {
                let start = Instant::now();
                for _ in 0..count {
                    pass();
                }
                samples.push(start.elapsed().as_nanos() as f64 / f64::from(count) / (*polygons).max(1) as f64);
            }
        }
        for ((_, polygons), samples) in passes.iter().zip(&mut samples) {
            if *polygons == 0 {
                samples.clear();
            }
        }
        samples
    }
}

/// What a fill is measured against: what writing its pixels alone costs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Bound {
    /// One `memset` (`<[u8]>::fill`, the safe `write_bytes`) of each
    /// polygon's exact pixel count: what its bytes would cost if they were
    /// one run, which no polygon narrower than the screen is.
    Memset,
    /// The exact reference's spans stored straight into a 320x200 byte
    /// buffer by the framebuffer's own span store
    /// ([`raster::stores::set_bytes`]), in a loop over the recorded spans with
    /// no call per span: the true lower bound of a fill into that
    /// framebuffer, which must store the same spans and find them too.
    Store,
    /// The same spans sent one by one through `&mut dyn SpanSink` into a
    /// [`Framebuffer`]: what the sink's interface costs a method that is not
    /// compiled for its sink (a call through the vtable, the contract check
    /// and the store per span).
    DynSink,
}

impl Bound {
    pub const ALL: [Bound; 3] = [Bound::Memset, Bound::Store, Bound::DynSink];

    pub const fn name(self) -> &'static str {
        match self {
            Bound::Memset => "memset bound",
            Bound::Store => "store bound",
            Bound::DynSink => "dyn-sink replay",
        }
    }

    pub const fn source(self) -> &'static str {
        match self {
            Bound::Memset => "one memset (slice fill) of each polygon's exact pixel count",
            Bound::Store => "the reference's spans stored into a 320x200 buffer, no call per span",
            Bound::DynSink => "the reference's spans sent through &mut dyn SpanSink into a Framebuffer",
        }
    }

    /// What it does inside the timed pass and what before it.
    pub const fn clock(self) -> Clock {
        const BUFFER: &str = "a 320x200 byte buffer";
        match self {
            Bound::Memset => Clock {
                before: "each polygon's exact pixel count",
                setup: "none",
                fill: "one slice fill (`memset`) of that many bytes",
                surface: BUFFER,
                pixel_format: "8-bit",
                anti_aliasing: "none (the reference's pixels)",
            },
            Bound::Store => Clock {
                before: "the reference's spans, as byte ranges of the buffer",
                setup: "none",
                fill: "the framebuffer's span store (`set_bytes`) a span, no call per span",
                surface: BUFFER,
                pixel_format: "8-bit",
                anti_aliasing: "none (the reference's pixels)",
            },
            Bound::DynSink => Clock {
                before: "the reference's spans",
                setup: "none",
                fill: "`SpanSink::span` through `&mut dyn SpanSink` a span (the contract check, the store)",
                surface: "320x200 `Framebuffer`",
                pixel_format: "8-bit index",
                anti_aliasing: "none (the reference's pixels)",
            },
        }
    }

    /// One pass over the polygons whose exact spans are `exact`.
    pub fn pass<'a>(self, exact: &[&'a [Span]]) -> Box<dyn FnMut() + 'a> {
        match self {
            Bound::Memset => {
                let counts: Vec<usize> = exact.iter().map(|s| spans::pixel_count(s) as usize).collect();
                let mut bytes = vec![0u8; SCREEN.width as usize * SCREEN.height as usize];
                Box::new(move || {
                    for &count in &counts {
                        let len = count.min(bytes.len());
                        black_box(&mut bytes[..len]).fill(0x55);
                    }
                })
            }
            Bound::Store => {
                // Byte ranges of the visible spans, worked out before timing.
                let ranges: Vec<Vec<(usize, usize)>> = exact.iter().map(|s| spans::byte_ranges(s)).collect();
                let mut bytes = vec![0u8; SCREEN.width as usize * SCREEN.height as usize];
                Box::new(move || {
                    let bytes = black_box(&mut bytes[..]);
                    for polygon in &ranges {
                        for &(start, end) in polygon {
                            set_bytes(&mut bytes[start..end], 0x55);
                        }
                    }
                })
            }
            Bound::DynSink => {
                let exact = exact.to_vec();
                let mut screen = Framebuffer::new(SCREEN);
                Box::new(move || {
                    let sink: &mut dyn SpanSink = black_box(&mut screen);
                    for spans in &exact {
                        spans::replay(spans, 0x55, sink);
                    }
                })
            }
        }
    }
}

/// The samples of every lane timed on a family in one run.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Speeds {
    /// Per contender, in the order given; empty where nothing was timed.
    pub contenders: Vec<Samples>,
    /// Per bound, in [`Bound::ALL`] order.
    pub bounds: Vec<Samples>,
    /// Per lane of "what modelling costs", in the order given; empty
    /// where the lane was not timed.
    pub lanes: Vec<Samples>,
    /// On sweeps timed per value: the same, for each run of the sweep.
    pub runs: Vec<Speeds>,
}

/// How many timing jobs [`time_family`] runs on `family`, for progress.
pub fn jobs(family: &Family, lanes: usize) -> u64 {
    let lanes = lanes as u64;
    match &family.sweep {
        Some(sweep) if sweep.axis.timed_per_value() => lanes * sweep.runs().len() as u64,
        _ => lanes,
    }
}

/// A lane's time on a family, over every run and repeat, as results.json
/// gives it for every contender, bound and lane of "what modelling costs".
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Timed {
    /// The median ns per polygon of every repeat of every run.
    pub ns_per_polygon: Option<f64>,
    /// The least and most of those repeats.
    pub ns_min: Option<f64>,
    pub ns_max: Option<f64>,
    /// Its time over `exact`'s on the same family, repeat by repeat (the
    /// two timed in turn), every run's repeats together, with its interval.
    pub vs_exact: Option<Ratio>,
    /// The same over the store bound's.
    pub vs_store: Option<Ratio>,
    /// Each run alone: its median and its ratio to `exact`'s.
    pub runs: Vec<RunFigures>,
    /// ns per polygon in every repeat, run by run.
    pub samples_ns: Vec<Samples>,
}

/// One run's figures of a lane.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RunFigures {
    pub ns_per_polygon: Option<f64>,
    pub vs_exact: Option<Ratio>,
}

impl Timed {
    /// From a lane's samples in each run, and `exact`'s and the store
    /// bound's in the same repeats of the same runs.
    pub fn of(runs: &[&Samples], exact: &[&Samples], store: &[&Samples]) -> Timed {
        let all: Samples = runs.iter().flat_map(|s| s.iter().copied()).collect();
        let paired = |others: &[&Samples]| {
            let (mine, theirs): (Samples, Samples) = runs
                .iter()
                .zip(others)
                .filter(|(a, b)| a.len() == b.len())
                .flat_map(|(a, b)| a.iter().copied().zip(b.iter().copied()))
                .unzip();
            Ratio::paired(&mine, &theirs)
        };
        let spread = Spread::of(&all);
        Timed {
            ns_per_polygon: spread.map(|s| s.median),
            ns_min: spread.map(|s| s.min),
            ns_max: spread.map(|s| s.max),
            vs_exact: paired(exact),
            vs_store: paired(store),
            runs: runs
                .iter()
                .zip(exact)
                .map(|(mine, exact)| RunFigures { ns_per_polygon: median(mine), vs_exact: Ratio::paired(mine, exact) })
                .collect(),
            samples_ns: runs.iter().map(|s| s.to_vec()).collect(),
        }
    }
}

/// Times every contender that takes `family` on the polygons it did not
/// fail on, and the bounds and the lanes of "what modelling costs" on all
/// of them (`lanes`: `None` where a lane is not timed on the family), all
/// in turn within each repeat; per sweep value where the family's axis asks for it, the
/// family's figure in each repeat then being the mean over its polygons.
/// `progress` is told of each job done.
pub fn time_family(
    family: &Family,
    judged: &Judged,
    contenders: &[Contender],
    lanes: &[Option<Lane>],
    timing: Timing,
    progress: &dyn Fn(),
) -> Speeds {
    let per_value = family.sweep.as_ref().is_some_and(|s| s.axis.timed_per_value());
    if !per_value {
        return time_range(family, judged, contenders, lanes, timing, 0..family.polygons.len(), progress);
    }
    let runs: Vec<Speeds> = judged
        .runs
        .iter()
        .map(|(_, range)| time_range(family, judged, contenders, lanes, timing, range.clone(), progress))
        .collect();
    let all = |r: usize| judged.runs[r].1.len();
    let contender_means = (0..contenders.len())
        .map(|c| {
            let timed_in = |r: usize| judged.timed[c].iter().filter(|&&i| judged.runs[r].1.contains(&i)).count();
            weighted_mean(&runs, &|s| &s.contenders[c], &timed_in)
        })
        .collect();
    let bound_means = (0..Bound::ALL.len()).map(|b| weighted_mean(&runs, &|s| &s.bounds[b], &all)).collect();
    let lane_means = (0..lanes.len()).map(|l| weighted_mean(&runs, &|s| &s.lanes[l], &all)).collect();
    Speeds { contenders: contender_means, bounds: bound_means, lanes: lane_means, runs }
}

/// Repeat by repeat, the mean time per polygon over the sweep's runs, each
/// weighted by the polygons timed in it.
fn weighted_mean(runs: &[Speeds], pick: &dyn Fn(&Speeds) -> &Samples, counts: &dyn Fn(usize) -> usize) -> Samples {
    let repeats = runs.iter().map(|s| pick(s).len()).max().unwrap_or(0);
    (0..repeats)
        .filter_map(|repeat| {
            let (mut time, mut n) = (0.0, 0);
            for (r, speeds) in runs.iter().enumerate() {
                if let Some(ns) = pick(speeds).get(repeat) {
                    time += ns * counts(r) as f64;
                    n += counts(r);
                }
            }
            (n > 0).then(|| time / n as f64)
        })
        .collect()
}

fn time_range(
    family: &Family,
    judged: &Judged,
    contenders: &[Contender],
    lanes: &[Option<Lane>],
    timing: Timing,
    range: Range<usize>,
    progress: &dyn Fn(),
) -> Speeds {
    // Every contender that takes the family, every bound and every lane
    // timed there, in turn.
    let polygons: Vec<Vec<&Polygon>> = (0..contenders.len())
        .map(|c| judged.timed[c].iter().filter(|i| range.contains(i)).map(|&i| &family.polygons[i]).collect())
        .collect();
    let all: Vec<&Polygon> = family.polygons[range.clone()].iter().collect();
    let exact: Vec<&[Span]> = judged.exact[range.clone()].iter().map(Vec::as_slice).collect();
    let timed: Vec<usize> = (0..contenders.len()).filter(|&c| judged.tallies[c].is_some()).collect();
    let lanes_timed: Vec<usize> = (0..lanes.len()).filter(|&l| lanes[l].is_some()).collect();
    let mut passes: Vec<(Box<dyn FnMut() + '_>, usize)> =
        timed.iter().map(|&c| (contenders[c].pass(&polygons[c]), polygons[c].len())).collect();
    passes.extend(Bound::ALL.iter().map(|bound| (bound.pass(&exact), exact.len())));
    passes.extend(lanes_timed.iter().filter_map(|&l| Some((lanes[l]?.pass(&all), all.len()))));
    let mut samples = timing.samples_each(passes.iter_mut().map(|(p, n)| (&mut **p as &mut dyn FnMut(), *n)).collect());
    for _ in 0..contenders.len() + Bound::ALL.len() + lanes.len() {
        progress();
    }
    let lane_samples = samples.split_off(timed.len() + Bound::ALL.len());
    let bound_samples = samples.split_off(timed.len());
    let mut contender_samples = vec![Samples::new(); contenders.len()];
    for (&c, ns) in timed.iter().zip(samples) {
        contender_samples[c] = ns;
    }
    let mut lane_all = vec![Samples::new(); lanes.len()];
    for (&l, ns) in lanes_timed.iter().zip(lane_samples) {
        lane_all[l] = ns;
    }
    Speeds { contenders: contender_samples, bounds: bound_samples, lanes: lane_all, runs: vec![] }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn no_polygons_take_no_time() {
        assert_eq!(Timing::QUICK.samples_each(vec![(&mut || {}, 0)]), vec![Samples::new()]);
    }

    #[test]
    fn passes_timed_in_turn_each_run_every_repeat() {
        let (mut a, mut b) = (0, 0);
        let timing = Timing { repeats: 3, min_repeat: Duration::ZERO };
        let (mut pass_a, mut pass_b) = (|| a += 1, || b += 1);
        let times = timing.samples_each(vec![(&mut pass_a, 5), (&mut pass_b, 0)]);
        assert_eq!(times[0].len(), 3);
        assert!(times[0].iter().all(|&ns| ns >= 0.0));
        assert!(times[1].is_empty());
        assert_eq!((a, b), (4, 4));
    }

    #[test]
    fn a_sweep_figure_weighs_each_value_by_its_polygons_repeat_by_repeat() {
        let run = |ns: Samples| Speeds { bounds: vec![ns], ..Speeds::default() };
        let runs = [run(vec![10.0, 20.0]), run(vec![40.0, 50.0])];
        let mean = weighted_mean(&runs, &|s| &s.bounds[0], &|r| [3, 1][r]);
        assert_eq!(mean, vec![17.5, 27.5]);
    }
}
