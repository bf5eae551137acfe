//! What a run found that the docs show, in a file small enough to commit:
//! summary.json beside results.json (docs/lab-results.json is one run's).
//! The processor and the timing, and family by family `exact`'s time and
//! the closest peer's time over it. report.md's table of the closest peers
//! is [`Summary::closest_peers`], and so is docs/lab-results.md's, which a
//! test holds to docs/lab-results.json.

use std::fmt::Write;

use serde::{Deserialize, Serialize};

use super::format::{duration, ratio};
use crate::results::{Kind, Results, Row, EXACT};
use crate::stats::Ratio;

/// A run's figures for the docs.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Summary {
    /// The processor, as results.json's `timing` names it.
    pub cpu: Option<String>,
    /// Launches (fresh processes) of the whole timing, and repeats in
    /// each.
    pub launches: usize,
    pub repeats: usize,
    /// The 1-minute load average when the timing started and ended.
    pub load_average: (Option<f64>, Option<f64>),
    /// Family by family, in the corpus's order.
    pub families: Vec<FamilySummary>,
}

/// One family: `exact`'s time per polygon, and the peer whose time over
/// `exact`'s is the least (on the polygons it drew), with that ratio.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FamilySummary {
    pub family: String,
    pub exact_ns: Option<f64>,
    pub closest_peer: Option<String>,
    pub vs_exact: Option<Ratio>,
}

impl Summary {
    pub fn of(results: &Results) -> Self {
        let timing = &results.timing;
        let families = results
            .families
            .iter()
            .map(|family| {
                let peer = closest_peer(results, family.name);
                FamilySummary {
                    family: family.name.to_string(),
                    exact_ns: results.row(EXACT, family.name).and_then(|row| row.time.ns_per_polygon),
                    closest_peer: peer.map(|peer| peer.name.to_string()),
                    vs_exact: peer.and_then(|peer| peer.time.vs_exact),
                }
            })
            .collect();
        Self {
            cpu: timing.cpu.clone(),
            launches: timing.launches,
            repeats: timing.repeats,
            load_average: timing.load_average,
            families,
        }
    }

    /// The closest peer on every family that has one, as a Markdown table:
    /// `exact`'s time, the peer, its time over `exact`'s with the interval,
    /// and whether the interval's lower end is above 1 and above 2.
    pub fn closest_peers(&self) -> String {
        let mut table = format!(
            "| family | `{EXACT}` | closest peer | time / `{EXACT}`'s | above 1 | above 2 |\n|---|---:|---|---:|---|---|\n"
        );
        for family in &self.families {
            let (Some(peer), Some(r)) = (&family.closest_peer, family.vs_exact) else { continue };
            let yes = |x: f64| if r.surely_above(x) { "yes" } else { "no" };
            let time = family.exact_ns.map_or("–".to_string(), duration);
            let _ = writeln!(
                table,
                "| {} | {time} | {peer} | {} | {} | {} |",
                family.family,
                ratio(&r),
                yes(1.0),
                yes(2.0)
            );
        }
        table
    }
}

/// The peer closest to `exact`'s time on `family`: the least time over
/// `exact`'s of the peers timed there.
pub(super) fn closest_peer<'a>(results: &'a Results, family: &str) -> Option<&'a Row> {
    results.rows.iter().filter(|r| r.kind == Kind::Peer && r.family == family && r.time.vs_exact.is_some()).min_by(
        |a, b| {
            let ratio = |r: &Row| r.time.vs_exact.map_or(f64::INFINITY, |v| v.ratio);
            ratio(a).total_cmp(&ratio(b))
        },
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn summary() -> Summary {
        let r = |ratio, low| Some(Ratio { ratio, low: Some(low), high: Some(ratio + 0.1), count: 7 });
        let family = |name: &str, peer: Option<&str>, vs_exact| FamilySummary {
            family: name.to_string(),
            exact_ns: Some(1_500.0),
            closest_peer: peer.map(str::to_string),
            vs_exact,
        };
        Summary {
            cpu: Some("a CPU".to_string()),
            launches: 1,
            repeats: 7,
            load_average: (Some(1.5), Some(1.0)),
            families: vec![
                family("stars", Some("tiny-skia"), r(2.15, 2.11)),
                family("flags", Some("allegro"), r(1.24, 1.21)),
                family("offscreen", None, None),
            ],
        }
    }

    #[test]
    fn the_closest_peers_table_says_where_exact_is_surely_faster_and_twice_as_fast() {
        assert_eq!(
            summary().closest_peers(),
            "| family | `exact` | closest peer | time / `exact`'s | above 1 | above 2 |\n|---|---:|---|---:|---|---|\n\
             | stars | 1.50 µs | tiny-skia | 2.15× (2.11–2.25) | yes | yes |\n\
             | flags | 1.50 µs | allegro | 1.24× (1.21–1.34) | yes | no |\n"
        );
    }

    #[test]
    fn a_summary_reads_back_from_its_json() {
        let text = serde_json::to_string(&summary()).unwrap();
        assert_eq!(serde_json::from_str::<Summary>(&text).unwrap(), summary());
    }

    /// docs/lab-results.md shows the closest peers of the run whose
    /// summary is docs/lab-results.json: the table that file makes, as the
    /// lab writes it in report.md.
    #[test]
    fn docs_lab_results_md_holds_the_closest_peers_lab_results_json_makes() {
        let docs = concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs");
        let json = std::fs::read_to_string(format!("{docs}/lab-results.json")).expect("docs/lab-results.json is there");
        let summary: Summary = serde_json::from_str(&json).expect("docs/lab-results.json is a summary");
        let page = std::fs::read_to_string(format!("{docs}/lab-results.md")).expect("docs/lab-results.md is there");
        let made = summary.closest_peers();
        assert!(
            page.contains(&made),
            "docs/lab-results.md's closest peers differ from docs/lab-results.json's:\n{made}"
        );
    }
}
