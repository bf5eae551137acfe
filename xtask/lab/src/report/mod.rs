//! report.md: the corpus, the contenders, tables of every measure, how
//! `exact` stands against its goals, and one sentence per classic method
//! on where it fails, tied to its seed. Every number comes from
//! [`Results`]; nothing here measures. What modelling costs is in
//! `modelling.rs`; the speed tables with their spread, the peers and the
//! launches' disagreement in `speed.rs`; what each contender does inside the
//! clock in `clock.rs`.

mod clock;
mod format;
mod modelling;
mod speed;
mod summary;

pub use clock::clock_table;
pub use summary::Summary;

use std::fmt::Write;

use crate::corpus::Group;
use crate::results::{GoalRow, Kind, Results, Row, EXACT, ZERO_FLOOR};
use crate::stats::pareto_front;
use format::{count, duration, ratio};

/// The machine and the build, in a sentence each: the processor, the
/// build with its commit and the CPU features it was compiled to use, and
/// the load average when the first launch started and the last ended,
/// launch by launch.
pub fn machine(results: &Results) -> String {
    let (build, timing) = (&results.build, &results.timing);
    let load = |l: Option<f64>| l.map_or("unknown".to_string(), |l| format!("{l:.2}"));
    let per_launch: Vec<String> =
        timing.launch_loads.iter().map(|(start, end)| format!("{}–{}", load(*start), load(*end))).collect();
    let features =
        if build.features.is_empty() { "no feature past SSE2".to_string() } else { build.features.join(", ") };
    let avx512 = if build.features.iter().any(|f| f.starts_with("avx512")) { "" } else { ", no AVX-512" };
    format!(
        "Processor: {}. Build: `{}` of commit {}, compiled for {features}{avx512}. Load average {} when the first \
         launch started, {} when the last ended (launch by launch: {}).",
        timing.cpu.as_deref().unwrap_or("unknown"),
        build.name,
        build.commit.as_deref().unwrap_or("unknown"),
        load(timing.load_average.0),
        load(timing.load_average.1),
        per_launch.join(", ")
    )
}

/// What the console is told at the end of a run: the machine and the
/// build ([`machine`]), and `exact` against its goals.
pub fn summary(results: &Results) -> String {
    let mut out = format!("lab: {}", machine(results));
    for goal in &results.goals {
        let met = if goal.met { "met" } else { "not met" };
        let _ = write!(out, "\nlab: {}: {} (goal: {}; {met})", goal.measure, shown(goal), goal.goal);
    }
    out
}

/// The whole report.
pub fn markdown(results: &Results) -> String {
    let mut out = String::new();
    let measured = match (&results.scene, results.quick) {
        (None, true) => format!("quick (`--quick`, a small corpus); corpus seed `{:#x}`", results.seed),
        (None, false) => format!("full; corpus seed `{:#x}`", results.seed),
        (Some(scene), quick) => format!(
            "{}; the polygons of your scene `{}` ({}), in place of the corpus",
            if quick { "quick (`--quick`, short timing)" } else { "full" },
            scene.name,
            scene.from
        ),
    };
    let _ = writeln!(out, "# Polygon-fill lab\n");
    let timing = &results.timing;
    let launches = timing.launches;
    let _ = writeln!(
        out,
        "Run: {measured}. {}\n\nHost wall-clock times in release, filling into a 320x200 framebuffer, in {launches} \
         launch{} of the lab, each a fresh process, one after the other: in each, every contender, bound and lane of \
         a family timed in turn in each of {} repeats (each at least {} ms), in an order shuffled afresh for every \
         family (launch k, from 0, draws its orders from seed `{}` + k). A peer's time is set against `{EXACT}`'s \
         on the very polygons the peer drew, the two timed in the same repeats. A time is the median of every \
         launch's repeats, with the least and the most of them. A ratio of two times is taken within each launch \
         as the geometric mean of its repeats' ratios, with its {:.0}% interval (Student's t on their logarithms, \
         {} degrees of freedom), and across launches as the geometric mean of the launches' ratios, with its \
         {:.0}% interval (Student's t on their logarithms, {} degree{} of freedom{}): the tables give the ratio \
         across launches. Each of the {} timed frames of `raster`'s methods, every launch's, held its judged \
         fill's pixels. Accuracy against `raster::reference`. Charts: {} (.svg and .png beside this file).\n",
        machine(results),
        if launches == 1 { "" } else { "es" },
        timing.repeats,
        timing.min_repeat_ms,
        timing.order_seed,
        timing.confidence * 100.0,
        timing.repeats.saturating_sub(1),
        timing.confidence * 100.0,
        launches.saturating_sub(1),
        if launches == 2 { "" } else { "s" },
        if launches == 1 { ", so none: one launch has no interval across launches" } else { "" },
        count(timing.screens_checked as u64),
        crate::charts::Chart::drawn(results).map(|c| c.name()).collect::<Vec<_>>().join(", "),
    );
    corpus_table(&mut out, results);
    contender_table(&mut out, results);
    let _ = writeln!(out, "## What each contender does inside the clock\n\n{}", clock_table());
    exact_goals(&mut out, results);
    modelling::modelling_tables(&mut out, results);
    speed::spans_against_stores(&mut out, results);
    classic_failures(&mut out, results);
    speed::closest_peers(&mut out, results);
    speed::peers_on_everyday_families(&mut out, results);
    speed::launches_disagreement(&mut out, results);
    measure_table(&mut out, results, "Speed: ns per polygon, median (least–most of the repeats)", true, |r| {
        let t = &r.time;
        Some(format!("{} ({}–{})", duration(t.ns_per_polygon?), duration(t.ns_min?), duration(t.ns_max?)))
    });
    measure_table(
        &mut out,
        results,
        &format!("Speed: time over `{EXACT}`'s, with its {:.0}% interval", timing.confidence * 100.0),
        true,
        |r| r.time.vs_exact.as_ref().filter(|_| r.name != EXACT).map(ratio),
    );
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
    match results.scene {
        None => out.push_str("## Corpus\n\n"),
        Some(_) => {
            let _ = writeln!(out, "## Families\n\n{}\n", crate::corpus::user::FAMILIES_FORMED);
        }
    }
    let _ = writeln!(out, "| family | group | polygons | exact pixels | what |\n|---|---|---:|---:|---|");
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
        "- {}: {} wrong pixels, {} overdrawn, {} gaps, {} failures, {} declined polygons.\n",
        if results.scene.is_some() { "Your whole scene" } else { "Whole corpus" },
        count(sum(|r| r.wrong_pixels)),
        count(sum(|r| r.overdraw)),
        count(sum(|r| r.gaps)),
        count(sum(|r| r.failures)),
        count(sum(|r| r.refusals)),
    );
    let _ = writeln!(out, "| measure | measured | goal | met |\n|---|---:|---|---|");
    for goal in &results.goals {
        let met = if goal.met { "yes" } else { "no" };
        let _ = writeln!(out, "| {} | {} | {} | {met} |", goal.measure, shown(goal), goal.goal);
    }
    out.push('\n');
}

/// A goal's measure as the report shows it: its note, else its value.
fn shown(goal: &GoalRow) -> String {
    match (&goal.note, goal.value) {
        (Some(note), _) => note.clone(),
        (None, Some(v)) => format!("{v}"),
        (None, None) => "not measured".to_string(),
    }
}

/// One sentence per classic method: how far it is from exact under our
/// convention and its own, where it is worst, what it draws twice or
/// leaves out, what it declines and where it fails.
fn classic_failures(out: &mut String, results: &Results) {
    let _ = writeln!(
        out,
        "## Where each classic method fails\n\nTotals over {}; \"own convention\" samples where the method does (see \
         Contenders); declined polygons draw nothing and are not counted as wrong.\n",
        if results.scene.is_some() { "your whole scene" } else { "the whole corpus" }
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
        Group::Real => "real",
        Group::UserScene => "your scene",
    }
}
