//! What a lab run found, as written to results.json: one row per
//! contender (method, peer or bound) per family, and the sweep points the
//! rotation and scaling charts draw. The report and the charts read only
//! this.

use serde::Serialize;

use crate::contender::Contender;
use crate::convention::Own;
use crate::corpus::{Axis, Family, Group};
use crate::measure::{Judged, Tally};
use crate::modelling::{self, PathRow, ShowRow};
use crate::spans;
use crate::stats::Spread;
use crate::timing::{Bound, Samples, Speeds, Timed};

/// The method held to zero wrong pixels, overdraw, gaps and failures.
pub const EXACT: &str = "exact";

/// Error rates (in %) below this count as none where rates are averaged in
/// logarithms or drawn on a log axis.
pub const ZERO_FLOOR: f64 = 1e-4;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Kind {
    Method,
    Peer,
    Bound,
}

/// One goal: what is measured, its value in this run, the bound it must
/// keep and whether it does.
#[derive(Clone, Debug, Serialize)]
pub struct GoalRow {
    pub measure: String,
    /// The measured ratio or count; `None` where this run has no figure.
    pub value: Option<f64>,
    /// What it shows instead of a number, where it is not one (the peers
    /// faster than `exact`).
    pub note: Option<String>,
    pub goal: String,
    pub met: bool,
}

#[derive(Clone, Debug, Serialize)]
pub struct Results {
    pub seed: u64,
    pub quick: bool,
    /// The user's scene whose polygons were measured in place of the
    /// corpus (`lab --scene`); `None` for the corpus.
    pub scene: Option<SceneInfo>,
    pub families: Vec<FamilyInfo>,
    pub contenders: Vec<ContenderInfo>,
    pub rows: Vec<Row>,
    pub sweeps: Vec<SweepPoint>,
    /// What modelling costs: exact's paths, fill_auto and classification
    /// alone, per family.
    pub modelling: Vec<PathRow>,
    /// The show's shaded entries as they need and over-modelled.
    pub show_modelling: Vec<ShowRow>,
    /// `exact` against its goals ([`crate::goals`]), once all is measured.
    pub goals: Vec<GoalRow>,
    /// What the lab binary was built for.
    pub build: Build,
    /// How the times were taken.
    pub timing: TimingInfo,
}

/// The user's scene a run measured.
#[derive(Clone, Debug, Serialize)]
pub struct SceneInfo {
    /// The scene's name (its file's stem).
    pub name: String,
    /// What the user gave: the file, and how it was read.
    pub from: String,
}

/// How the times were taken: how many launches of the whole timing, how
/// many repeats in each, in what orders, and the machine's load around
/// them.
#[derive(Clone, Debug, Default, Serialize)]
pub struct TimingInfo {
    /// Launches of the whole timing (`--launches`), each a fresh process,
    /// one after the other.
    pub launches: usize,
    /// The seed of the orders passes are timed in; launch `k` (from 0)
    /// draws its orders from `order_seed + k` ([`crate::timing::Order`]).
    pub order_seed: u64,
    /// Repeats of every lane in each launch, timed in turn.
    pub repeats: usize,
    /// How long each repeat of a pass lasts at least, in milliseconds.
    pub min_repeat_ms: f64,
    /// The confidence of the intervals of ratios.
    pub confidence: f64,
    /// The 1-minute load average when the first launch started and when
    /// the last ended, where the system tells it (`/proc/loadavg`).
    pub load_average: (Option<f64>, Option<f64>),
    /// The same for each launch.
    pub launch_loads: Vec<(Option<f64>, Option<f64>)>,
    /// The processor the times were taken on, where the system tells it
    /// (`/proc/cpuinfo`): ratios between contenders differ from one
    /// generation to another.
    pub cpu: Option<String>,
    /// Timed framebuffers of ours checked against their judged pixels,
    /// every launch's together ([`crate::timing::check_screen`]).
    pub screens_checked: usize,
}

/// The CPU features of x86-64 a fill's code may be compiled to use, as
/// `target_feature` names them, from SSE4.2 (x86-64-v2) through AVX2 and
/// its companions (x86-64-v3) to AVX-512 (x86-64-v4 and beyond).
const FEATURES: [(&str, bool); 15] = [
    ("sse4.2", cfg!(target_feature = "sse4.2")),
    ("popcnt", cfg!(target_feature = "popcnt")),
    ("avx", cfg!(target_feature = "avx")),
    ("avx2", cfg!(target_feature = "avx2")),
    ("bmi1", cfg!(target_feature = "bmi1")),
    ("bmi2", cfg!(target_feature = "bmi2")),
    ("fma", cfg!(target_feature = "fma")),
    ("lzcnt", cfg!(target_feature = "lzcnt")),
    ("avx512f", cfg!(target_feature = "avx512f")),
    ("avx512bw", cfg!(target_feature = "avx512bw")),
    ("avx512cd", cfg!(target_feature = "avx512cd")),
    ("avx512dq", cfg!(target_feature = "avx512dq")),
    ("avx512vl", cfg!(target_feature = "avx512vl")),
    ("avx512vbmi", cfg!(target_feature = "avx512vbmi")),
    ("avx512vbmi2", cfg!(target_feature = "avx512vbmi2")),
];

/// What the lab binary is: the build as its caller names it (`cargo
/// xtask lab --build`: `native`, `-C target-cpu=native`, or `x86-64-v3`),
/// the commit it was built from, and the CPU features it was compiled to
/// use.
#[derive(Clone, Debug, Serialize)]
pub struct Build {
    pub name: String,
    /// `git describe`'s commit of the working tree as the run started
    /// (`cargo xtask lab` has just built the binary from it), with `-dirty`
    /// where it held uncommitted changes; `None` outside a git checkout.
    pub commit: Option<String>,
    /// Of [`FEATURES`], those this binary was compiled to use.
    pub features: Vec<&'static str>,
}

impl Build {
    /// This binary, built as `name`.
    pub fn this(name: &str) -> Build {
        let commit = std::process::Command::new("git")
            .args(["describe", "--always", "--dirty", "--abbrev=12", "--exclude=*"])
            .output()
            .ok()
            .filter(|out| out.status.success())
            .and_then(|out| Some(String::from_utf8(out.stdout).ok()?.trim().to_string()));
        let features = FEATURES.iter().filter(|(_, on)| *on).map(|(name, _)| *name).collect();
        Build { name: name.to_string(), commit, features }
    }
}

#[derive(Clone, Debug, Serialize)]
pub struct FamilyInfo {
    pub name: &'static str,
    pub group: Group,
    pub description: &'static str,
    pub polygons: usize,
    pub tilings: usize,
    /// Pixels of the exact fill, our convention.
    pub pixels: u64,
}

#[derive(Clone, Debug, Serialize)]
pub struct ContenderInfo {
    pub name: &'static str,
    pub kind: Kind,
    /// Seed file, crate, or what the bound does.
    pub source: &'static str,
    pub summary: String,
    /// Own sample point in subpixels from the pixel's corner (none for
    /// bounds, and for a peer that decides by area coverage; for an
    /// integer peer, the corner of its closed polygon in whole pixels).
    pub sample: Option<(i32, i32)>,
    /// For a peer timed a second way (its paths built inside the clock or
    /// before it), the peer it draws the same pixels as.
    pub variant_of: Option<&'static str>,
}

/// One contender on one family. Accuracy fields are `None` for the bounds;
/// `gaps` is `None` on families that do not tile.
#[derive(Clone, Debug, Serialize)]
pub struct Row {
    pub name: &'static str,
    pub kind: Kind,
    pub family: &'static str,
    pub group: Group,
    pub polygons: u64,
    /// Pixels of the exact fill of the family (our convention).
    pub pixels: u64,
    /// Polygons timed: all but the failed ones (for a peer, the ones it
    /// drew).
    pub timed_polygons: u64,
    /// Its time per polygon, with its spread and its ratios to `exact`
    /// and the store bound.
    #[serde(flatten)]
    pub time: Timed,
    /// Exact pixels of the timed polygons per second of fill (medians).
    pub pixels_per_second: Option<f64>,
    /// Time over the memset bound's on the same family (medians).
    pub time_vs_memset: Option<f64>,
    pub wrong_pixels: Option<u64>,
    pub wrong_pixels_own: Option<u64>,
    /// Of the wrong pixels, those the reference draws and the contender
    /// left out (the rest it drew and the reference does not), under our
    /// convention and under its own.
    pub missing_pixels: Option<u64>,
    pub missing_pixels_own: Option<u64>,
    pub overdraw: Option<u64>,
    pub gaps: Option<u64>,
    pub failures: Option<u64>,
    pub refusals: Option<u64>,
    pub faulty_polygons: Option<u64>,
    pub drawn_pixels: Option<u64>,
    /// Mean (dx, dy) of drawn minus exact centroids, in pixels.
    pub centroid_bias: Option<(f64, f64)>,
    pub first_failure: Option<String>,
    pub first_refusal: Option<String>,
}

impl Row {
    /// Wrong pixels per exact pixel (our convention), where measured.
    pub fn error_rate(&self) -> Option<f64> {
        Some(self.wrong_pixels? as f64 / self.pixels.max(1) as f64)
    }

    /// Pixels drawn wrong by the contender's own convention, drawn twice,
    /// or left as gaps: how badly it breaks.
    pub fn damaged_pixels(&self) -> Option<u64> {
        Some(self.wrong_pixels_own? + self.overdraw? + self.gaps.unwrap_or(0))
    }

    /// [`Row::damaged_pixels`] per exact pixel; `None` where the exact fill
    /// draws nothing (wholly off-screen polygons).
    pub fn damage_rate(&self) -> Option<f64> {
        (self.pixels > 0).then_some(self.damaged_pixels()? as f64 / self.pixels as f64)
    }
}

/// One contender at one value of a sweep.
#[derive(Clone, Debug, Serialize)]
pub struct SweepPoint {
    pub name: &'static str,
    pub kind: Kind,
    pub family: &'static str,
    pub axis: Axis,
    pub value: f64,
    pub polygons: u64,
    pub pixels: u64,
    pub wrong_pixels: Option<u64>,
    pub wrong_pixels_own: Option<u64>,
    pub faulty_polygons: Option<u64>,
    /// Only for the axes timed per value (area, vertex count): the median
    /// of the repeats, with their least and most.
    pub ns_per_polygon: Option<Spread>,
}

impl Results {
    pub fn new(seed: u64, quick: bool, contenders: &[Contender], build: Build) -> Self {
        let mut infos: Vec<ContenderInfo> = contenders
            .iter()
            .map(|c| ContenderInfo {
                name: c.name(),
                kind: if c.is_peer() { Kind::Peer } else { Kind::Method },
                source: c.source(),
                summary: c.summary(),
                sample: match c.own() {
                    Own::Sample(sample) => Some((sample.x, sample.y)),
                    Own::Closed { .. } => Some((0, 0)),
                    Own::Coverage { .. } => None,
                },
                variant_of: match c {
                    Contender::Peer(p) => p.info().variant_of,
                    _ => None,
                },
            })
            .collect();
        infos.extend(Bound::ALL.map(|b| ContenderInfo {
            name: b.name(),
            kind: Kind::Bound,
            source: b.source(),
            summary: String::new(),
            sample: None,
            variant_of: None,
        }));
        Self {
            seed,
            quick,
            scene: None,
            families: vec![],
            contenders: infos,
            rows: vec![],
            sweeps: vec![],
            modelling: vec![],
            show_modelling: vec![],
            goals: vec![],
            build,
            timing: TimingInfo::default(),
        }
    }

    /// Adds what was measured on `family`: its judgement, its lanes'
    /// (`lanes`), and the samples of every launch of the timing
    /// (`runs`).
    pub fn add_family(
        &mut self,
        family: &Family,
        contenders: &[Contender],
        judged: &Judged,
        lanes: &modelling::Judgement,
        runs: &[Speeds],
    ) {
        let pixels_of = |indices: &mut dyn Iterator<Item = usize>| {
            indices.map(|i| spans::pixel_count(&judged.exact[i])).sum::<u64>()
        };
        let pixels = pixels_of(&mut (0..family.polygons.len()));
        self.families.push(FamilyInfo {
            name: family.name,
            group: family.group,
            description: family.description,
            polygons: family.polygons.len(),
            tilings: family.tilings.len(),
            pixels,
        });
        let exact = contenders.iter().position(|c| c.name() == EXACT);
        let none = Samples::new();
        let exact_runs: Vec<&Samples> = runs.iter().map(|s| exact.map_or(&none, |e| &s.contenders[e])).collect();
        let store_runs: Vec<&Samples> = runs.iter().map(|s| &s.bounds[Bound::Store as usize]).collect();
        let timed = |pick: &dyn Fn(&Speeds) -> &Samples| {
            let mine: Vec<&Samples> = runs.iter().map(pick).collect();
            Timed::of(&mine, &exact_runs, &store_runs)
        };
        let memset = timed(&|s| &s.bounds[Bound::Memset as usize]).ns_per_polygon;
        let row = |name, kind, polygons: u64, timed: u64, timed_pixels: u64, time: Timed| Row {
            name,
            kind,
            family: family.name,
            group: family.group,
            polygons,
            pixels,
            timed_polygons: timed,
            pixels_per_second: time.ns_per_polygon.map(|ns| timed_pixels as f64 / (ns * timed as f64) * 1e9),
            time_vs_memset: time.ns_per_polygon.zip(memset).map(|(ns, memset)| ns / memset),
            time,
            wrong_pixels: None,
            wrong_pixels_own: None,
            missing_pixels: None,
            missing_pixels_own: None,
            overdraw: None,
            gaps: None,
            failures: None,
            refusals: None,
            faulty_polygons: None,
            drawn_pixels: None,
            centroid_bias: None,
            first_failure: None,
            first_refusal: None,
        };
        for (c, contender) in contenders.iter().enumerate() {
            let Some(tally) = &judged.tallies[c] else { continue };
            let timed_polygons = &judged.timed[c];
            let exact_on: Vec<&Samples> = runs.iter().map(|s| &s.exact_on[c]).collect();
            let kind = if contender.is_peer() { Kind::Peer } else { Kind::Method };
            let base = row(
                contender.name(),
                kind,
                tally.polygons,
                timed_polygons.len() as u64,
                pixels_of(&mut timed_polygons.iter().copied()),
                Timed::of(&runs.iter().map(|s| &s.contenders[c]).collect::<Vec<_>>(), &exact_on, &store_runs),
            );
            self.rows.push(with_tally(base, tally, !family.tilings.is_empty()));
        }
        for bound in Bound::ALL {
            let n = family.polygons.len() as u64;
            self.rows.push(row(bound.name(), Kind::Bound, n, n, pixels, timed(&|s| &s.bounds[bound as usize])));
        }
        let lane_runs: Vec<Vec<&Samples>> = runs.iter().map(|s| s.lanes.iter().collect()).collect();
        self.modelling.extend(lanes.rows(&lane_runs, &exact_runs, &store_runs));
        self.add_sweeps(family, contenders, judged, runs);
    }

    /// The sweep's points, each value's samples of every run together.
    fn add_sweeps(&mut self, family: &Family, contenders: &[Contender], judged: &Judged, runs: &[Speeds]) {
        let Some(sweep) = &family.sweep else { return };
        for (r, (value, range)) in judged.runs.iter().enumerate() {
            let pixels = range.clone().map(|i| spans::pixel_count(&judged.exact[i])).sum();
            let point = |name, kind, tally: Option<&Tally>, ns: &Samples| SweepPoint {
                name,
                kind,
                family: family.name,
                axis: sweep.axis,
                value: *value,
                polygons: range.len() as u64,
                pixels,
                wrong_pixels: tally.map(|t| t.wrong_pixels),
                wrong_pixels_own: tally.map(|t| t.wrong_pixels_own),
                faulty_polygons: tally.map(|t| t.faulty_polygons),
                ns_per_polygon: Spread::of(ns),
            };
            let timed_per_value = runs.iter().any(|speeds| speeds.runs.get(r).is_some());
            let pooled = |pick: &dyn Fn(&Speeds) -> &Samples| -> Samples {
                runs.iter().filter_map(|speeds| speeds.runs.get(r)).flat_map(|s| pick(s).iter().copied()).collect()
            };
            for (c, contender) in contenders.iter().enumerate() {
                let Some(tally) = judged.run_tallies[c].get(r) else { continue };
                let kind = if contender.is_peer() { Kind::Peer } else { Kind::Method };
                self.sweeps.push(point(contender.name(), kind, Some(tally), &pooled(&|s| &s.contenders[c])));
            }
            if timed_per_value {
                for bound in Bound::ALL {
                    self.sweeps.push(point(bound.name(), Kind::Bound, None, &pooled(&|s| &s.bounds[bound as usize])));
                }
            }
        }
    }

    /// The speed-against-accuracy points: one per method or peer per
    /// everyday family (scenes, random, tilings), at (time over the memset
    /// bound, wrong pixels in % of exact pixels, at least `zero_floor`,
    /// which must be positive for [`Results::speed_accuracy_means`]).
    /// Rows with a refusal or failure are left out: they drew less work,
    /// and their point would flatter them; so are the peers timed a second
    /// way, which draw the same pixels as their first.
    pub fn speed_accuracy_points(&self, zero_floor: f64) -> Vec<(&Row, (f64, f64))> {
        let variant = |name: &str| self.contenders.iter().any(|c| c.name == name && c.variant_of.is_some());
        self.rows
            .iter()
            .filter(|r| r.group.is_everyday() && r.refusals == Some(0) && r.failures == Some(0) && !variant(r.name))
            .filter_map(|r| Some((r, (r.time_vs_memset?, (r.error_rate()? * 100.0).max(zero_floor)))))
            .collect()
    }

    /// One point per method or peer: the geometric means of its
    /// [`Results::speed_accuracy_points`] on both axes, over the families
    /// it has a point on, with how many those are. In results order.
    pub fn speed_accuracy_means(&self, zero_floor: f64) -> Vec<MeanPoint> {
        let points = self.speed_accuracy_points(zero_floor);
        self.contenders
            .iter()
            .filter(|c| c.kind != Kind::Bound && c.variant_of.is_none())
            .filter_map(|c| {
                let mine: Vec<(f64, f64)> = points.iter().filter(|(r, _)| r.name == c.name).map(|(_, p)| *p).collect();
                let mean = geometric_mean(mine.iter().map(|p| p.0))?;
                let error = geometric_mean(mine.iter().map(|p| p.1))?;
                Some(MeanPoint { name: c.name, kind: c.kind, at: (mean, error), families: mine.len() })
            })
            .collect()
    }

    /// Rows of contender `name`.
    pub fn rows_of<'a>(&'a self, name: &'a str) -> impl Iterator<Item = &'a Row> + 'a {
        self.rows.iter().filter(move |r| r.name == name)
    }

    /// The row of contender `name` on `family`.
    pub fn row(&self, name: &str, family: &str) -> Option<&Row> {
        self.rows.iter().find(|r| r.name == name && r.family == family)
    }
}

/// A contender's mean point on the speed-against-accuracy chart.
#[derive(Clone, Debug, PartialEq)]
pub struct MeanPoint {
    pub name: &'static str,
    pub kind: Kind,
    /// (time over the memset bound's, wrong pixels in %), geometric means.
    pub at: (f64, f64),
    /// Families the means are over.
    pub families: usize,
}

/// The geometric mean of positive `values`; `None` for none.
fn geometric_mean(values: impl Iterator<Item = f64>) -> Option<f64> {
    let (sum, n) = values.fold((0.0, 0u32), |(sum, n), v| (sum + v.ln(), n + 1));
    (n > 0).then(|| (sum / f64::from(n)).exp())
}

fn with_tally(row: Row, tally: &Tally, tiled: bool) -> Row {
    Row {
        wrong_pixels: Some(tally.wrong_pixels),
        wrong_pixels_own: Some(tally.wrong_pixels_own),
        missing_pixels: Some(tally.missing_pixels),
        missing_pixels_own: Some(tally.missing_pixels_own),
        overdraw: Some(tally.overdraw),
        gaps: tiled.then_some(tally.gaps),
        failures: Some(tally.failures),
        refusals: Some(tally.refusals),
        faulty_polygons: Some(tally.faulty_polygons),
        drawn_pixels: Some(tally.drawn_pixels),
        centroid_bias: tally.bias.mean(),
        first_failure: tally.first_failure.clone(),
        first_refusal: tally.first_refusal.clone(),
        ..row
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A row of `name` on `family` with nothing measured.
    pub(crate) fn row(name: &'static str, family: &'static str) -> Row {
        Row {
            name,
            kind: Kind::Method,
            family,
            group: Group::Stress,
            polygons: 0,
            pixels: 0,
            timed_polygons: 0,
            time: Timed::default(),
            pixels_per_second: None,
            time_vs_memset: None,
            wrong_pixels: None,
            wrong_pixels_own: None,
            missing_pixels: None,
            missing_pixels_own: None,
            overdraw: None,
            gaps: None,
            failures: None,
            refusals: None,
            faulty_polygons: None,
            drawn_pixels: None,
            centroid_bias: None,
            first_failure: None,
            first_refusal: None,
        }
    }

    /// Results with `families` and no contender or row.
    pub(crate) fn results(families: &[&'static str]) -> Results {
        let mut results = Results::new(0, true, &[], Build::this("test"));
        results.families = families
            .iter()
            .map(|&name| FamilyInfo { name, group: Group::Stress, description: "", polygons: 0, tilings: 0, pixels: 0 })
            .collect();
        results
    }

    /// The build names the features it was compiled with, and only those.
    #[test]
    fn the_build_names_its_features() {
        let build = Build::this("native");
        assert_eq!(build.name, "native");
        assert_eq!(build.features.contains(&"avx2"), cfg!(target_feature = "avx2"));
        assert_eq!(build.features.contains(&"avx512bw"), cfg!(target_feature = "avx512bw"));
        assert!(build.features.iter().all(|f| FEATURES.iter().any(|(name, on)| name == f && *on)));
    }
}
