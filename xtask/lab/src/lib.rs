//! The polygon-fill lab (`cargo xtask lab`): every method of `raster`, the
//! peers (tiny-skia, embedded-graphics) and two bounds (memset, span write)
//! on one seeded corpus; accuracy against `raster::reference`, speed in
//! wall-clock time; results.json, report.md and four charts under the
//! output directory.
//!
//! Speed is measured, never asserted. What fails a run is a missing
//! results.json or any wrong pixel, overdraw, gap or failure of `exact`.
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

use anyhow::{bail, Context, Result};
use indicatif::{ProgressBar, ProgressStyle};

pub mod charts;
pub mod contender;
pub mod corpus;
pub mod measure;
pub mod peers;
pub mod report;
pub mod results;
pub mod spans;
pub mod stats;
pub mod timing;

use contender::Contender;
use corpus::Budget;
use results::Results;
use timing::Timing;

/// The method held to zero wrong pixels, overdraw, gaps and failures.
pub const EXACT: &str = "exact";

/// What `cargo xtask lab` asks for.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LabOptions {
    /// A small corpus and short timing, for CI.
    pub quick: bool,
    /// Where results.json, report.md and the charts go.
    pub out_dir: PathBuf,
}

impl Default for LabOptions {
    fn default() -> Self {
        Self { quick: false, out_dir: PathBuf::from("target/lab") }
    }
}

/// Runs the lab: measures, writes every output, then checks them.
pub fn run(options: &LabOptions) -> Result<()> {
    let (budget, timing) = if options.quick { (Budget::QUICK, Timing::QUICK) } else { (Budget::FULL, Timing::FULL) };
    if cfg!(debug_assertions) {
        eprintln!("warning: the lab is built without optimisations; its timings mean little (use --release)");
    }
    let results = measure_corpus(options.quick, budget, timing);

    let out = &options.out_dir;
    fs::create_dir_all(out).with_context(|| format!("failed to create {}", out.display()))?;
    let json = serde_json::to_string_pretty(&results).context("failed to serialise the results")?;
    write(&out.join("results.json"), &json)?;
    write(&out.join("report.md"), &report::markdown(&results))?;
    charts::draw_all(&results, out)?;
    eprintln!("lab: wrote results.json, report.md and charts to {}", out.display());
    check(&out.join("results.json"))
}

/// Judges and times every contender on every family, with a progress bar.
fn measure_corpus(quick: bool, budget: Budget, timing: Timing) -> Results {
    let families = corpus::build(budget);
    let contenders = Contender::all();
    let work: u64 = families.iter().map(|f| f.polygons.len() as u64 + timing::jobs(f, contenders.len())).sum();
    let bar = ProgressBar::new(work).with_style(
        ProgressStyle::with_template("{elapsed_precise} [{bar:40}] {percent:>3}% {msg}")
            .expect("the progress template is valid")
            .progress_chars("=> "),
    );
    let mut results = Results::new(corpus::SEED, quick, &contenders);
    for family in &families {
        bar.set_message(format!("judging {}", family.name));
        let judged = measure::quietly(|| measure::judge(family, &contenders, &|| bar.inc(1)));
        bar.set_message(format!("timing {}", family.name));
        let speeds = timing::time_family(family, &judged, &contenders, timing, &|| bar.inc(1));
        results.add_family(family, &contenders, &judged, &speeds);
    }
    bar.finish_and_clear();
    results
}

fn write(path: &Path, contents: &str) -> Result<()> {
    fs::write(path, contents).with_context(|| format!("failed to write {}", path.display()))
}

/// Reads results.json back and fails if `exact` (once it exists) has any
/// wrong pixel, overdraw, gap or failure on any family.
pub fn check(results_json: &Path) -> Result<()> {
    let text = fs::read_to_string(results_json).with_context(|| format!("{} is missing", results_json.display()))?;
    let results: serde_json::Value =
        serde_json::from_str(&text).with_context(|| format!("{} is not valid JSON", results_json.display()))?;
    let rows = results["rows"].as_array().context("results.json has no rows")?;
    let exact: Vec<&serde_json::Value> = rows.iter().filter(|r| r["name"] == EXACT).collect();
    if exact.is_empty() {
        eprintln!("lab: no `{EXACT}` method yet; nothing to hold to zero");
        return Ok(());
    }
    let mut faults = Vec::new();
    for row in exact {
        for field in ["wrong_pixels", "overdraw", "gaps", "failures"] {
            let value = row[field].as_u64().unwrap_or(0);
            if value > 0 {
                faults.push(format!("{}: {field} = {value}", row["family"].as_str().unwrap_or("?")));
            }
        }
    }
    if !faults.is_empty() {
        bail!("`{EXACT}` is not exact:\n  {}", faults.join("\n  "));
    }
    eprintln!("lab: `{EXACT}` has no wrong pixel, overdraw, gap or failure on any family");
    Ok(())
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

    #[test]
    fn a_missing_results_file_fails_the_check() {
        let dir = tempfile::tempdir().unwrap();
        assert!(check(&dir.path().join("results.json")).is_err());
    }

    #[test]
    fn exact_must_have_nothing_wrong() {
        let row = |wrong: u64| {
            format!(
                r#"{{"rows": [{{"name": "exact", "family": "f", "wrong_pixels": {wrong}, "overdraw": 0, "gaps": null, "failures": 0}}]}}"#
            )
        };
        let (_dir, path) = results_file(&row(0));
        assert!(check(&path).is_ok());
        let (_dir, path) = results_file(&row(3));
        let error = check(&path).unwrap_err().to_string();
        assert!(error.contains("f: wrong_pixels = 3"), "{error}");
    }

    #[test]
    fn without_exact_only_the_file_is_checked() {
        let (_dir, path) = results_file(r#"{"rows": [{"name": "wgt", "wrong_pixels": 9}]}"#);
        assert!(check(&path).is_ok());
    }
}
