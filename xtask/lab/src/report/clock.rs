//! The table of what each contender does inside the clock, made from the
//! contenders' own descriptions ([`crate::peers::Clock`]: each peer's
//! `PeerInfo` (`peers/peer.rs`), the methods' [`crate::contender::METHODS_CLOCK`],
//! each bound's [`Bound::clock`]), for report.md and docs/lab.md; a test
//! holds docs/lab.md's copy to it.

use std::fmt::Write;

use crate::contender::Contender;
use crate::peers::Clock;
use crate::timing::Bound;

/// The Markdown table: one row for the methods of `raster` together, one
/// for each peer, one for each bound.
pub fn clock_table() -> String {
    let contenders = Contender::all();
    let methods = contenders.iter().filter(|c| !c.is_peer()).count();
    let mut rows: Vec<(String, Clock)> = Vec::new();
    if let Some(method) = contenders.iter().find(|c| !c.is_peer()) {
        rows.push((format!("the {methods} methods of `raster`"), method.clock()));
    }
    rows.extend(contenders.iter().filter(|c| c.is_peer()).map(|c| (c.name().to_string(), c.clock())));
    rows.extend(Bound::ALL.map(|b| (b.name().to_string(), b.clock())));
    let mut table = String::from(
        "| contender | before the clock | path or vertex set-up, inside | fill, inside | surface | pixels | \
         anti-aliasing and threshold |\n|---|---|---|---|---|---|---|\n",
    );
    for (name, c) in rows {
        let _ = writeln!(
            table,
            "| {name} | {} | {} | {} | {} | {} | {} |",
            c.before, c.setup, c.fill, c.surface, c.pixel_format, c.anti_aliasing
        );
    }
    table
}

#[cfg(test)]
mod tests {
    use super::*;

    /// docs/lab.md shows the table as the code makes it: a peer whose
    /// description changes fails here until the page is made again.
    #[test]
    fn docs_lab_md_holds_the_clock_table_as_the_code_makes_it() {
        let page = concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/lab.md");
        let text = std::fs::read_to_string(page).expect("docs/lab.md is there");
        let table = clock_table();
        assert!(
            text.contains(&table),
            "docs/lab.md's table of what each contender does inside the clock differs from the code's; \
             put this one in its place:\n\n{table}"
        );
    }

    #[test]
    fn every_peer_and_bound_has_a_row() {
        let table = clock_table();
        for peer in crate::peers::ALL {
            assert!(table.contains(&format!("\n| {} |", peer.info().name)), "{}", peer.info().name);
        }
        for bound in Bound::ALL {
            assert!(table.contains(&format!("\n| {} |", bound.name())), "{}", bound.name());
        }
        let methods = format!("\n| the {} methods of `raster` |", raster::MethodId::ALL.len());
        assert!(table.contains(&methods), "{table}");
    }
}
