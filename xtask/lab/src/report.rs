//! report.md: the corpus, the contenders, tables of every measure, how
//! `exact` stands against its goals, and one sentence per classic method
//! on where it fails, tied to its seed. Every number comes from
//! [`Results`]; nothing here measures.

use std::fmt::Write;

use crate::corpus::Group;
use crate::results::{Kind, Results, Row, EXACT, ZERO_FLOOR};
use crate::stats::pareto_front;

/// The whole report.
pub fn markdown(results: &Results) -> String {
    let mut out = String::new();
    let mode = if results.quick { "quick (`--quick`, a small corpus)" } else { "full" };
    let _ = writeln!(out, "# Polygon-fill lab\n");
    let _ = writeln!(
        out,
        "Run: {mode}; corpus seed `{:#x}`. Host wall-clock times in release, median of repeats, \
         filling into a 320x200 framebuffer; accuracy against `raster::reference`. \
         Charts: speed_vs_accuracy, stability, rotation, scaling, modelling_cost (.svg and .png beside this file).\n",
        results.seed
    );
    corpus_table(&mut out, results);
    contender_table(&mut out, results);
    exact_goals(&mut out, results);
    modelling_tables(&mut out, results);
    classic_failures(&mut out, results);
    peers_on_everyday_families(&mut out, results);
    measure_table(&mut out, results, "Speed: ns per polygon", true, |r| r.ns_per_polygon.map(duration));
    measure_table(&mut out, results, "Speed: time over the memset bound's", false, |r| {
        r.time_vs_memset.map(|x| format!("{x:.1}×"))
    });
    measure_table(&mut out, results, "Wrong pixels: our convention / the method's own", false, |r| {
        Some(format!("{} / {}", count(r.wrong_pixels?), count(r.wrong_pixels_own?)))
    });
    measure_table(
        &mut out,
        results,
        "Missing pixels (the reference's, left out): our convention / the method's own",
        false,
        |r| Some(format!("{} / {}", count(r.missing_pixels?), count(r.missing_pixels_own?))),
    );
    measure_table(&mut out, results, "Overdraw / gaps (gaps on tilings only)", false, |r| {
        let gaps = r.gaps.map_or("–".to_string(), count);
        Some(format!("{} / {gaps}", count(r.overdraw?)))
    });
    measure_table(&mut out, results, "Failures / declined polygons", false, |r| {
        Some(format!("{} / {}", count(r.failures?), count(r.refusals?)))
    });
    measure_table(&mut out, results, "Mean centroid bias (dx, dy) in pixels", false, |r| {
        r.centroid_bias.map(|(dx, dy)| format!("{dx:+.2}, {dy:+.2}"))
    });
    pareto_list(&mut out, results);
    out
}

fn corpus_table(out: &mut String, results: &Results) {
    let _ = writeln!(out, "## Corpus\n\n| family | group | polygons | exact pixels | what |\n|---|---|---:|---:|---|");
    for f in &results.families {
        let _ = writeln!(
            out,
            "| {} | {} | {} | {} | {} |",
            f.name,
            group(f.group),
            count(f.polygons as u64),
            count(f.pixels),
            f.description
        );
    }
    out.push('\n');
}

fn contender_table(out: &mut String, results: &Results) {
    let _ = writeln!(out, "## Contenders\n\n| name | kind | source | arithmetic and convention |\n|---|---|---|---|");
    for c in &results.contenders {
        let kind = match c.kind {
            Kind::Method => "method",
            Kind::Peer => "peer",
            Kind::Bound => "bound",
        };
        let _ = writeln!(out, "| {} | {kind} | {} | {} |", c.name, c.source, c.summary);
    }
    out.push('\n');
}

/// Where `exact` stands against its goals, in numbers, one run.
fn exact_goals(out: &mut String, results: &Results) {
    let _ = writeln!(out, "## `{EXACT}` against its goals\n");
    let rows: Vec<&Row> = results.rows_of(EXACT).collect();
    if rows.is_empty() {
        let _ = writeln!(out, "No `{EXACT}` method in `raster::MethodId::ALL` yet.\n");
        return;
    }
    let sum = |pick: fn(&Row) -> Option<u64>| rows.iter().filter_map(|r| pick(r)).sum::<u64>();
    let _ = writeln!(
        out,
        "- Whole corpus: {} wrong pixels, {} overdrawn, {} gaps, {} failures, {} declined polygons.\n",
        count(sum(|r| r.wrong_pixels)),
        count(sum(|r| r.overdraw)),
        count(sum(|r| r.gaps)),
        count(sum(|r| r.failures)),
        count(sum(|r| r.refusals)),
    );
    let _ = writeln!(out, "| measure | measured | goal | met |\n|---|---:|---|---|");
    for goal in &results.goals {
        let shown = match (&goal.note, goal.value) {
            (Some(note), _) => note.clone(),
            (None, Some(v)) => format!("{v}"),
            (None, None) => "not measured".to_string(),
        };
        let _ =
            writeln!(out, "| {} | {shown} | {} | {} |", goal.measure, goal.goal, if goal.met { "yes" } else { "no" });
    }
    out.push('\n');
}

/// What modelling costs: each family through each of exact's paths, fill_auto
/// and classification alone; then the show's shaded entries.
fn modelling_tables(out: &mut String, results: &Results) {
    let _ = writeln!(
        out,
        "## What modelling costs\n\nEach family drawn by `{EXACT}` through each of its paths alone (a path refuses \
         polygons outside its class), by `fill_auto` (its classification, then the path it picks), and classified \
         alone: `dispatch` is `fill_auto`'s own classification, `classify` is `raster::classify` (every class, \
         simplicity included); `spans unstored` is `fill_auto` into a sink that stores nothing, what finding the \
         spans costs alone. The paths and `fill_auto` keep one `Scratch` from polygon to polygon, as a program \
         drawing frame after frame would. Cells: time per polygon, time over the cheapest path's that takes the \
         whole family, heap allocations per polygon once the lane has gone over the family (a scratch grown to the \
         largest polygon allocates no more); ← marks the path `fill_auto` picks, with how many polygons.\n"
    );
    let lanes = crate::modelling::Lane::ALL.map(|lane| lane.name());
    let _ = writeln!(out, "| family | {} |\n|---|{}", lanes.join(" | "), "---:|".repeat(lanes.len()));
    let mut slower = Vec::new();
    for f in &results.families {
        let row = |lane: &str| results.modelling.iter().find(|r| r.family == f.name && r.lane == lane);
        let auto = row("fill_auto");
        let cells: Vec<String> = lanes
            .iter()
            .map(|&lane| {
                let Some(r) = row(lane) else { return "–".to_string() };
                let mut cell = match (r.ns_per_polygon, r.refusals) {
                    (None, Some(refused)) => format!("refuses {}", count(refused)),
                    (None, None) => "–".to_string(),
                    (Some(ns), _) => duration(ns),
                };
                if let Some(ratio) = r.time_vs_cheapest {
                    let _ = write!(cell, " ({ratio:.2}×)");
                }
                if lane == "dispatch" || lane == "spans unstored" {
                    if let (Some(ns), Some(total)) = (r.ns_per_polygon, auto.and_then(|a| a.ns_per_polygon)) {
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
    let _ = writeln!(
        out,
        "The show's shaded entries, every frame drawn by `{EXACT}`: as they need (one interpolated attribute for \
         Gouraud, two for the texture, two and a depth buffer for the Z-buffer), and with four attributes and a \
         depth buffer forced on (the same pictures).\n\n| entry | as needed, per frame | over-modelled, per frame | \
         over-modelled / needed |\n|---|---:|---:|---:|"
    );
    let entries: Vec<&str> = results.show_modelling.iter().map(|r| r.entry).fold(Vec::new(), |mut seen, e| {
        if !seen.contains(&e) {
            seen.push(e);
        }
        seen
    });
    for entry in entries {
        let row = |m: &str| results.show_modelling.iter().find(|r| r.entry == entry && r.modelling == m);
        let time = |m: &str| row(m).and_then(|r| r.ns_per_frame).map_or("–".to_string(), duration);
        let ratio = row("forced").and_then(|r| r.time_vs_needed).map_or("–".to_string(), |x| format!("{x:.2}×"));
        let _ = writeln!(out, "| {entry} | {} | {} | {ratio} |", time("needed"), time("forced"));
    }
    out.push('\n');
}

/// One sentence per classic method: how far it is from exact under our
/// convention and its own, where it is worst, what it draws twice or
/// leaves out, what it declines and where it fails.
fn classic_failures(out: &mut String, results: &Results) {
    let _ = writeln!(
        out,
        "## Where each classic method fails\n\nTotals over the whole corpus; \"own convention\" samples where the method \
         does (see Contenders); declined polygons draw nothing and are not counted as wrong.\n"
    );
    for c in results.contenders.iter().filter(|c| c.kind == Kind::Method && c.name != EXACT) {
        let rows: Vec<&Row> = results.rows_of(c.name).collect();
        let sum = |pick: fn(&Row) -> Option<u64>| rows.iter().filter_map(|r| pick(r)).sum::<u64>();
        let mut parts = vec![format!(
            "differs from the exact fill in {} pixels under our convention and {} under its own",
            count(sum(|r| r.wrong_pixels)),
            count(sum(|r| r.wrong_pixels_own)),
        )];
        let worst = rows
            .iter()
            .filter(|r| r.pixels > 0 && r.wrong_pixels_own.unwrap_or(0) > 0)
            .max_by(|a, b| own_rate(a).total_cmp(&own_rate(b)));
        if let Some(w) = worst {
            parts.push(format!(
                "it is worst on {}, wrong by its own convention in {:.1}% of the exact pixels ({} of {} polygons faulty)",
                w.family,
                own_rate(w) * 100.0,
                count(w.faulty_polygons.unwrap_or(0)),
                count(w.polygons),
            ));
        }
        for r in rows.iter().filter(|r| r.pixels == 0 && r.wrong_pixels_own.unwrap_or(0) > 0) {
            parts.push(format!(
                "it draws {} pixels on {}, where the exact fill draws none",
                count(r.wrong_pixels_own.unwrap_or(0)),
                r.family
            ));
        }
        let overdraw = sum(|r| r.overdraw);
        if overdraw > 0 {
            parts.push(format!("draws {} pixels twice", count(overdraw)));
        }
        let gaps = sum(|r| r.gaps);
        if gaps > 0 {
            parts.push(format!("leaves {} pixels of tilings undrawn", count(gaps)));
        }
        let refused = sum(|r| r.refusals);
        if let Some(first) = rows.iter().find_map(|r| Some(format!("{}, {}", r.family, r.first_refusal.as_ref()?))) {
            parts.push(format!("declines {} polygons (first: {first})", count(refused)));
        }
        let failed = sum(|r| r.failures);
        match rows.iter().find_map(|r| Some(format!("{}, {}", r.family, r.first_failure.as_ref()?))) {
            Some(first) => parts.push(format!("and fails {} times (first: {first})", count(failed))),
            None => parts.push("and never fails".to_string()),
        }
        let _ = writeln!(out, "- **{}** ({}) {}.", c.name, c.source, parts.join("; "));
    }
    out.push('\n');
}

/// The peers on the everyday families: each one's time per polygon and
/// wrong pixels under its own convention, family by family; then, over
/// the families each draws whole (declining and failing on none), its
/// time against `exact`'s and its wrong pixels, with the fastest and the
/// most exact of them.
fn peers_on_everyday_families(out: &mut String, results: &Results) {
    let peers: Vec<&str> = results.contenders.iter().filter(|c| c.kind == Kind::Peer).map(|c| c.name).collect();
    let _ = writeln!(
        out,
        "## The peers on the everyday families\n\nTime per polygon and wrong pixels under the peer's own convention \
         (`exact`'s own is ours); a peer is timed on the polygons it drew, and declined ones are counted.\n"
    );
    let _ = writeln!(out, "| family | {EXACT} | {} |\n|---|{}", peers.join(" | "), "---:|".repeat(peers.len() + 1));
    for f in results.families.iter().filter(|f| f.group.is_everyday()) {
        let cells: Vec<String> = std::iter::once(EXACT)
            .chain(peers.iter().copied())
            .map(|name| {
                let Some(r) = results.row(name, f.name) else { return "–".to_string() };
                let mut cell = format!(
                    "{}, {}",
                    r.ns_per_polygon.map_or("–".to_string(), duration),
                    r.wrong_pixels_own.map_or("–".to_string(), count)
                );
                if let Some(declined) = r.refusals.filter(|&n| n > 0) {
                    let _ = write!(cell, " ({} declined)", count(declined));
                }
                cell
            })
            .collect();
        let _ = writeln!(out, "| {} | {} |", f.name, cells.join(" | "));
    }
    let _ = writeln!(
        out,
        "\nOver the everyday families each peer draws whole: its time over `{EXACT}`'s (geometric mean of the \
         families' ratios) and its wrong pixels in % of the exact pixels of those families.\n\n\
         | peer | families | time / exact's | wrong, our convention | wrong, its own |\n|---|---:|---:|---:|---:|"
    );
    let summaries: Vec<PeerSummary> = peers.iter().filter_map(|&peer| PeerSummary::of(results, peer)).collect();
    for s in &summaries {
        let _ = writeln!(
            out,
            "| {} | {} | {:.2}× | {:.3}% | {:.3}% |",
            s.name,
            s.families,
            s.time_over_exact,
            s.wrong * 100.0,
            s.wrong_own * 100.0
        );
    }
    let fastest = summaries.iter().min_by(|a, b| a.time_over_exact.total_cmp(&b.time_over_exact));
    let most_exact = summaries.iter().min_by(|a, b| a.wrong.total_cmp(&b.wrong));
    if let (Some(fastest), Some(most_exact)) = (fastest, most_exact) {
        let _ = writeln!(
            out,
            "\nFastest of the peers: {} ({:.2}× `{EXACT}`'s time); most exact: {} ({:.3}% of the pixels wrong under \
             our convention).",
            fastest.name,
            fastest.time_over_exact,
            most_exact.name,
            most_exact.wrong * 100.0
        );
    }
    out.push('\n');
}

/// One peer over the everyday families it draws whole.
struct PeerSummary {
    name: &'static str,
    families: usize,
    /// Geometric mean of its time per polygon over `exact`'s.
    time_over_exact: f64,
    /// Wrong pixels per exact pixel, our convention and its own.
    wrong: f64,
    wrong_own: f64,
}

impl PeerSummary {
    fn of(results: &Results, name: &'static str) -> Option<Self> {
        let whole: Vec<(&Row, f64)> = results
            .rows_of(name)
            .filter(|r| r.group.is_everyday() && r.refusals == Some(0) && r.failures == Some(0))
            .filter_map(|r| Some((r, r.ns_per_polygon? / results.row(EXACT, r.family)?.ns_per_polygon?)))
            .collect();
        if whole.is_empty() {
            return None;
        }
        let pixels = whole.iter().map(|(r, _)| r.pixels).sum::<u64>().max(1) as f64;
        let rate =
            |pick: fn(&Row) -> Option<u64>| whole.iter().filter_map(|(r, _)| pick(r)).sum::<u64>() as f64 / pixels;
        let log_mean = whole.iter().map(|(_, ratio)| ratio.ln()).sum::<f64>() / whole.len() as f64;
        Some(Self {
            name,
            families: whole.len(),
            time_over_exact: log_mean.exp(),
            wrong: rate(|r| r.wrong_pixels),
            wrong_own: rate(|r| r.wrong_pixels_own),
        })
    }
}

fn own_rate(r: &Row) -> f64 {
    r.wrong_pixels_own.unwrap_or(0) as f64 / r.pixels as f64
}

/// A table of one measure, families down, contenders across.
fn measure_table(
    out: &mut String,
    results: &Results,
    title: &str,
    with_bounds: bool,
    cell: impl Fn(&Row) -> Option<String>,
) {
    let columns: Vec<&str> =
        results.contenders.iter().filter(|c| with_bounds || c.kind != Kind::Bound).map(|c| c.name).collect();
    let _ = writeln!(out, "## {title}\n\n| family | {} |", columns.join(" | "));
    let _ = writeln!(out, "|---|{}", "---:|".repeat(columns.len()));
    for f in &results.families {
        let cells: Vec<String> =
            columns.iter().map(|c| results.row(c, f.name).and_then(&cell).unwrap_or_else(|| "–".to_string())).collect();
        let _ = writeln!(out, "| {} | {} |", f.name, cells.join(" | "));
    }
    out.push('\n');
}

fn pareto_list(out: &mut String, results: &Results) {
    let means = results.speed_accuracy_means(ZERO_FLOOR);
    let coordinates: Vec<(f64, f64)> = means.iter().map(|m| m.at).collect();
    let front: Vec<String> = pareto_front(&coordinates)
        .into_iter()
        .map(|i| {
            let (x, y) = means[i].at;
            let error = if y <= ZERO_FLOOR { "no wrong pixel".to_string() } else { format!("{y:.3}% wrong") };
            format!("{} ({x:.1}× memset, {error}, over {} families)", means[i].name, means[i].families)
        })
        .collect();
    let _ = writeln!(
        out,
        "## Pareto front of speed_vs_accuracy\n\nOf the methods' and peers' geometric means over the everyday \
         families: {}\n",
        front.join("; ")
    );
}

fn group(g: Group) -> &'static str {
    match g {
        Group::Scene => "scene",
        Group::Random => "random",
        Group::Tiling => "tiling",
        Group::Stress => "stress",
    }
}

/// Nanoseconds, readably.
fn duration(ns: f64) -> String {
    if ns >= 1e6 {
        format!("{:.2} ms", ns / 1e6)
    } else if ns >= 1e3 {
        format!("{:.2} µs", ns / 1e3)
    } else {
        format!("{ns:.0} ns")
    }
}

/// An integer with thin thousands separators.
fn count(n: u64) -> String {
    let digits = n.to_string();
    let mut grouped = String::new();
    for (i, d) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i).is_multiple_of(3) {
            grouped.push(',');
        }
        grouped.push(d);
    }
    grouped
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_group_thousands() {
        assert_eq!(count(0), "0");
        assert_eq!(count(999), "999");
        assert_eq!(count(1_234_567), "1,234,567");
    }

    #[test]
    fn durations_pick_their_unit() {
        assert_eq!(duration(820.4), "820 ns");
        assert_eq!(duration(1_500.0), "1.50 µs");
        assert_eq!(duration(2_500_000.0), "2.50 ms");
    }
}
