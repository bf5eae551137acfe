//! Wall-clock timing of fill passes, and the bounds every fill is compared
//! with. Nothing here is ever asserted: speed is reported only.

use std::hash::{DefaultHasher, Hash, Hasher};
use std::hint::black_box;
use std::ops::Range;
use std::time::{Duration, Instant};

use rand::seq::SliceRandom;
use rand::SeedableRng;
use rand_pcg::Pcg64Mcg;
use raster::stores::set_bytes;
use raster::{Framebuffer, MethodId, Polygon, SpanSink, SCREEN};
use serde::{Deserialize, Serialize};

use crate::contender::Contender;
use crate::corpus::Family;
use crate::lane::Lane;
use crate::measure::Judged;
use crate::peers::Clock;
use crate::spans::{self, Recorder, Span};
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
    /// within a repeat every pass is timed in turn, in an order `order`
    /// draws (the same in every repeat), so that a change in the machine's
    /// load falls on all of them alike and the ratios between them, repeat
    /// by repeat, hold ([`crate::stats::Ratio::paired`]), and no pass
    /// always follows the same other.
    pub fn samples_each(&self, mut passes: Vec<(&mut dyn FnMut(), usize)>, order: &mut Order) -> Vec<Samples> {
        let turns = order.next(passes.len());
        // Each pass runs as often as it takes to last `min_repeat`.
        let mut counts = vec![1u32; passes.len()];
        for &i in &turns {
            let start = Instant::now();
            (passes[i].0)();
            let once = start.elapsed().max(Duration::from_nanos(1));
            counts[i] = (self.min_repeat.as_nanos() / once.as_nanos()).clamp(1, 1 << 20) as u32;
        }
        let mut samples = vec![Vec::with_capacity(self.repeats); passes.len()];
        for _ in 0..self.repeats {
            for &i in &turns {
                let (pass, polygons) = &mut passes[i];
                let start = Instant::now();
                for _ in 0..counts[i] {
                    pass();
                }
                samples[i].push(start.elapsed().as_nanos() as f64 / f64::from(counts[i]) / (*polygons).max(1) as f64);
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

/// The order passes are timed in within a repeat: a permutation drawn
/// afresh for every set of passes (every family, every sweep value, the
/// show's entries) from one generator, seeded once per launch
/// ([`Order::seeded`]), so a launch's orders are known from its seed.
pub struct Order(Pcg64Mcg);

impl Order {
    pub fn seeded(seed: u64) -> Self {
        Order(Pcg64Mcg::seed_from_u64(seed))
    }

    /// The next permutation of `0..n`.
    pub fn next(&mut self, n: usize) -> Vec<usize> {
        let mut order: Vec<usize> = (0..n).collect();
        order.shuffle(&mut self.0);
        order
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

/// What a launch is told of a family by the judging before it: which
/// polygons each contender is timed on, and which lanes are timed.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FamilyPlan {
    pub family: String,
    /// Per contender, in the order given: the polygons it is timed on
    /// ([`Judged::timed`]), or `None` where it does not take the family.
    pub timed: Vec<Option<Vec<usize>>>,
    /// Per lane of [`Lane::all`]: whether it is timed on the family.
    pub lanes: Vec<bool>,
}

impl FamilyPlan {
    pub fn of(family: &Family, judged: &Judged, lanes: &[Option<Lane>]) -> Self {
        FamilyPlan {
            family: family.name.to_string(),
            timed: judged
                .tallies
                .iter()
                .zip(&judged.timed)
                .map(|(t, timed)| t.as_ref().map(|_| timed.clone()))
                .collect(),
            lanes: lanes.iter().map(Option::is_some).collect(),
        }
    }

    /// The lanes timed, in [`Lane::all`] order: `None` for those not.
    fn lanes(&self) -> Vec<Option<Lane>> {
        Lane::all().into_iter().zip(&self.lanes).map(|(lane, &timed)| timed.then_some(lane)).collect()
    }
}

/// The samples of every lane timed on a family in one launch.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Speeds {
    /// Per contender, in the order given; empty where nothing was timed.
    pub contenders: Vec<Samples>,
    /// Per contender: `exact` timed on the very polygons that contender
    /// is timed on, in the same repeats, which its time is set against
    /// (empty where it is not timed; `exact`'s own samples where its
    /// polygons are all of `exact`'s).
    pub exact_on: Vec<Samples>,
    /// Per bound, in [`Bound::ALL`] order.
    pub bounds: Vec<Samples>,
    /// Per lane of "what modelling costs", in the order given; empty
    /// where the lane was not timed.
    pub lanes: Vec<Samples>,
    /// On sweeps timed per value: the same, for each run of the sweep.
    pub runs: Vec<Speeds>,
    /// Timed frames of ours checked against their judged pixels.
    pub screens_checked: usize,
}

/// How many timing jobs [`time_family`] runs on `family`, for progress.
pub fn jobs(family: &Family, lanes: usize) -> u64 {
    let lanes = lanes as u64;
    match &family.sweep {
        Some(sweep) if sweep.axis.timed_per_value() => lanes * sweep.runs().len() as u64,
        _ => lanes,
    }
}

/// A lane's time on a family, over every launch and repeat, as
/// results.json gives it for every contender, bound and lane of "what
/// modelling costs".
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Timed {
    /// The median ns per polygon of every repeat of every launch.
    pub ns_per_polygon: Option<f64>,
    /// The least and most of those repeats.
    pub ns_min: Option<f64>,
    pub ns_max: Option<f64>,
    /// Its time over `exact`'s on the same polygons across launches
    /// ([`Ratio::across`] of each launch's [`LaunchFigures::vs_exact`]):
    /// no interval with one launch.
    pub vs_exact: Option<Ratio>,
    /// The same over the store bound's.
    pub vs_store: Option<Ratio>,
    /// Each launch alone: its median and its ratios within it.
    pub launches: Vec<LaunchFigures>,
    /// ns per polygon in every repeat, launch by launch.
    pub samples_ns: Vec<Samples>,
}

/// One launch's figures of a lane.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LaunchFigures {
    pub ns_per_polygon: Option<f64>,
    /// Its time over `exact`'s on the same polygons, repeat by repeat (the
    /// two timed in turn), with its interval within the launch.
    pub vs_exact: Option<Ratio>,
    /// The same over the store bound's.
    pub vs_store: Option<Ratio>,
}

impl Timed {
    /// From a lane's samples in each launch, and those of `exact` (on the
    /// same polygons) and of the store bound in the same repeats of the
    /// same launches.
    pub fn of(launches: &[&Samples], exact: &[&Samples], store: &[&Samples]) -> Timed {
        let all: Samples = launches.iter().flat_map(|s| s.iter().copied()).collect();
        let figures: Vec<LaunchFigures> = launches
            .iter()
            .zip(exact)
            .zip(store)
            .map(|((mine, exact), store)| LaunchFigures {
                ns_per_polygon: median(mine),
                vs_exact: Ratio::paired(mine, exact),
                vs_store: Ratio::paired(mine, store),
            })
            .collect();
        let across = |pick: fn(&LaunchFigures) -> Option<Ratio>| {
            Ratio::across(&figures.iter().filter_map(pick).collect::<Vec<Ratio>>())
        };
        let spread = Spread::of(&all);
        Timed {
            ns_per_polygon: spread.map(|s| s.median),
            ns_min: spread.map(|s| s.min),
            ns_max: spread.map(|s| s.max),
            vs_exact: across(|f| f.vs_exact),
            vs_store: across(|f| f.vs_store),
            launches: figures,
            samples_ns: launches.iter().map(|s| s.to_vec()).collect(),
        }
    }
}

/// Times every contender that takes `family` on the polygons `plan` says,
/// `exact` on each of those sets of polygons, the bounds on all of them
/// (`exact`'s spans: `exact`) and the lanes the plan times, all in turn
/// within each repeat, in orders drawn from `order`; per sweep value where
/// the family's axis asks for it, the family's figure in each repeat then
/// being the mean over its polygons. Then checks that each pass of ours
/// left the pixels its judged fill draws ([`check_screen`]): an error
/// where not. `progress` is told of each job done.
pub fn time_family(
    family: &Family,
    plan: &FamilyPlan,
    exact: &[Vec<Span>],
    contenders: &[Contender],
    timing: Timing,
    order: &mut Order,
    progress: &dyn Fn(),
) -> Result<Speeds, String> {
    let lanes = plan.lanes();
    let job = Job { family, plan, exact, contenders, lanes: &lanes, timing };
    let mut time = |range: Range<usize>| job.time(range, order, progress);
    let per_value = family.sweep.as_ref().filter(|s| s.axis.timed_per_value());
    let Some(sweep) = per_value else { return time(0..family.polygons.len()) };
    let values = sweep.runs();
    let runs: Vec<Speeds> = values.iter().map(|(_, range)| time(range.clone())).collect::<Result<_, _>>()?;
    let all = |r: usize| values[r].1.len();
    let timed_in = |c: usize, r: usize| {
        plan.timed[c].as_ref().map_or(0, |t| t.iter().filter(|&&i| values[r].1.contains(&i)).count())
    };
    let contender_means =
        (0..contenders.len()).map(|c| weighted_mean(&runs, &|s| &s.contenders[c], &|r| timed_in(c, r)));
    let exact_means = (0..contenders.len()).map(|c| weighted_mean(&runs, &|s| &s.exact_on[c], &|r| timed_in(c, r)));
    let bound_means = (0..Bound::ALL.len()).map(|b| weighted_mean(&runs, &|s| &s.bounds[b], &all)).collect();
    let lane_means = (0..lanes.len()).map(|l| weighted_mean(&runs, &|s| &s.lanes[l], &all)).collect();
    Ok(Speeds {
        contenders: contender_means.collect(),
        exact_on: exact_means.collect(),
        bounds: bound_means,
        lanes: lane_means,
        screens_checked: runs.iter().map(|s| s.screens_checked).sum(),
        runs,
    })
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

/// What timing a family takes, besides the polygons of the moment.
struct Job<'a> {
    family: &'a Family,
    plan: &'a FamilyPlan,
    /// `exact`'s spans of every polygon of the family.
    exact: &'a [Vec<Span>],
    contenders: &'a [Contender],
    /// The lanes timed, in [`Lane::all`] order.
    lanes: &'a [Option<Lane>],
    timing: Timing,
}

impl Job<'_> {
    /// Times the polygons of `range` ([`time_family`]).
    fn time(&self, range: Range<usize>, order: &mut Order, progress: &dyn Fn()) -> Result<Speeds, String> {
        let Job { family, plan, exact, contenders, lanes, timing } = *self;
        // Per contender, the polygons of the range it is timed on.
        let subsets: Vec<Option<Vec<usize>>> = plan
            .timed
            .iter()
            .map(|timed| Some(timed.as_ref()?.iter().copied().filter(|i| range.contains(i)).collect()))
            .collect();
        let polygons_of = |subset: &[usize]| -> Vec<&Polygon> { subset.iter().map(|&i| &family.polygons[i]).collect() };
        let polygons: Vec<Vec<&Polygon>> =
            subsets.iter().map(|s| s.as_deref().map(polygons_of).unwrap_or_default()).collect();
        let timed: Vec<usize> = (0..contenders.len()).filter(|&c| subsets[c].is_some()).collect();
        // `exact` again on each other set of polygons a contender is timed on.
        let exact_at = contenders.iter().position(|c| matches!(c, Contender::Method(MethodId::Exact)));
        let exact_set = exact_at.and_then(|e| subsets[e].clone());
        let mut other_sets: Vec<Vec<usize>> = Vec::new();
        for subset in subsets.iter().flatten() {
            if exact_at.is_some() && exact_set.as_ref() != Some(subset) && !other_sets.contains(subset) {
                other_sets.push(subset.clone());
            }
        }
        let all: Vec<&Polygon> = family.polygons[range.clone()].iter().collect();
        let spans: Vec<&[Span]> = exact[range.clone()].iter().map(Vec::as_slice).collect();
        let lanes_timed: Vec<usize> = (0..lanes.len()).filter(|&l| lanes[l].is_some()).collect();
        let mut screens: Vec<Framebuffer> = timed.iter().map(|_| Framebuffer::new(SCREEN)).collect();
        let mut passes: Vec<(Box<dyn FnMut() + '_>, usize)> = timed
            .iter()
            .zip(&mut screens)
            .map(|(&c, screen)| {
                let pass =
                    contenders[c].pass_into(&polygons[c], screen).unwrap_or_else(|| contenders[c].pass(&polygons[c]));
                (pass, polygons[c].len())
            })
            .collect();
        if let Some(e) = exact_at {
            passes.extend(other_sets.iter().map(|set| (contenders[e].pass(&polygons_of(set)), set.len())));
        }
        passes.extend(Bound::ALL.iter().map(|bound| (bound.pass(&spans), spans.len())));
        passes.extend(lanes_timed.iter().filter_map(|&l| Some((lanes[l]?.pass(&all), all.len()))));
        let mut samples =
            timing.samples_each(passes.iter_mut().map(|(p, n)| (&mut **p as &mut dyn FnMut(), *n)).collect(), order);
        drop(passes);
        for _ in 0..contenders.len() + Bound::ALL.len() + lanes.len() {
            progress();
        }
        let mut screens_checked = 0;
        for (&c, screen) in timed.iter().zip(&screens) {
            if !contenders[c].is_peer() {
                check_screen(&contenders[c], &polygons[c], screen).map_err(|e| format!("{}: {e}", family.name))?;
                screens_checked += 1;
            }
        }
        let lane_samples = samples.split_off(timed.len() + other_sets.len() + Bound::ALL.len());
        let bound_samples = samples.split_off(timed.len() + other_sets.len());
        let other_samples = samples.split_off(timed.len());
        let mut contender_samples = vec![Samples::new(); contenders.len()];
        for (&c, ns) in timed.iter().zip(samples) {
            contender_samples[c] = ns;
        }
        let exact_on = (0..contenders.len())
            .map(|c| {
                let (Some(e), Some(subset)) = (exact_at, &subsets[c]) else { return Samples::new() };
                match other_sets.iter().position(|set| set == subset) {
                    Some(s) => other_samples[s].clone(),
                    None => contender_samples[e].clone(),
                }
            })
            .collect();
        let mut lane_all = vec![Samples::new(); lanes.len()];
        for (&l, ns) in lanes_timed.iter().zip(lane_samples) {
            lane_all[l] = ns;
        }
        Ok(Speeds {
            contenders: contender_samples,
            exact_on,
            bounds: bound_samples,
            lanes: lane_all,
            runs: vec![],
            screens_checked,
        })
    }
}

/// Fails unless `screen`, into which `contender` (one of ours) filled
/// `polygons` in its timed pass, holds the pixels of its judged fill: each
/// polygon drawn by [`Contender::draw`] into a recorder, through `&mut dyn
/// SpanSink`, as the judging draws it, and its spans replayed in order
/// into a fresh framebuffer in the polygon's colour. The timed pass is the
/// fill compiled for the framebuffer, wide and masked stores included;
/// this holds it to the pixels that were judged. The error names both
/// frames' hashes and the first pixel that differs.
pub fn check_screen(contender: &Contender, polygons: &[&Polygon], screen: &Framebuffer) -> Result<(), String> {
    let mut judged = Framebuffer::new(SCREEN);
    for polygon in polygons {
        let mut recorder = Recorder::default();
        let _ = contender.draw(polygon, &mut recorder);
        spans::replay(&recorder.spans, polygon.color, &mut judged);
    }
    let (timed, judged) = (screen.pixels(), judged.pixels());
    let Some(first) = timed.iter().zip(judged).position(|(a, b)| a != b) else { return Ok(()) };
    let width = SCREEN.width as usize;
    Err(format!(
        "`{}`'s timed framebuffer (hash {:016x}) is not its judged pixels (hash {:016x}): first at ({}, {}), {} \
         timed, {} judged",
        contender.name(),
        pixel_hash(timed),
        pixel_hash(judged),
        first % width,
        first / width,
        timed[first],
        judged[first]
    ))
}

/// A hash of a frame's pixels, to name it in a message.
fn pixel_hash(pixels: &[u8]) -> u64 {
    let mut hasher = DefaultHasher::new();
    pixels.hash(&mut hasher);
    hasher.finish()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::corpus::Group;
    use raster::Point;

    fn order() -> Order {
        Order::seeded(1)
    }

    #[test]
    fn no_polygons_take_no_time() {
        assert_eq!(Timing::QUICK.samples_each(vec![(&mut || {}, 0)], &mut order()), vec![Samples::new()]);
    }

    #[test]
    fn passes_timed_in_turn_each_run_every_repeat() {
        let (mut a, mut b) = (0, 0);
        let timing = Timing { repeats: 3, min_repeat: Duration::ZERO };
        let (mut pass_a, mut pass_b) = (|| a += 1, || b += 1);
        let times = timing.samples_each(vec![(&mut pass_a, 5), (&mut pass_b, 0)], &mut order());
        assert_eq!(times[0].len(), 3);
        assert!(times[0].iter().all(|&ns| ns >= 0.0));
        assert!(times[1].is_empty());
        assert_eq!((a, b), (4, 4));
    }

    /// An order is a permutation, the same from the same seed, another
    /// from another seed or the next draw.
    #[test]
    fn the_order_is_a_seeded_permutation() {
        let (mut one, mut again, mut other) = (Order::seeded(7), Order::seeded(7), Order::seeded(8));
        let first = one.next(20);
        let mut sorted = first.clone();
        sorted.sort_unstable();
        assert_eq!(sorted, (0..20).collect::<Vec<_>>());
        assert_ne!(first, sorted, "not shuffled");
        assert_eq!(again.next(20), first);
        assert_ne!(other.next(20), first);
        assert_ne!(one.next(20), first);
    }

    /// Within every repeat the passes run in the order drawn, the warm-up
    /// too, and each pass's samples stay its own.
    #[test]
    fn passes_are_timed_in_the_order_drawn() {
        let ran = std::cell::RefCell::new(Vec::new());
        let log = &ran;
        let mut passes: Vec<Box<dyn FnMut()>> =
            (0..6).map(|i| Box::new(move || log.borrow_mut().push(i)) as Box<dyn FnMut()>).collect();
        let timing = Timing { repeats: 2, min_repeat: Duration::ZERO };
        let samples =
            timing.samples_each(passes.iter_mut().map(|p| (&mut **p as &mut dyn FnMut(), 1)).collect(), &mut order());
        let turns = order().next(6);
        assert_eq!(*ran.borrow(), [turns.clone(), turns.clone(), turns].concat());
        assert!(samples.iter().all(|s| s.len() == 2));
    }

    #[test]
    fn a_sweep_figure_weighs_each_value_by_its_polygons_repeat_by_repeat() {
        let run = |ns: Samples| Speeds { bounds: vec![ns], ..Speeds::default() };
        let runs = [run(vec![10.0, 20.0]), run(vec![40.0, 50.0])];
        let mean = weighted_mean(&runs, &|s| &s.bounds[0], &|r| [3, 1][r]);
        assert_eq!(mean, vec![17.5, 27.5]);
    }

    fn square(x: i32, color: u8) -> Polygon {
        let p = |x: i32, y: i32| Point::new(x * 256, y * 256);
        Polygon::new(vec![p(x, 0), p(x + 20, 0), p(x + 20, 20), p(x, 20)], color)
    }

    fn family(polygons: Vec<Polygon>) -> Family {
        Family { name: "test", group: Group::Stress, description: "", polygons, tilings: vec![], sweep: None }
    }

    /// A contender timed on fewer polygons than `exact` is set against
    /// `exact` timed again on those very polygons, in a pass of its own; one
    /// timed on all of them against `exact`'s own samples.
    #[test]
    fn exact_is_timed_on_each_contenders_own_polygons() {
        let family = family((0..4).map(|i| square(30 * i, 2 + i as u8)).collect());
        let exact = family.polygons.iter().map(crate::measure::exact_spans).collect::<Vec<_>>();
        let contenders = [Contender::Method(MethodId::Exact), Contender::Method(MethodId::AbrashInt)];
        let plan = |timed: Vec<usize>| FamilyPlan {
            family: "test".into(),
            timed: vec![Some(vec![0, 1, 2, 3]), Some(timed)],
            lanes: vec![false; Lane::all().len()],
        };
        let timing = Timing { repeats: 3, min_repeat: Duration::ZERO };
        let time = |plan: &FamilyPlan| time_family(&family, plan, &exact, &contenders, timing, &mut order(), &|| {});
        let all = time(&plan(vec![0, 1, 2, 3])).unwrap();
        assert_eq!(all.exact_on[1], all.contenders[0]);
        assert_eq!(all.exact_on[0], all.contenders[0]);
        let fewer = time(&plan(vec![1, 3])).unwrap();
        assert_eq!(fewer.exact_on[1].len(), 3);
        assert_ne!(fewer.exact_on[1], fewer.contenders[0]);
        assert_eq!(fewer.exact_on[0], fewer.contenders[0]);
    }

    /// The pixels a timed pass left are the judged fill's; one pixel
    /// written otherwise is caught, and named.
    #[test]
    fn a_timed_pass_that_writes_another_pixel_is_caught() {
        let polygons = [square(0, 5), square(10, 6), square(100, 7)];
        let polygons: Vec<&Polygon> = polygons.iter().collect();
        let exact = Contender::Method(MethodId::Exact);
        let mut screen = Framebuffer::new(SCREEN);
        let mut pass = exact.pass_into(&polygons, &mut screen).unwrap();
        pass();
        pass();
        drop(pass);
        assert_eq!(check_screen(&exact, &polygons, &screen), Ok(()));
        screen.span(3, 12, 13, 5);
        let error = check_screen(&exact, &polygons, &screen).unwrap_err();
        assert!(
            error.contains("`exact`'s timed framebuffer (hash")
                && error.contains("first at (12, 3), 5 timed, 6 judged"),
            "{error}"
        );
    }
}
