//! Where `exact` stands against its goals, in numbers from one run:
//! computed from the other results once every family is measured, written
//! to results.json with them and shown in report.md.

use crate::results::{GoalRow, Kind, Results, EXACT};

/// A bound a measure must keep.
#[derive(Clone, Copy)]
enum Bound {
    AtLeast(f64),
    AtMost(f64),
}

impl Bound {
    fn holds(self, value: f64) -> bool {
        match self {
            Bound::AtLeast(goal) => value >= goal,
            Bound::AtMost(goal) => value <= goal,
        }
    }

    fn text(self) -> String {
        match self {
            Bound::AtLeast(goal) => format!("≥ {goal}×"),
            Bound::AtMost(goal) => format!("≤ {goal}×"),
        }
    }
}

/// The families whose `exact` time is held to the store bound's.
pub const EVERYDAY_GENERAL: [&str; 4] = ["concave", "stars", "holes", "nonconvex_shapes"];

/// Every goal of `exact`, measured in `results`.
pub fn measure(results: &Results) -> Vec<GoalRow> {
    let ns = |name: &str, family: &str| results.row(name, family)?.ns_per_polygon;
    let ratio = |a: Option<f64>, b: Option<f64>| Some(a? / b?);
    let over_store = |family: &str| results.row(EXACT, family)?.time_vs_store;
    let ratio_row = |measure: String, value: Option<f64>, bound: Bound| GoalRow {
        measure,
        value,
        note: None,
        goal: bound.text(),
        met: value.is_some_and(|v| bound.holds(v)),
    };
    let mut goals = vec![
        ratio_row(
            "small triangles: exact's time / the store bound's".into(),
            over_store("small_triangles"),
            Bound::AtMost(2.5),
        ),
        ratio_row(
            "small triangles: tiny-skia's time / exact's".into(),
            ratio(ns("tiny-skia", "small_triangles"), ns(EXACT, "small_triangles")),
            Bound::AtLeast(15.0),
        ),
        ratio_row(
            "large convex: the memset bound's time / exact's".into(),
            results.row(EXACT, "large_convex").and_then(|r| Some(1.0 / r.time_vs_memset?)),
            Bound::AtLeast(0.45),
        ),
    ];
    for family in EVERYDAY_GENERAL {
        goals.push(ratio_row(
            format!("{family}: exact's time / the store bound's"),
            over_store(family),
            Bound::AtMost(2.5),
        ));
    }
    goals.push(allocations(results));
    goals.push(against_peers(results));
    let wrong: u64 =
        results.rows_of(EXACT).filter_map(|r| Some(r.wrong_pixels? + r.overdraw? + r.gaps.unwrap_or(0))).sum();
    goals.push(GoalRow {
        measure: "exact's wrong, overdrawn and missing pixels over the whole corpus".into(),
        value: Some(wrong as f64),
        note: None,
        goal: "0, the same pixels (exact_golden)".into(),
        met: wrong == 0,
    });
    goals
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
/// takes, and where not.
fn against_peers(results: &Results) -> GoalRow {
    let slower: Vec<String> = results
        .rows
        .iter()
        .filter(|r| r.kind == Kind::Peer)
        .filter_map(|peer| {
            let mine = results.row(EXACT, peer.family)?.ns_per_polygon?;
            (peer.ns_per_polygon? < mine).then(|| format!("{} on {}", peer.name, peer.family))
        })
        .collect();
    let met = slower.is_empty();
    GoalRow {
        measure: "exact against every peer".into(),
        value: None,
        note: Some(if met { "faster on every family".into() } else { format!("slower than {}", slower.join(", ")) }),
        goal: "faster on every family".into(),
        met,
    }
}
