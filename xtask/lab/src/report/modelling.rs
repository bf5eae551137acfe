//! report.md's "What modelling costs": each family through each of
//! `exact`'s paths, `fill_auto` and classification alone; then the show's
//! shaded entries as they need and over-modelled.

use std::fmt::Write;

use super::format::{count, duration, ratio};
use crate::lane::Lane;
use crate::results::{Results, EXACT};

/// What modelling costs: each family through each of exact's paths, fill_auto
/// and classification alone; then the show's shaded entries, where the run
/// timed them (not on the user's scene).
pub(super) fn modelling_tables(out: &mut String, results: &Results) {
    let _ = writeln!(
        out,
        "## What modelling costs\n\nEach family drawn by `{EXACT}` through each of its paths alone (a path refuses \
         polygons outside its class), by `fill_auto` (its classification, then the path it picks), and classified \
         alone: `dispatch` is `fill_auto`'s own classification, `classify` is `raster::classify` (every class, \
         simplicity included); `spans unstored` is `fill_auto` into a sink that stores nothing, what finding the \
         spans costs alone. The paths and `fill_auto` keep one `Scratch` from polygon to polygon, as a program \
         drawing frame after frame would. Every lane is timed in turn with the family's contenders and bounds, so its \
         ratios to `exact`'s time and the store bound's are paired within each launch, and taken across launches \
         (results.json's `vs_exact` and `vs_store`, each with its interval). Cells: time per polygon (the median), time over the cheapest path's that takes the \
         whole family, heap allocations per polygon once the lane has gone over the family (a scratch grown to the \
         largest polygon allocates no more); ← marks the path `fill_auto` picks, with how many polygons.\n"
    );
    let lanes: Vec<&str> = Lane::all().into_iter().map(Lane::name).collect();
    let _ = writeln!(out, "| family | {} |\n|---|{}", lanes.join(" | "), "---:|".repeat(lanes.len()));
    let mut slower = Vec::new();
    for f in &results.families {
        let row = |lane: &str| results.modelling.iter().find(|r| r.family == f.name && r.lane == lane);
        let auto = row("fill_auto");
        let cells: Vec<String> = lanes
            .iter()
            .map(|&lane| {
                let Some(r) = row(lane) else { return "–".to_string() };
                let mut cell = match (r.time.ns_per_polygon, r.refusals) {
                    (None, Some(refused)) => format!("refuses {}", count(refused)),
                    (None, None) => "–".to_string(),
                    (Some(ns), _) => duration(ns),
                };
                if let Some(ratio) = r.time_vs_cheapest {
                    let _ = write!(cell, " ({ratio:.2}×)");
                }
                if lane == "dispatch" || lane == "spans unstored" {
                    if let (Some(ns), Some(total)) = (r.time.ns_per_polygon, auto.and_then(|a| a.time.ns_per_polygon)) {
                        let _ = write!(cell, " ({:.0}% of fill_auto)", 100.0 * ns / total);
                    }
                }
                if let Some(allocations) = r.allocations_per_polygon {
                    let _ = write!(cell, ", {allocations:.1} alloc");
                }
                if let Some(chosen) = r.chosen_by_fill_auto.filter(|&n| n > 0) {
                    let _ = write!(cell, " ← {}", count(chosen));
                }
                cell
            })
            .collect();
        let _ = writeln!(out, "| {} | {} |", f.name, cells.join(" | "));
        if let Some(ratio) = auto.and_then(|a| a.time_vs_cheapest).filter(|&r| r > 1.05) {
            slower.push(format!("{} ({ratio:.2}×)", f.name));
        }
    }
    if slower.is_empty() {
        let _ = writeln!(out, "\n`fill_auto` is within 5% of the cheapest path on every family.\n");
    } else {
        let _ =
            writeln!(out, "\n`fill_auto` is more than 5% slower than the cheapest path on: {}.\n", slower.join(", "));
    }
    if results.show_modelling.is_empty() {
        return;
    }
    let _ = writeln!(
        out,
        "The show's shaded entries, every frame drawn by `{EXACT}`: as they need (one interpolated attribute for \
         Gouraud, two for the texture, two and a depth buffer for the Z-buffer), and with four attributes and a \
         depth buffer forced on (the same pictures).\n\n| entry | as needed, per frame | over-modelled, per frame | \
         over-modelled / needed (interval) |\n|---|---:|---:|---:|"
    );
    let entries: Vec<&str> = results.show_modelling.iter().map(|r| r.entry).fold(Vec::new(), |mut seen, e| {
        if !seen.contains(&e) {
            seen.push(e);
        }
        seen
    });
    for entry in entries {
        let row = |m: &str| results.show_modelling.iter().find(|r| r.entry == entry && r.modelling == m);
        let time = |m: &str| {
            row(m).and_then(|r| r.ns_per_frame).map_or("–".to_string(), |t| {
                format!("{} ({}–{})", duration(t.median), duration(t.min), duration(t.max))
            })
        };
        let ratio = row("forced").and_then(|r| r.time_vs_needed.as_ref()).map_or("–".to_string(), ratio);
        let _ = writeln!(out, "| {entry} | {} | {} | {ratio} |", time("needed"), time("forced"));
    }
    out.push('\n');
}
