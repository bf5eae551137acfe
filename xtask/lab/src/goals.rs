//! Where `exact` stands against its goals, in numbers from one run:
//! computed from the other results once every family is measured, written
//! to results.json with them and shown in report.md. The goals are the
//! ones docs/lab.md#goals states: no wrong pixel, no allocation per
//! polygon in `fill_auto`, faster than every peer. No ratio to a bound is
//! a goal: a bound replays spans worked out before the clock starts
//! (docs/lab-results.md#where-exacts-time-goes).

use std::fmt::Write;

use crate::results::{GoalRow, Kind, Results, EXACT};

/// Every goal of `exact`, measured in `results`.
pub fn measure(results: &Results) -> Vec<GoalRow> {
    let wrong: u64 =
        results.rows_of(EXACT).filter_map(|r| Some(r.wrong_pixels? + r.overdraw? + r.gaps.unwrap_or(0))).sum();
    vec![
        GoalRow {
            measure: "exact's wrong, overdrawn and missing pixels over every family".into(),
            value: Some(wrong as f64),
            note: None,
            goal: "0, the same pixels (exact_golden)".into(),
            met: wrong == 0,
        },
        allocations(results),
        against_peers(results),
    ]
}

/// The most heap allocations per polygon `fill_auto` makes on any family,
/// once its scratch has grown.
fn allocations(results: &Results) -> GoalRow {
    let rows = results.modelling.iter().filter(|r| r.lane == "fill_auto");
    let counted: Vec<f64> = rows.filter_map(|r| r.allocations_per_polygon).collect();
    let most = counted.iter().copied().reduce(f64::max);
    GoalRow {
        measure: "allocations per polygon, fill_auto, most on any family".into(),
        value: most,
        note: None,
        goal: "0".into(),
        met: most == Some(0.0) && counted.len() == results.families.len(),
    }
}

/// Whether `exact` is faster than every peer on every family the peer
/// takes (each peer's time over `exact`'s above 1, from the paired
/// repeats), where not, and the closest with its interval.
fn against_peers(results: &Results) -> GoalRow {
    let peers = || results.rows.iter().filter(|r| r.kind == Kind::Peer);
    let slower: Vec<String> = peers()
        .filter(|peer| peer.time.vs_exact.is_some_and(|r| r.ratio < 1.0))
        .map(|peer| format!("{} on {}", peer.name, peer.family))
        .collect();
    let unsure: Vec<String> = peers()
        .filter(|peer| peer.time.vs_exact.is_some_and(|r| r.ratio >= 1.0 && !r.surely_above(1.0)))
        .map(|peer| format!("{} on {}", peer.name, peer.family))
        .collect();
    let closest = peers()
        .filter_map(|peer| Some((peer, peer.time.vs_exact?)))
        .min_by(|a, b| a.1.ratio.total_cmp(&b.1.ratio))
        .map(|(peer, r)| {
            let interval = match (r.low, r.high) {
                (Some(low), Some(high)) => format!(" ({low:.2}–{high:.2})"),
                _ => String::new(),
            };
            format!("closest: {} on {}, {:.2}×{interval}", peer.name, peer.family, r.ratio)
        });
    let met = slower.is_empty();
    let mut note =
        if met { "faster on every family".to_string() } else { format!("slower than {}", slower.join(", ")) };
    if let Some(closest) = closest {
        let _ = write!(note, "; {closest}");
    }
    match unsure.as_slice() {
        [] => {}
        [one] => {
            let _ = write!(note, "; the interval reaches below 1 for {one}");
        }
        [first, ..] => {
            let _ = write!(
                note,
                "; the interval reaches below 1 for {} peers on families ({first} the first; report.md's \
                 closest peer on every family)",
                unsure.len()
            );
        }
    }
    GoalRow {
        measure: "exact against every peer (time over exact's, paired repeats)".into(),
        value: None,
        note: Some(note),
        goal: "faster on every family".into(),
        met,
    }
}
