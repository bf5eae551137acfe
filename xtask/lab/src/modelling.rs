//! What modelling costs: "model no more than a scene needs", measured.
//!
//! `exact` fills a polygon by the narrowest of its paths that takes it
//! ([`raster::ExactPath`]: triangle, monotone, active edges, edge flags),
//! chosen by `fill_auto`'s linear-time classification. Here every family is
//! drawn through each path alone (a path refuses what is outside its class,
//! and must never draw it wrong), through `fill_auto`, and classified alone
//! (`fill_auto`'s own choice, and `raster::classify`'s full one), each
//! judged against the reference and timed, with its heap allocations per
//! polygon; and `fill_auto` into a sink that stores nothing, which is what
//! finding the spans costs alone. The show's shaded entries are timed as they are modelled and
//! over-modelled ([`scenes::show::Modelling`]).

use std::hint::black_box;

use raster::{ExactPath, MethodId, Polygon};
use scenes::show::{Entry, Modelling, Stage, ENTRIES_IN_ORDER};
use serde::Serialize;

use crate::contender::Contender;
use crate::corpus::Family;
use crate::heap;
use crate::lane::Lane;
use crate::measure::{self, Tally};
use crate::stats::{Ratio, Spread};
use crate::timing::{Order, Samples, Timed, Timing};

/// One lane on one family, as written to results.json. Accuracy fields are
/// `None` for the lanes that only classify.
#[derive(Clone, Debug, Serialize)]
pub struct PathRow {
    pub family: &'static str,
    pub lane: &'static str,
    pub polygons: u64,
    /// Polygons the path refused as outside its class.
    pub refusals: Option<u64>,
    pub wrong_pixels: Option<u64>,
    pub overdraw: Option<u64>,
    /// On tiling families only.
    pub gaps: Option<u64>,
    pub failures: Option<u64>,
    /// Its time, only where the lane takes every polygon of the family;
    /// over `exact`'s and the store bound's, paired within each launch,
    /// across launches.
    #[serde(flatten)]
    pub time: Timed,
    /// Heap allocations per polygon once the lane has run over the family
    /// (a scratch has grown to the largest polygon), `None` where they are
    /// not counted.
    pub allocations_per_polygon: Option<f64>,
    /// For a path: the polygons `fill_auto` sends down it.
    pub chosen_by_fill_auto: Option<u64>,
    /// For the drawing lanes: time over the cheapest path's that takes
    /// every polygon of the family (medians).
    pub time_vs_cheapest: Option<f64>,
}

/// Every lane on a family, judged, with its allocations counted: what
/// timing needs to know before it starts, and the rows' other figures.
pub struct Judgement {
    family: &'static str,
    polygons: u64,
    tiled: bool,
    /// Per lane of [`Lane::all`]: its tally, for the lanes that draw.
    tallies: Vec<Option<Tally>>,
    /// Per lane: timed only on what it all takes, and only if it never failed.
    takes_all: Vec<bool>,
    allocations: Vec<Option<f64>>,
    /// Per path: the polygons `fill_auto` sends down it.
    chosen: Vec<u64>,
}

/// Every lane on `family`: judged on every core, then its allocations
/// counted on this thread alone. `progress` is told of each polygon judged.
pub fn judge(family: &Family, progress: &(dyn Fn() + Sync)) -> Judgement {
    let lanes = Lane::all();
    let contenders: Vec<Contender> = lanes.iter().filter_map(|lane| lane.contender()).collect();
    let judged = measure::quietly(|| measure::judge(family, &contenders, progress));
    let polygons: Vec<&Polygon> = family.polygons.iter().collect();
    let mut chosen = vec![0u64; ExactPath::NAMES.len()];
    for path in polygons.iter().filter_map(|&p| ExactPath::choose(p)) {
        chosen[path.index()] += 1;
    }
    let tallies: Vec<Option<Tally>> = lanes
        .iter()
        .map(|lane| {
            let c = contenders.iter().position(|c| Some(c.name()) == lane.contender().map(|l| l.name()))?;
            judged.tallies[c].clone()
        })
        .collect();
    let takes_all: Vec<bool> =
        tallies.iter().map(|tally| tally.as_ref().is_none_or(|t| t.refusals == 0 && t.failures == 0)).collect();
    let allocations = lanes
        .iter()
        .zip(&takes_all)
        .map(|(lane, &takes)| {
            // The pass is made and run once first: only the fills' own
            // allocations in a steady state count, not a scratch growing.
            let mut pass = lane.pass(&polygons);
            pass();
            heap::per_item(polygons.len(), pass).filter(|_| takes)
        })
        .collect();
    Judgement {
        family: family.name,
        polygons: polygons.len() as u64,
        tiled: !family.tilings.is_empty(),
        tallies,
        takes_all,
        allocations,
        chosen,
    }
}

impl Judgement {
    /// The lanes timed on the family, in [`Lane::all`] order: `None` for
    /// those not timed there.
    pub fn timed(&self) -> Vec<Option<Lane>> {
        Lane::all().into_iter().zip(&self.takes_all).map(|(lane, &takes)| takes.then_some(lane)).collect()
    }

    /// The rows of the family, from `lanes`, each lane's samples in each
    /// launch (in [`Lane::all`] order), and `exact`'s and the store bound's
    /// in the same repeats.
    pub fn rows(&self, lanes: &[Vec<&Samples>], exact: &[&Samples], store: &[&Samples]) -> Vec<PathRow> {
        let mut rows: Vec<PathRow> = Lane::all()
            .into_iter()
            .enumerate()
            .map(|(l, lane)| {
                let tally = self.tallies[l].as_ref();
                let runs: Vec<&Samples> = lanes.iter().map(|run| run[l]).collect();
                PathRow {
                    family: self.family,
                    lane: lane.name(),
                    polygons: self.polygons,
                    refusals: tally.map(|t| t.refusals),
                    wrong_pixels: tally.map(|t| t.wrong_pixels),
                    overdraw: tally.map(|t| t.overdraw),
                    // Pixels of refused tiles are gaps of the tiling, not faults.
                    gaps: tally.filter(|t| self.tiled && t.refusals == 0).map(|t| t.gaps),
                    failures: tally.map(|t| t.failures),
                    time: Timed::of(&runs, exact, store),
                    allocations_per_polygon: self.allocations[l],
                    chosen_by_fill_auto: match lane {
                        Lane::Path(which) => Some(self.chosen[which]),
                        _ => None,
                    },
                    time_vs_cheapest: None,
                }
            })
            .collect();
        let cheapest = rows
            .iter()
            .filter(|r| ExactPath::NAMES.contains(&r.lane))
            .filter_map(|r| r.time.ns_per_polygon)
            .min_by(f64::total_cmp);
        for row in rows.iter_mut().filter(|r| r.refusals.is_some()) {
            row.time_vs_cheapest = row.time.ns_per_polygon.zip(cheapest).map(|(ns, cheapest)| ns / cheapest);
        }
        rows
    }
}

/// A shaded entry of the show, timed as modelled or over-modelled.
#[derive(Clone, Debug, Serialize)]
pub struct ShowRow {
    pub entry: &'static str,
    /// `needed` (what the entry uses) or `forced` (four attributes and a
    /// depth buffer).
    pub modelling: &'static str,
    /// Frames timed: every frame of the entry, drawn by `exact`.
    pub frames: u32,
    /// The median time per frame, with the least and most of the repeats
    /// of every launch.
    pub ns_per_frame: Option<Spread>,
    /// Time over the same entry's as it needs, across launches
    /// ([`Ratio::across`]).
    pub time_vs_needed: Option<Ratio>,
    /// The same within each launch, from its paired repeats.
    pub launches: Vec<Option<Ratio>>,
}

/// The shaded entries of the show, in order.
fn shaded_entries() -> Vec<&'static Entry> {
    let mut stage = Stage::new();
    ENTRIES_IN_ORDER
        .iter()
        .filter(|entry| stage.draw_modelled(entry, 0, MethodId::Exact, Modelling::Needed).is_some())
        .collect()
}

/// Every shaded entry of the show, every frame, drawn by `exact` as the
/// entry needs and over-modelled, the two timed in turn (in an order
/// `order` draws): per entry, the samples as needed, then forced.
pub fn time_show(timing: Timing, order: &mut Order) -> Vec<Samples> {
    let method = MethodId::Exact;
    let (mut as_needed, mut forced) = (Stage::new(), Stage::new());
    let mut samples = Vec::new();
    for entry in shaded_entries() {
        let every_frame = |stage: &mut Stage, modelling: Modelling| {
            for frame in 0..entry.frames {
                black_box(stage.draw_modelled(entry, frame, method, modelling));
            }
        };
        let mut pass_needed = || every_frame(&mut as_needed, Modelling::Needed);
        let mut pass_forced = || every_frame(&mut forced, Modelling::Forced);
        let frames = entry.frames as usize;
        samples.extend(timing.samples_each(vec![(&mut pass_needed, frames), (&mut pass_forced, frames)], order));
    }
    samples
}

/// The show's rows from each launch's [`time_show`].
pub fn show_rows(launches: &[Vec<Samples>]) -> Vec<ShowRow> {
    let mut rows = Vec::new();
    for (e, entry) in shaded_entries().into_iter().enumerate() {
        let needed: Vec<&Samples> = launches.iter().filter_map(|launch| launch.get(2 * e)).collect();
        for (m, name) in ["needed", "forced"].into_iter().enumerate() {
            let mine: Vec<&Samples> = launches.iter().filter_map(|launch| launch.get(2 * e + m)).collect();
            let within: Vec<Option<Ratio>> =
                mine.iter().zip(&needed).map(|(ns, needed)| Ratio::paired(ns, needed)).collect();
            let all: Samples = mine.iter().flat_map(|s| s.iter().copied()).collect();
            rows.push(ShowRow {
                entry: entry.name,
                modelling: name,
                frames: entry.frames,
                ns_per_frame: Spread::of(&all),
                time_vs_needed: Ratio::across(&within.iter().flatten().copied().collect::<Vec<_>>()),
                launches: within,
            });
        }
    }
    rows
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::corpus::{self, Budget};

    fn family(name: &str) -> Family {
        corpus::build(Budget::QUICK).unwrap().into_iter().find(|f| f.name == name).unwrap()
    }

    const FAST: Timing = Timing { repeats: 2, min_repeat: std::time::Duration::ZERO };

    /// Judges every lane of `family` and times the ones it takes, with
    /// made-up times for `exact` and the store bound.
    fn rows(family: &Family) -> Vec<PathRow> {
        let judgement = judge(family, &|| {});
        let polygons: Vec<&Polygon> = family.polygons.iter().collect();
        let mut passes: Vec<(Box<dyn FnMut()>, usize)> = judgement
            .timed()
            .iter()
            .map(|lane| (lane.map_or_else(|| Lane::Dispatch.pass(&[]), |l| l.pass(&polygons)), polygons.len()))
            .collect();
        let mut samples = FAST.samples_each(
            passes.iter_mut().map(|(p, n)| (&mut **p as &mut dyn FnMut(), *n)).collect(),
            &mut Order::seeded(1),
        );
        for (samples, lane) in samples.iter_mut().zip(judgement.timed()) {
            if lane.is_none() {
                samples.clear();
            }
        }
        let (exact, store) = (vec![100.0, 100.0], vec![50.0, 50.0]);
        judgement.rows(&[samples.iter().collect()], &[&exact], &[&store])
    }

    #[test]
    fn on_triangles_every_path_draws_and_fill_auto_takes_the_triangle_path() {
        let rows = rows(&family("small_triangles"));
        let names: Vec<&str> = rows.iter().map(|r| r.lane).collect();
        assert_eq!(
            names,
            [
                "triangle",
                "monotone",
                "active edges",
                "edge flags",
                "fill_auto",
                "dispatch",
                "classify",
                "spans unstored"
            ]
        );
        for row in &rows[..5] {
            assert_eq!(
                (row.refusals, row.wrong_pixels, row.overdraw, row.failures),
                (Some(0), Some(0), Some(0), Some(0))
            );
            assert!(row.time.ns_per_polygon.is_some() && row.time_vs_cheapest.is_some(), "{row:?}");
            assert_eq!(row.time.launches[0].vs_exact.map(|r| r.count), Some(2), "{row:?}");
            assert_eq!(row.time.vs_exact.map(|r| r.count), Some(1), "{row:?}");
        }
        assert_eq!(rows[0].chosen_by_fill_auto, Some(rows[0].polygons));
        assert_eq!(rows[1].chosen_by_fill_auto, Some(0));
        assert_eq!(rows[5].refusals, None);
        // The unit tests keep the system allocator: no count is made up.
        assert_eq!(rows[0].allocations_per_polygon, None);
    }

    #[test]
    fn a_path_refuses_what_it_cannot_fill_and_is_not_timed_there() {
        let rows = rows(&family("concave"));
        let triangle = &rows[0];
        assert_eq!(triangle.refusals, Some(triangle.polygons));
        assert_eq!((triangle.wrong_pixels, triangle.time.ns_per_polygon), (Some(0), None));
        assert_eq!(triangle.time.vs_exact, None);
        // Both paths that take any polygon take them all; one is the cheapest.
        let general = &rows[2..4];
        assert!(general.iter().all(|path| path.refusals == Some(0)), "{general:?}");
        assert!(general.iter().any(|path| path.time_vs_cheapest == Some(1.0)), "{general:?}");
    }

    #[test]
    fn every_shaded_entry_is_timed_both_ways() {
        let rows = show_rows(&[time_show(FAST, &mut Order::seeded(1))]);
        let entries: Vec<(&str, &str)> = rows.iter().map(|r| (r.entry, r.modelling)).collect();
        assert_eq!(
            entries,
            [
                ("wgt-gouraud", "needed"),
                ("wgt-gouraud", "forced"),
                ("wgt-texture", "needed"),
                ("wgt-texture", "forced"),
                ("pendleton-zbuffer", "needed"),
                ("pendleton-zbuffer", "forced"),
            ]
        );
        assert!(rows.iter().all(|r| r.ns_per_frame.is_some()));
        assert_eq!(rows[0].time_vs_needed.map(|r| r.ratio), Some(1.0));
    }
}
