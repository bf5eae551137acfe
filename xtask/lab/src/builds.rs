//! Two builds side by side (`cargo xtask lab --build both`): each build's
//! run is whole in a folder of its own, with its results.json and
//! report.md; this reads their results.json back and writes a report.md
//! above them that sets, build by build, the machine, `exact`'s goals and
//! every family's closest peer and lowest lower end next to each other.

use std::fmt::Write;
use std::fs;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use serde_json::Value;

/// A build's run: its name and the folder its outputs are in.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BuildRun {
    pub name: String,
    pub dir: PathBuf,
}

impl BuildRun {
    /// `NAME=DIR`, as `lab --compare` takes it.
    pub fn parse(text: &str) -> Result<BuildRun, String> {
        let (name, dir) = text.split_once('=').ok_or_else(|| format!("`{text}` is not NAME=DIR"))?;
        Ok(BuildRun { name: name.to_string(), dir: PathBuf::from(dir) })
    }
}

/// Reads each build's results.json and writes `out`/report.md setting
/// them side by side.
pub fn compare(runs: &[BuildRun], out: &Path) -> Result<()> {
    let results: Vec<Value> = runs
        .iter()
        .map(|run| {
            let path = run.dir.join("results.json");
            let text = fs::read_to_string(&path).with_context(|| format!("{} is missing", path.display()))?;
            serde_json::from_str(&text).with_context(|| format!("{} is not valid JSON", path.display()))
        })
        .collect::<Result<_>>()?;
    let path = out.join("report.md");
    fs::write(&path, markdown(runs, &results)).with_context(|| format!("failed to write {}", path.display()))?;
    eprintln!("lab: wrote {}, the builds side by side", path.display());
    Ok(())
}

/// The report of `runs` side by side, from their results.
fn markdown(runs: &[BuildRun], results: &[Value]) -> String {
    let names: Vec<&str> = runs.iter().map(|r| r.name.as_str()).collect();
    let mut out = format!(
        "# Polygon-fill lab: {} builds\n\nEach build measured whole, one after the other; each one's own report is \
         its folder's report.md ({}).\n\n| build | commit | compiled for | processor | launches | load average, \
         first launch's start – last's end |\n|---|---|---|---|---:|---|\n",
        runs.len(),
        names.iter().map(|n| format!("{n}/report.md")).collect::<Vec<_>>().join(", ")
    );
    for (name, r) in names.iter().zip(results) {
        let load = |v: &Value| v.as_f64().map_or("unknown".to_string(), |l| format!("{l:.2}"));
        let features: Vec<&str> =
            r["build"]["features"].as_array().into_iter().flatten().filter_map(Value::as_str).collect();
        let _ = writeln!(
            out,
            "| {name} | {} | {} | {} | {} | {} – {} |",
            r["build"]["commit"].as_str().unwrap_or("unknown"),
            if features.is_empty() { "no feature past SSE2".to_string() } else { features.join(", ") },
            r["timing"]["cpu"].as_str().unwrap_or("unknown"),
            r["timing"]["launches"],
            load(&r["timing"]["load_average"][0]),
            load(&r["timing"]["load_average"][1]),
        );
    }
    let _ = writeln!(
        out,
        "\n## `exact` against its goals\n\n| goal | {} |\n|---|{}",
        names.join(" | "),
        "---|".repeat(names.len())
    );
    let goals = results.first().and_then(|r| r["goals"].as_array()).cloned().unwrap_or_default();
    for (g, goal) in goals.iter().enumerate() {
        let cells: Vec<String> = results
            .iter()
            .map(|r| {
                let goal = &r["goals"][g];
                let shown = goal["note"].as_str().map_or_else(|| goal["value"].to_string(), str::to_string);
                format!("{shown} ({})", if goal["met"] == true { "met" } else { "not met" })
            })
            .collect();
        let _ = writeln!(out, "| {} | {} |", goal["measure"].as_str().unwrap_or("?"), cells.join(" | "));
    }
    let _ = writeln!(
        out,
        "\n## The closest peer and the lowest lower end on every family\n\nPer build: the peer whose time over \
         `exact`'s (on the polygons it drew) is the least, that ratio across launches with its interval, and the \
         lowest lower end of the intervals across launches over the family's peers, with whose it is.\n\n| family | \
         {} |\n|---|{}",
        names.iter().map(|n| format!("{n}: closest peer | {n}: lowest lower end")).collect::<Vec<_>>().join(" | "),
        "---|---:|".repeat(names.len())
    );
    let families = results.first().and_then(|r| r["families"].as_array()).cloned().unwrap_or_default();
    for family in families.iter().filter_map(|f| f["name"].as_str()) {
        let cells: Vec<String> = results.iter().map(|r| closest_and_lowest(r, family)).collect();
        let _ = writeln!(out, "| {family} | {} |", cells.join(" | "));
    }
    out
}

/// A build's two cells on `family`: the closest peer with its ratio, and
/// the lowest lower end with its peer.
fn closest_and_lowest(results: &Value, family: &str) -> String {
    let peers: Vec<&Value> = results["rows"]
        .as_array()
        .into_iter()
        .flatten()
        .filter(|row| row["kind"] == "peer" && row["family"] == family && row["vs_exact"].is_object())
        .collect();
    let ratio = |row: &Value| row["vs_exact"]["ratio"].as_f64().unwrap_or(f64::INFINITY);
    let low = |row: &Value| row["vs_exact"]["low"].as_f64().unwrap_or(0.0);
    let closest = peers.iter().min_by(|a, b| ratio(a).total_cmp(&ratio(b)));
    let lowest = peers.iter().min_by(|a, b| low(a).total_cmp(&low(b)));
    let (Some(closest), Some(lowest)) = (closest, lowest) else { return "– | –".to_string() };
    let interval = match (closest["vs_exact"]["low"].as_f64(), closest["vs_exact"]["high"].as_f64()) {
        (Some(l), Some(h)) => format!(" ({l:.2}–{h:.2})"),
        _ => String::new(),
    };
    format!(
        "{} {:.2}×{interval} | {:.2} ({})",
        closest["name"].as_str().unwrap_or("?"),
        ratio(closest),
        low(lowest),
        lowest["name"].as_str().unwrap_or("?")
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn results(commit: &str, low: f64) -> Value {
        serde_json::json!({
            "build": {"name": commit, "commit": commit, "features": ["avx2"]},
            "timing": {"cpu": "Some CPU", "launches": 3, "load_average": [1.0, 1.5]},
            "goals": [{"measure": "speed", "note": "fine", "value": low, "met": true}],
            "families": [{"name": "stars"}],
            "rows": [
                {"name": "tiny-skia", "kind": "peer", "family": "stars", "vs_exact": {"ratio": 2.2, "low": 2.1, "high": 2.3}},
                {"name": "cairo", "kind": "peer", "family": "stars", "vs_exact": {"ratio": 2.4, "low": low, "high": 3.0}},
                {"name": "exact", "kind": "method", "family": "stars", "vs_exact": {"ratio": 1.0}}
            ]
        })
    }

    /// Both builds' machines, goals and families stand side by side; the
    /// lowest lower end is the peer's whose interval reaches lowest.
    #[test]
    fn the_builds_stand_side_by_side() {
        let runs = ["native=a", "x86-64-v3=b"].map(|t| BuildRun::parse(t).unwrap());
        let report = markdown(&runs, &[results("aaa", 2.0), results("bbb", 1.9)]);
        assert!(report.contains("| native | aaa | avx2 | Some CPU | 3 | 1.00 – 1.50 |"), "{report}");
        assert!(report.contains("| speed | fine (met) | fine (met) |"), "{report}");
        assert!(
            report.contains(
                "| stars | tiny-skia 2.20× (2.10–2.30) | 2.00 (cairo) | tiny-skia 2.20× (2.10–2.30) | 1.90 (cairo) |"
            ),
            "{report}"
        );
        assert!(BuildRun::parse("nodir").is_err());
    }
}
