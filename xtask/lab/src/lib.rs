//! The polygon-fill lab (`cargo xtask lab`): every method of `raster`, the
//! peers (tiny-skia, Cairo, embedded-graphics, vello_cpu, Allegro 4,
//! SDL2_gfx, GD, imageproc) and three bounds (memset, span stores, the
//! dyn-sink replay) on one seeded corpus, or on the polygons of the user's
//! scene ([`Shapes`]); accuracy against `raster::reference`, speed in
//! wall-clock time; results.json, report.md and the charts under the
//! output directory.
//!
//! Speed is measured, never asserted, in launches: fresh processes of the
//! lab, each timing everything ([`run_launch`]), every ratio's interval
//! across them (docs/lab-method.md). What fails a run is a missing
//! results.json, any wrong pixel, overdraw, gap or failure of `exact`, or
//! a timed frame of `raster`'s methods that is not its judged pixels.
//!
//! ## Examples
//!
//! ```no_run
//! let options = lab::LabOptions { quick: true, ..lab::LabOptions::default() };
//! lab::run(&options)?;
//! # Ok::<(), anyhow::Error>(())
//! ```

use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;

use anyhow::{anyhow, bail, Context, Result};
use indicatif::{ProgressBar, ProgressStyle};
use scenes::Scene;

// One face: the modules are private and what the xtask, the tests and
// the benches use is re-exported here, each item at one path; `corpus`
// and `measure` stay namespaces, their items called by their names
// (`corpus::build`, `measure::judge`).
mod area_reference;
mod builds;
mod charts;
mod closed_reference;
mod contender;
mod convention;
pub mod corpus;
mod goals;
mod heap;
mod lane;
pub mod measure;
mod modelling;
mod peers;
mod report;
mod results;
mod spans;
mod stats;
mod timing;

pub use builds::{compare, BuildRun};
pub use contender::Contender;
pub use heap::Counting;
pub use report::Summary;
pub use spans::Span;
pub use timing::Bound;

use corpus::Budget;
use results::{Build, Results, TimingInfo, EXACT};
use serde::{Deserialize, Serialize};
use timing::{FamilyPlan, Order, Speeds, Timing};

/// What `cargo xtask lab` asks for.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LabOptions {
    /// A small corpus and short timing, for CI; with a scene, the short
    /// timing alone.
    pub quick: bool,
    /// Launches of the whole timing, each a fresh process, one after the
    /// other (at least 1; [`default_launches`]): each ratio's interval is
    /// across them.
    pub launches: usize,
    /// The seed of the orders passes are timed in: launch `k` (from 0)
    /// draws its orders from `order_seed + k`.
    pub order_seed: u64,
    /// What the caller built the lab binary as (`native`, `x86-64-v3`),
    /// for the report.
    pub build: String,
    /// Where results.json, report.md and the charts go.
    pub out_dir: PathBuf,
    /// What is measured: the corpus, or a scene's polygons.
    pub shapes: Shapes,
}

impl Default for LabOptions {
    fn default() -> Self {
        Self {
            quick: false,
            launches: default_launches(false),
            order_seed: ORDER_SEED,
            build: String::from("as built"),
            out_dir: PathBuf::from(default_out_dir(&Shapes::Corpus)),
            shapes: Shapes::Corpus,
        }
    }
}

/// Launches unless told: 3 for a full run, the fewest an interval across
/// launches can be worked out from, 2, with `--quick`.
pub const fn default_launches(quick: bool) -> usize {
    if quick {
        2
    } else {
        3
    }
}

/// The seed of the orders passes are timed in, unless told.
pub const ORDER_SEED: u64 = 0x6b2c_41f7;

/// The polygons a run measures.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Shapes {
    /// The seeded corpus.
    Corpus,
    /// The polygons of the user's scene, in families by class
    /// ([`corpus::user`]).
    Scene(UserScene),
}

/// Where a run's outputs go unless told: `target/lab` for the corpus,
/// `target/lab-scene` for a scene, so that neither run leaves the other's
/// charts beside its report.
pub const fn default_out_dir(shapes: &Shapes) -> &'static str {
    match shapes {
        Shapes::Corpus => "target/lab",
        Shapes::Scene(_) => "target/lab-scene",
    }
}

/// A scene whose polygons the lab measures in place of the corpus, and
/// where it came from, as the report names it. However the user gave it
/// (a scene file today), the xtask reads it into a [`Scene`] and hands
/// the lab that scene as a scene file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UserScene {
    pub scene: Scene,
    /// What the user gave: the file, and how it was read.
    pub from: String,
}

impl UserScene {
    /// Reads and parses the scene file at `path` whole, its stem the
    /// scene's name; `from` says where the scene came from (the path
    /// itself where `None`). A bad file is an error naming its line.
    pub fn read(path: &Path, from: Option<String>) -> Result<Self> {
        let text = fs::read_to_string(path).with_context(|| format!("failed to read scene file {}", path.display()))?;
        let name = path.file_stem().map_or_else(|| "scene".to_string(), |stem| stem.to_string_lossy().into_owned());
        let scene = scenes::file::parse(&name, &text)
            .map_err(|error| anyhow!("{}: bad scene file: {error}", path.display()))?;
        Ok(Self { scene, from: from.unwrap_or_else(|| path.display().to_string()) })
    }
}

/// Runs the lab: judges every contender on every family, times them all
/// in `launches` fresh processes of this binary one after the other
/// ([`run_launch`]), writes every output from what they all timed, then
/// checks them. Bad input (a scene with no polygon, no launch) is refused
/// before anything is written; a launch that fails (its timed pixels not
/// the judged ones, say) fails the run.
pub fn run(options: &LabOptions) -> Result<()> {
    let timing = timing_of(options);
    if cfg!(debug_assertions) {
        eprintln!("warning: the lab is built without optimisations; its timings mean little (use --release)");
    }
    if options.launches == 0 {
        bail!("--launches must be at least 1");
    }
    let families = families_of(options)?;
    let scene = match &options.shapes {
        Shapes::Corpus => None,
        Shapes::Scene(user) => Some(user),
    };
    // The commit as the run starts, right after `cargo run` built from it.
    let build = Build::this(&options.build);
    let out = &options.out_dir;
    let launch_dir = out.join("launches");
    fs::create_dir_all(&launch_dir).with_context(|| format!("failed to create {}", launch_dir.display()))?;
    let contenders = Contender::all();
    let judged = judge_families(&families, &contenders);
    let plans: Vec<FamilyPlan> = families
        .iter()
        .zip(&judged)
        .map(|(family, (judged, lanes))| FamilyPlan::of(family, judged, &lanes.timed()))
        .collect();
    let plan_path = launch_dir.join("plan.json");
    write(&plan_path, &serde_json::to_string(&plans).context("failed to serialise the plan")?)?;
    let scene_path = match scene {
        Some(user) => {
            let path = launch_dir.join(format!("{}.scene", user.scene.name));
            write(&path, &scenes::file::write(&user.scene))?;
            Some(path)
        }
        None => None,
    };
    let load_at_start = load_average();
    let mut records = Vec::with_capacity(options.launches);
    for launch in 0..options.launches {
        records.push(launch_one(options, launch, &plan_path, scene_path.as_deref(), &launch_dir)?);
    }
    let load_at_end = load_average();

    let mut results = Results::new(corpus::SEED, options.quick, &contenders, build);
    results.scene = scene.map(|user| results::SceneInfo { name: user.scene.name.clone(), from: user.from.clone() });
    for (f, (family, (judged, lanes))) in families.iter().zip(&judged).enumerate() {
        let speeds: Vec<Speeds> = records.iter().map(|r| r.families[f].clone()).collect();
        results.add_family(family, &contenders, judged, lanes, &speeds);
    }
    results.show_modelling = modelling::show_rows(&records.iter().map(|r| r.show.clone()).collect::<Vec<_>>());
    results.timing = TimingInfo {
        launches: options.launches,
        order_seed: options.order_seed,
        repeats: timing.repeats,
        min_repeat_ms: timing.min_repeat.as_secs_f64() * 1e3,
        confidence: stats::CONFIDENCE,
        load_average: (load_at_start, load_at_end),
        launch_loads: records.iter().map(|r| r.load_average).collect(),
        cpu: fs::read_to_string("/proc/cpuinfo").ok().and_then(|text| cpu_model(&text)),
        screens_checked: records.iter().map(|r| r.families.iter().map(|s| s.screens_checked).sum::<usize>()).sum(),
    };
    results.goals = goals::measure(&results);

    write_real_shape_scenes(&families, &out.join("scenes"))?;
    let json = serde_json::to_string_pretty(&results).context("failed to serialise the results")?;
    write(&out.join("results.json"), &json)?;
    let summary = serde_json::to_string_pretty(&report::Summary::of(&results)).context("failed to serialise")?;
    write(&out.join("summary.json"), &(summary + "\n"))?;
    write(&out.join("report.md"), &report::markdown(&results))?;
    charts::draw_all(&results, out)?;
    eprintln!("{}", report::summary(&results));
    eprintln!("lab: wrote results.json, summary.json, report.md and the charts to {}", out.display());
    check(&out.join("results.json"))
}

/// The timing a run asks for.
fn timing_of(options: &LabOptions) -> Timing {
    if options.quick {
        Timing::QUICK
    } else {
        Timing::FULL
    }
}

/// The families a run measures: the corpus, or the scene's.
fn families_of(options: &LabOptions) -> Result<Vec<corpus::Family>> {
    match &options.shapes {
        Shapes::Corpus => corpus::build(if options.quick { Budget::QUICK } else { Budget::FULL }),
        Shapes::Scene(user) => corpus::user::families(&user.scene),
    }
}

/// Judges every contender and lane on every family, with a progress bar.
fn judge_families(
    families: &[corpus::Family],
    contenders: &[Contender],
) -> Vec<(measure::Judged, modelling::Judgement)> {
    let bar = progress_bar(families.iter().map(|f| 2 * f.polygons.len() as u64).sum());
    let judged = families
        .iter()
        .map(|family| {
            bar.set_message(format!("judging {}", family.name));
            let judged = measure::quietly(|| measure::judge(family, contenders, &|| bar.inc(1)));
            (judged, modelling::judge(family, &|| bar.inc(1)))
        })
        .collect();
    bar.finish_and_clear();
    judged
}

fn progress_bar(work: u64) -> ProgressBar {
    ProgressBar::new(work).with_style(
        ProgressStyle::with_template("{elapsed_precise} [{bar:40}] {percent:>3}% {msg}")
            .expect("the progress template is valid")
            .progress_chars("=> "),
    )
}

/// What one launch timed, as it hands it back in its record file.
#[derive(Debug, Serialize, Deserialize)]
struct LaunchRecord {
    /// The 1-minute load average when it started timing and when it ended.
    load_average: (Option<f64>, Option<f64>),
    /// Per family, in the plan's order.
    families: Vec<Speeds>,
    /// The show's samples ([`modelling::time_show`]); none for a scene.
    show: Vec<timing::Samples>,
}

/// Runs launch `launch` (from 0) as a fresh process of this binary, told
/// the plan (and the scene, if any) and where to write its record; reads
/// the record back.
fn launch_one(
    options: &LabOptions,
    launch: usize,
    plan: &Path,
    scene: Option<&Path>,
    dir: &Path,
) -> Result<LaunchRecord> {
    let record = dir.join(format!("launch-{}.json", launch + 1));
    let exe = std::env::current_exe().context("failed to find the lab binary to launch")?;
    let mut command = Command::new(exe);
    if options.quick {
        command.arg("--quick");
    }
    if let Some(scene) = scene {
        command.arg("--scene").arg(scene);
    }
    command.arg("--launch").arg(launch.to_string()).arg("--launches").arg(options.launches.to_string());
    command.arg("--order-seed").arg(options.order_seed.to_string());
    command.arg("--plan").arg(plan).arg("--record").arg(&record);
    let status = command.status().context("failed to start a launch of the lab")?;
    if !status.success() {
        bail!("launch {} of {} failed ({status})", launch + 1, options.launches);
    }
    let text = fs::read_to_string(&record).with_context(|| format!("launch {} left no record", launch + 1))?;
    serde_json::from_str(&text).with_context(|| format!("{} is not a launch record", record.display()))
}

/// One launch, in a process of its own: times every family as `plan`
/// (the judging's [`FamilyPlan`]s, a JSON file) says, in orders drawn from
/// `options.order_seed + launch`, checks each timed frame of ours against
/// its judged pixels, times the show (on the corpus), and writes what it
/// timed to `record`. A frame that is not its judged pixels fails it.
pub fn run_launch(options: &LabOptions, launch: usize, plan: &Path, record: &Path) -> Result<()> {
    let timing = timing_of(options);
    let families = families_of(options)?;
    let text = fs::read_to_string(plan).with_context(|| format!("failed to read {}", plan.display()))?;
    let plans: Vec<FamilyPlan> =
        serde_json::from_str(&text).with_context(|| format!("{} is not a plan", plan.display()))?;
    let names = |plans: &[FamilyPlan]| plans.iter().map(|p| p.family.clone()).collect::<Vec<_>>();
    if names(&plans) != families.iter().map(|f| f.name.to_string()).collect::<Vec<_>>() {
        bail!("{} plans other families than this launch builds: {:?}", plan.display(), names(&plans));
    }
    let contenders = Contender::all();
    let lanes = contenders.len() + timing::Bound::ALL.len() + lane::Lane::all().len();
    let bar = progress_bar(families.iter().map(|f| timing::jobs(f, lanes)).sum());
    let mut order = Order::seeded(options.order_seed.wrapping_add(launch as u64));
    let load_at_start = load_average();
    let mut speeds = Vec::with_capacity(families.len());
    for (family, plan) in families.iter().zip(&plans) {
        bar.set_message(format!("timing {} (launch {} of {})", family.name, launch + 1, options.launches));
        let exact: Vec<Vec<spans::Span>> = family.polygons.iter().map(measure::exact_spans).collect();
        let timed = timing::time_family(family, plan, &exact, &contenders, timing, &mut order, &|| bar.inc(1));
        speeds.push(timed.map_err(|error| anyhow!("launch {}: {error}", launch + 1))?);
    }
    let show = match options.shapes {
        Shapes::Corpus => {
            bar.set_message(format!("timing the show (launch {} of {})", launch + 1, options.launches));
            modelling::time_show(timing, &mut order)
        }
        Shapes::Scene(_) => vec![],
    };
    let load_at_end = load_average();
    bar.finish_and_clear();
    let record_of = LaunchRecord { load_average: (load_at_start, load_at_end), families: speeds, show };
    write(record, &serde_json::to_string(&record_of).context("failed to serialise the launch's record")?)
}

/// The 1-minute load average, where the system tells it.
fn load_average() -> Option<f64> {
    fs::read_to_string("/proc/loadavg").ok()?.split_whitespace().next()?.parse().ok()
}

/// The processor `/proc/cpuinfo`'s text names: its model name, and on
/// x86 its family and model numbers, which tell apart the generations a
/// model name such as "AMD EPYC" covers.
fn cpu_model(cpuinfo: &str) -> Option<String> {
    let field = |name: &str| {
        cpuinfo.lines().find_map(|line| {
            let (key, value) = line.split_once(':')?;
            (key.trim() == name).then(|| value.trim().to_string())
        })
    };
    let name = field("model name")?;
    Some(match (field("cpu family"), field("model")) {
        (Some(family), Some(model)) => format!("{name} (family {family}, model {model})"),
        _ => name,
    })
}

/// Writes the first polygons of every real-shape family as a scene file
/// (`NAME.scene` in `dir`), as many as the explorer takes in one scene, to
/// be opened there (`cargo xtask explore`, "load one"); makes `dir` only
/// where there are some.
fn write_real_shape_scenes(families: &[corpus::Family], dir: &Path) -> Result<()> {
    let real: Vec<&corpus::Family> = families.iter().filter(|f| f.group == corpus::Group::Real).collect();
    if real.is_empty() {
        return Ok(());
    }
    fs::create_dir_all(dir).with_context(|| format!("failed to create {}", dir.display()))?;
    for family in real {
        write(&dir.join(format!("{}.scene", family.name)), &sample_scene(family))?;
    }
    Ok(())
}

/// The first polygons of `family` as a scene file, within the explorer's
/// limits on a scene's vertices and lines.
fn sample_scene(family: &corpus::Family) -> String {
    use explorer::model::{MAX_OPS, MAX_POLYGON_VERTICES, MAX_SCENE_VERTICES};
    let mut vertices = 0;
    let polygons: Vec<&raster::Polygon> = family
        .polygons
        .iter()
        .filter(|p| p.vertex_count() <= MAX_POLYGON_VERTICES)
        .take_while(|p| {
            vertices += p.vertex_count();
            vertices <= MAX_SCENE_VERTICES
        })
        .take(MAX_OPS - 1)
        .collect();
    let mut text = format!(
        "# The lab's {} family: {}.\n# Its first {} of {} polygons (the explorer takes {MAX_SCENE_VERTICES} vertices a \
         scene).\nclear 0\n",
        family.name,
        family.description,
        polygons.len(),
        family.polygons.len()
    );
    for polygon in polygons {
        text.push_str(&scenes::file::poly_line(polygon));
        text.push('\n');
    }
    text
}

fn write(path: &Path, contents: &str) -> Result<()> {
    fs::write(path, contents).with_context(|| format!("failed to write {}", path.display()))
}

/// Reads results.json back and fails unless `exact` has a row for every
/// family, and every row says, in numbers, that it has no wrong pixel, no
/// overdraw, no refusal and no failure (and no gap where the family tiles:
/// `gaps` is `null` only on families that do not); unless every path of
/// `exact` and `fill_auto` in "what modelling costs" drew no wrong pixel,
/// no overdraw, no gap and never failed (a path may refuse); and unless
/// `fill_auto` allocated nothing per polygon on every family, in a number
/// (the lab binary counts allocations; results from a build that did not,
/// where the figure is `null`, cannot show that). A missing row or field
/// fails: a gate that passes on what it cannot see is no gate.
pub fn check(results_json: &Path) -> Result<()> {
    let text = fs::read_to_string(results_json).with_context(|| format!("{} is missing", results_json.display()))?;
    let results: serde_json::Value =
        serde_json::from_str(&text).with_context(|| format!("{} is not valid JSON", results_json.display()))?;
    let rows = results["rows"].as_array().context("results.json has no rows")?;
    let families = results["families"].as_array().context("results.json has no families")?;
    let modelling = results["modelling"].as_array().context("results.json has no modelling rows")?;
    let mut faults = Vec::new();
    for family in families {
        let name = family["name"].as_str().context("results.json has a family without a name")?;
        let mut exact = rows.iter().filter(|row| row["name"] == EXACT && row["family"] == name);
        let Some(row) = exact.next() else {
            faults.push(format!("{name}: no `{EXACT}` row"));
            continue;
        };
        check_counts(&mut faults, name, row, &["wrong_pixels", "overdraw", "refusals", "failures", "gaps"]);
        let paths = modelling.iter().filter(|row| row["family"] == name && !row["refusals"].is_null());
        let mut lanes = 0;
        for row in paths {
            let lane = format!("{name}, {} path", row["lane"].as_str().unwrap_or("unnamed"));
            check_counts(&mut faults, &lane, row, &["wrong_pixels", "overdraw", "failures", "gaps"]);
            lanes += 1;
        }
        if lanes == 0 {
            faults.push(format!("{name}: no rows of exact's paths"));
        }
        match modelling.iter().find(|row| row["family"] == name && row["lane"] == "fill_auto") {
            None => faults.push(format!("{name}: no fill_auto row")),
            Some(row) => match (&row["allocations_per_polygon"], row["allocations_per_polygon"].as_f64()) {
                (_, Some(0.0)) => {}
                (_, Some(n)) => faults.push(format!("{name}, fill_auto: {n} allocations per polygon")),
                (value, None) => {
                    faults.push(format!("{name}, fill_auto: allocations_per_polygon is {value}, not a number"))
                }
            },
        }
    }
    if families.is_empty() {
        faults.push(String::from("no families"));
    }
    if !faults.is_empty() {
        bail!("`{EXACT}` is not proven exact by {}:\n  {}", results_json.display(), faults.join("\n  "));
    }
    eprintln!(
        "lab: `{EXACT}` has no wrong pixel, overdraw, gap, refusal or failure on any of {} families, nor its paths; \
         fill_auto allocates nothing",
        families.len()
    );
    Ok(())
}

/// Adds a fault for each of `fields` of `row` that is not a zero count
/// (`gaps` may be `null`: no tiling).
fn check_counts(faults: &mut Vec<String>, what: &str, row: &serde_json::Value, fields: &[&str]) {
    for &field in fields {
        match (&row[field], row[field].as_u64()) {
            (_, Some(0)) => {}
            (serde_json::Value::Null, None) if field == "gaps" && row.get(field).is_some() => {}
            (_, Some(value)) => faults.push(format!("{what}: {field} = {value}")),
            (value, None) => faults.push(format!("{what}: {field} is {value}, not a count")),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn results_file(json: &str) -> (tempfile::TempDir, PathBuf) {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("results.json");
        fs::write(&path, json).unwrap();
        (dir, path)
    }

    /// Each real-shape family's sample scene opens in the explorer, as the
    /// very polygons the family begins with, less those with more vertices
    /// than the explorer takes in one polygon (the flags' largest).
    #[test]
    fn the_real_shapes_sample_scenes_open_in_the_explorer() {
        use explorer::model::MAX_POLYGON_VERTICES;
        for family in corpus::build(Budget::QUICK).unwrap().iter().filter(|f| f.group == corpus::Group::Real) {
            let text = sample_scene(family);
            let explorer = explorer::model::Explorer::from_text(&text).unwrap();
            let shown: Vec<&raster::Polygon> = explorer.polygons().collect();
            assert!(shown.len() > 10, "{}: {}", family.name, shown.len());
            let taken = family.polygons.iter().filter(|p| p.vertex_count() <= MAX_POLYGON_VERTICES);
            assert!(shown.iter().zip(taken).all(|(a, b)| *a == b), "{}", family.name);
        }
    }

    /// The processor is named with its family and model where the text
    /// gives them (x86), by its name alone where not, and not at all
    /// where no model name is given.
    #[test]
    fn the_processor_is_read_from_cpuinfo() {
        let x86 =
            "processor\t: 0\nvendor_id\t: AuthenticAMD\ncpu family\t: 25\nmodel\t\t: 17\nmodel name\t: AMD EPYC\n";
        assert_eq!(cpu_model(x86).as_deref(), Some("AMD EPYC (family 25, model 17)"));
        let named = "processor\t: 0\nmodel name\t: Some Core\n";
        assert_eq!(cpu_model(named).as_deref(), Some("Some Core"));
        assert_eq!(cpu_model("processor\t: 0\nBogoMIPS\t: 50.00\n"), None);
    }

    #[test]
    fn a_missing_results_file_fails_the_check() {
        let dir = tempfile::tempdir().unwrap();
        assert!(check(&dir.path().join("results.json")).is_err());
    }

    /// results.json with one family `f`, one `exact` row whose fields are
    /// `fields` (JSON object members) and one clean path row.
    fn exact_row(fields: &str) -> String {
        format!(
            r#"{{"families": [{{"name": "f"}}], "rows": [{{"name": "exact", "family": "f", {fields}}}], "modelling": [{PATH}]}}"#
        )
    }

    const CLEAN: &str = r#""wrong_pixels": 0, "overdraw": 0, "refusals": 0, "failures": 0, "gaps": null"#;
    const PATH: &str = r#"{"family": "f", "lane": "monotone", "refusals": 4, "wrong_pixels": 0, "overdraw": 0, "failures": 0, "gaps": null}, {"family": "f", "lane": "fill_auto", "refusals": 0, "wrong_pixels": 0, "overdraw": 0, "failures": 0, "gaps": null, "allocations_per_polygon": 0.0}"#;

    #[test]
    fn a_clean_exact_row_passes() {
        let (_dir, path) = results_file(&exact_row(CLEAN));
        check(&path).unwrap();
        let (_dir, path) = results_file(&exact_row(&CLEAN.replace("null", "0")));
        check(&path).unwrap();
    }

    #[test]
    fn any_fault_of_exact_fails_naming_the_family_and_field() {
        for (field, bad) in [("wrong_pixels", 3), ("overdraw", 1), ("refusals", 2), ("failures", 1), ("gaps", 4)] {
            let fields = CLEAN.replace(&format!(r#""{field}": 0"#,), &format!(r#""{field}": {bad}"#));
            let fields = if field == "gaps" { CLEAN.replace("null", &bad.to_string()) } else { fields };
            let (_dir, path) = results_file(&exact_row(&fields));
            let error = check(&path).unwrap_err().to_string();
            assert!(error.contains(&format!("f: {field} = {bad}")), "{error}");
        }
    }

    #[test]
    fn a_missing_field_or_row_fails() {
        let (_dir, path) = results_file(&exact_row(&CLEAN.replace(r#""refusals": 0, "#, "")));
        let error = check(&path).unwrap_err().to_string();
        assert!(error.contains("f: refusals is null, not a count"), "{error}");
        let (_dir, path) = results_file(&exact_row(&CLEAN.replace(r#", "gaps": null"#, "")));
        let error = check(&path).unwrap_err().to_string();
        assert!(error.contains("f: gaps is null, not a count"), "{error}");
        let (_dir, path) =
            results_file(r#"{"families": [{"name": "f"}], "rows": [{"name": "wgt", "family": "f"}], "modelling": []}"#);
        let error = check(&path).unwrap_err().to_string();
        assert!(error.contains("f: no `exact` row"), "{error}");
        let (_dir, path) = results_file(r#"{"families": [], "rows": [], "modelling": []}"#);
        assert!(check(&path).is_err());
    }

    #[test]
    fn fill_auto_allocating_fails() {
        let json = exact_row(CLEAN);
        let (_dir, path) =
            results_file(&json.replace(r#""allocations_per_polygon": 0.0"#, r#""allocations_per_polygon": 1.5"#));
        let error = check(&path).unwrap_err().to_string();
        assert!(error.contains("f, fill_auto: 1.5 allocations per polygon"), "{error}");
    }

    #[test]
    fn an_uncounted_or_missing_allocation_figure_fails() {
        let json = exact_row(CLEAN);
        let uncounted = json.replace(r#""allocations_per_polygon": 0.0"#, r#""allocations_per_polygon": null"#);
        let missing = json.replace(r#", "allocations_per_polygon": 0.0"#, "");
        for json in [uncounted, missing] {
            let (_dir, path) = results_file(&json);
            let error = check(&path).unwrap_err().to_string();
            assert!(error.contains("f, fill_auto: allocations_per_polygon is null, not a number"), "{error}");
        }
    }

    #[test]
    fn a_path_drawing_wrong_fails_and_missing_paths_fail() {
        let json = exact_row(CLEAN);
        let (_dir, path) =
            results_file(&json.replace(r#""refusals": 4, "wrong_pixels": 0"#, r#""refusals": 4, "wrong_pixels": 2"#));
        let error = check(&path).unwrap_err().to_string();
        assert!(error.contains("f, monotone path: wrong_pixels = 2"), "{error}");
        let (_dir, path) = results_file(&json.replace(PATH, ""));
        let error = check(&path).unwrap_err().to_string();
        assert!(error.contains("f: no rows of exact's paths"), "{error}");
        let (_dir, path) = results_file(&json.replace(&format!(r#", "modelling": [{PATH}]"#), ""));
        assert!(check(&path).unwrap_err().to_string().contains("no modelling rows"));
    }
}
