//! Where `exact` stands against its goals, in numbers from one run of
//! the lab (every launch of it):
//! computed from the other results once every family is measured, written
//! to results.json with them and shown in report.md. The goals are the
//! ones docs/lab.md#goals states: no wrong pixel, no allocation per
//! polygon in `fill_auto`, faster than every peer. No ratio to a bound is
//! a goal: a bound replays spans worked out before the clock starts
//! (docs/lab-results.md#where-exacts-time-goes).

use std::fmt::Write;

use crate::results::{GoalRow, Kind, Results, Row, EXACT};

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

/// The thresholds the report judges `exact`'s lead over the peers at,
/// besides 1 (the goal).
pub const LEADS: [f64; 2] = [2.0, 2.5];

/// Of `rows` (peers, each with its time over `exact`'s), the one whose
/// ratio's interval across launches reaches lowest, with that lower end: a
/// lead is judged there, not at the lowest ratio, for a peer a little
/// slower may have moved more from launch to launch. A ratio with no
/// interval (one launch) has a lower end of 0: it is sure of nothing.
/// `None` where no row has a ratio.
pub fn lowest_lower_end<'a>(rows: impl Iterator<Item = &'a Row>) -> Option<(&'a Row, f64)> {
    rows.filter_map(|row| Some((row, row.time.vs_exact?.low.unwrap_or(0.0)))).min_by(|a, b| a.1.total_cmp(&b.1))
}

/// Whether `exact` is faster than every peer on every family the peer
/// takes, judged at the lowest lower end over every peer and family of
/// the interval across launches of its time over `exact`'s (on the
/// polygons the peer drew): above 1. The note names that peer and family,
/// any peer slower on its ratio alone, and on how many families the
/// lowest lower end is above each of [`LEADS`].
fn against_peers(results: &Results) -> GoalRow {
    let peers = || results.rows.iter().filter(|r| r.kind == Kind::Peer);
    let faster: Vec<String> = peers()
        .filter(|peer| peer.time.vs_exact.is_some_and(|r| r.ratio < 1.0))
        .map(|peer| format!("{} on {}", peer.name, peer.family))
        .collect();
    let lowest = lowest_lower_end(peers());
    let met = lowest.is_some_and(|(_, low)| low > 1.0);
    let mut note = match lowest {
        None => "no peer timed".to_string(),
        Some((peer, low)) => {
            let r = peer.time.vs_exact.expect("a lowest lower end has a ratio");
            let interval = match (r.low, r.high) {
                (Some(low), Some(high)) => format!("{:.2}× ({low:.2}–{high:.2})", r.ratio),
                _ => format!("{:.2}×, no interval across launches", r.ratio),
            };
            format!(
                "lowest lower end over every peer and family {low:.2}: {} on {}, {interval}; {}",
                peer.name,
                peer.family,
                if met { "faster on every family" } else { "not surely faster on every family" }
            )
        }
    };
    if !faster.is_empty() {
        let _ = write!(note, "; faster than `{EXACT}` on its ratio: {}", faster.join(", "));
    }
    let families: Vec<f64> = results
        .families
        .iter()
        .filter_map(|f| lowest_lower_end(peers().filter(|r| r.family == f.name)).map(|(_, low)| low))
        .collect();
    for lead in LEADS {
        let above = families.iter().filter(|&&low| low > lead).count();
        let _ = write!(note, "; above {lead} on {above} of {} families", families.len());
    }
    GoalRow {
        measure: "exact against every peer (time over exact's on the peer's polygons, lowest lower end of the \
                  intervals across launches)"
            .into(),
        value: lowest.map(|(_, low)| low),
        note: Some(note),
        goal: "above 1: faster on every family".into(),
        met,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::corpus::Group;
    use crate::stats::Ratio;
    use crate::timing::Timed;

    fn peer(name: &'static str, family: &'static str, ratio: f64, low: Option<f64>, high: Option<f64>) -> Row {
        let vs_exact = Some(Ratio { ratio, low, high, count: 3 });
        let mut row = crate::results::tests::row(name, family);
        row.kind = Kind::Peer;
        row.group = Group::Random;
        row.time = Timed { vs_exact, ..Timed::default() };
        row
    }

    /// The lead is judged at the interval reaching lowest, not at the
    /// lowest ratio: `steady`, the closer on its ratio, is surely slower
    /// than `exact`; `noisy`, further on its ratio, may not be.
    #[test]
    fn the_lead_is_judged_at_the_lowest_lower_end() {
        let rows = [
            peer("steady", "f", 1.5, Some(1.45), Some(1.55)),
            peer("noisy", "f", 2.0, Some(0.8), Some(5.0)),
            peer("far", "g", 4.0, Some(3.0), Some(5.3)),
        ];
        let (row, low) = lowest_lower_end(rows.iter()).unwrap();
        assert_eq!((row.name, low), ("noisy", 0.8));
        let mut results = crate::results::tests::results(&["f", "g"]);
        results.rows.extend(rows);
        let goal = against_peers(&results);
        assert!(!goal.met, "{goal:?}");
        assert_eq!(goal.value, Some(0.8));
        let note = goal.note.unwrap();
        assert!(
            note.contains("lowest lower end over every peer and family 0.80: noisy on f, 2.00× (0.80–5.00)"),
            "{note}"
        );
        assert!(note.contains("above 2 on 1 of 2 families; above 2.5 on 1 of 2 families"), "{note}");
    }

    /// With one launch there is no interval across launches: nothing is
    /// sure, and the goal is not met.
    #[test]
    fn one_launch_meets_no_lead() {
        let mut results = crate::results::tests::results(&["f"]);
        results.rows.push(peer("single", "f", 3.0, None, None));
        let goal = against_peers(&results);
        assert!(!goal.met && goal.value == Some(0.0), "{goal:?}");
        assert!(goal.note.unwrap().contains("3.00×, no interval across launches"));
    }
}
