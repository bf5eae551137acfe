//! report.md's speed tables beyond the one-measure tables: where
//! `exact`'s time goes (finding spans against storing them), the closest
//! peer on every family, the peers on the everyday families, and how far
//! the launches of the timing disagree.

use std::fmt::Write;

use super::format::{count, duration, ratio};
use super::summary::closest_peer;
use crate::goals::{lowest_lower_end, LEADS};
use crate::results::{Kind, Results, Row, EXACT};
use crate::stats::{disagreement, median};
use crate::timing::{LaunchFigures, Timed};

/// Per family: `exact`, finding its spans alone (`fill_auto` into a sink
/// that stores nothing) and the store bound, with the ratios that say
/// where `exact`'s time goes, each across launches of the paired repeats
/// within each.
pub(super) fn spans_against_stores(out: &mut String, results: &Results) {
    let _ = writeln!(
        out,
        "## Finding the spans against storing them\n\nPer polygon, every lane timed in turn: `{EXACT}`, \
         `spans unstored` (`fill_auto` into a sink that stores nothing: finding the spans alone), the store bound \
         (the reference's spans stored, worked out before the clock starts); then the ratios, each with its \
         interval: finding the spans over storing them, `{EXACT}` over the store bound, and `fill_auto`'s own lane \
         over `{EXACT}` in the family's lanes (the same fill timed by two loops: near 1).\n\n\
         | family | {EXACT} | spans unstored | store bound | spans unstored / store | {EXACT} / store | \
         fill_auto / {EXACT} |\n|---|---:|---:|---:|---:|---:|---:|"
    );
    for f in &results.families {
        let lane = |name: &str| results.modelling.iter().find(|r| r.family == f.name && r.lane == name);
        let (exact, store) = (results.row(EXACT, f.name), results.row("store bound", f.name));
        let (walk, auto) = (lane("spans unstored"), lane("fill_auto"));
        let time = |t: Option<&Timed>| t.and_then(|t| t.ns_per_polygon).map_or("–".to_string(), duration);
        let interval = |t: Option<&Timed>, pick: fn(&Timed) -> Option<&crate::stats::Ratio>| {
            t.and_then(pick).map_or("–".to_string(), ratio)
        };
        let _ = writeln!(
            out,
            "| {} | {} | {} | {} | {} | {} | {} |",
            f.name,
            time(exact.map(|r| &r.time)),
            time(walk.map(|r| &r.time)),
            time(store.map(|r| &r.time)),
            interval(walk.map(|r| &r.time), |t| t.vs_store.as_ref()),
            interval(exact.map(|r| &r.time), |t| t.vs_store.as_ref()),
            interval(auto.map(|r| &r.time), |t| t.vs_exact.as_ref()),
        );
    }
    out.push('\n');
}

/// Per family, the peer closest to `exact` with its time over `exact`'s
/// across launches with its interval, and within each launch with its
/// own; then the lowest lower end over the family's peers of the interval
/// across launches, which peer it is, and whether it is above 1 (`exact`
/// surely faster) and above each of [`LEADS`].
pub(super) fn closest_peers(out: &mut String, results: &Results) {
    let confidence = results.timing.confidence * 100.0;
    let leads: Vec<String> = LEADS.iter().map(|lead| format!("above {lead}")).collect();
    let _ = writeln!(
        out,
        "## The closest peer on every family\n\nThe peer whose time is the least over `{EXACT}`'s on each family \
         (both timed on the polygons the peer drew), that ratio across the {} launches with its {confidence:.0}% \
         interval, and within each launch with its own; then the lowest lower end of the intervals across launches \
         over all the family's peers, whose it is, and whether it is above 1 (`{EXACT}` surely faster) and above \
         each lead.\n\n| family | closest peer | time / {EXACT}'s, across launches | within each launch | lowest lower end \
         | above 1 | {} |\n|---|---|---:|---|---:|---|{}",
        results.timing.launches,
        leads.join(" | "),
        "---|".repeat(LEADS.len())
    );
    for f in &results.families {
        let Some(peer) = closest_peer(results, f.name) else { continue };
        let Some(r) = peer.time.vs_exact else { continue };
        let within: Vec<String> =
            peer.time.launches.iter().map(|l| l.vs_exact.as_ref().map_or("–".to_string(), ratio)).collect();
        let peers = results.rows.iter().filter(|row| row.kind == Kind::Peer && row.family == f.name);
        let Some((lowest, low)) = lowest_lower_end(peers) else { continue };
        let yes = |x: f64| if low > x { "yes" } else { "no" };
        let above: Vec<&str> = LEADS.iter().map(|&lead| yes(lead)).collect();
        let _ = writeln!(
            out,
            "| {} | {} | {} | {} | {low:.2} ({}) | {} | {} |",
            f.name,
            peer.name,
            ratio(&r),
            within.join("; "),
            lowest.name,
            yes(1.0),
            above.join(" | ")
        );
    }
    out.push('\n');
}

/// With two launches or more: how far they disagree, lane by lane, in time
/// and in time over `exact`'s; `exact`'s time and the closest peer's ratio
/// launch by launch on every family.
pub(super) fn launches_disagreement(out: &mut String, results: &Results) {
    let launches = results.timing.launches;
    if launches < 2 {
        return;
    }
    let mut times = Vec::new();
    let mut ratios = Vec::new();
    for r in results.rows.iter().filter(|r| r.name != EXACT) {
        let figure =
            |pick: fn(&LaunchFigures) -> Option<f64>| -> Vec<f64> { r.time.launches.iter().filter_map(pick).collect() };
        if let Some(d) = disagreement(&figure(|f| f.ns_per_polygon)) {
            times.push((d, r));
        }
        if let Some(d) = disagreement(&figure(|f| Some(f.vs_exact?.ratio))) {
            ratios.push((d, r));
        }
    }
    let _ = writeln!(
        out,
        "## How far the {launches} launches disagree\n\nThe whole timing was launched {launches} times, each a fresh \
         process, one after the other. For every contender and bound on every family, the launches' medians \
         disagree (the largest over the smallest, less one) by {}; their times over `{EXACT}`'s, each from its \
         launch's paired repeats, by {}.\n",
        summary(&mut times),
        summary(&mut ratios)
    );
    let columns: Vec<String> = (1..=launches).map(|r| format!("launch {r}")).collect();
    let _ = writeln!(
        out,
        "| family | `{EXACT}`, {} | disagree | closest peer | its time / `{EXACT}`'s, {} | disagree |\n|---|---:|---:|---|---:|---:|",
        columns.join(", "),
        columns.join(", "),
    );
    for f in &results.families {
        let Some(exact) = results.row(EXACT, f.name) else { continue };
        let medians: Vec<f64> = exact.time.launches.iter().filter_map(|r| r.ns_per_polygon).collect();
        let peer = closest_peer(results, f.name);
        let peer_ratios: Vec<f64> =
            peer.map(|p| p.time.launches.iter().filter_map(|r| Some(r.vs_exact?.ratio)).collect()).unwrap_or_default();
        let percent = |d: Option<f64>| d.map_or("–".to_string(), |d| format!("{:.1}%", d * 100.0));
        let _ = writeln!(
            out,
            "| {} | {} | {} | {} | {} | {} |",
            f.name,
            medians.iter().map(|&ns| duration(ns)).collect::<Vec<_>>().join(", "),
            percent(disagreement(&medians)),
            peer.map_or("–", |p| p.name),
            peer_ratios.iter().map(|r| format!("{r:.2}×")).collect::<Vec<_>>().join(", "),
            percent(disagreement(&peer_ratios)),
        );
    }
    out.push('\n');
}

/// "a median of X% and at most Y% (NAME on FAMILY)" over `disagreements`.
fn summary(disagreements: &mut [(f64, &Row)]) -> String {
    let values: Vec<f64> = disagreements.iter().map(|(d, _)| *d).collect();
    let Some(middle) = median(&values) else { return "nothing (no figure in two launches)".to_string() };
    disagreements.sort_by(|a, b| a.0.total_cmp(&b.0));
    let (most, row) = disagreements[disagreements.len() - 1];
    format!("a median of {:.1}% and at most {:.1}% ({} on {})", middle * 100.0, most * 100.0, row.name, row.family)
}

/// The peers on the everyday families: each one's time per polygon and
/// wrong pixels under its own convention, family by family; then, over
/// the families each draws whole (declining and failing on none), its
/// time against `exact`'s and its wrong pixels, with the fastest and the
/// most exact of them.
pub(super) fn peers_on_everyday_families(out: &mut String, results: &Results) {
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
                    r.time.ns_per_polygon.map_or("–".to_string(), duration),
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
    /// Geometric mean of its time per polygon over `exact`'s (each
    /// family's across launches).
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
            .filter_map(|r| Some((r, r.time.vs_exact?.ratio)))
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
