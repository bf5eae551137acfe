//! The kernel heap in the open and over time: `PING` reports it, and the
//! whole show played through `SHOW` with every method, cycle after cycle,
//! leaves it where it was (`harness::soak`; `cargo xtask soak` plays more
//! cycles). Both tests also see `PING`'s figures move when the stage
//! keeps a larger page, so figures stuck at any value fail.

use anyhow::{ensure, Context, Result};
use harness::soak::{plan, play, problems, settle};
use harness::{Console, Qemu, QemuOptions};
use protocol::HeapState;
use scenes::builtin;
use scenes::show::ENTRIES_IN_ORDER;

/// Full cycles this test plays (what a cycle takes under TCG is in
/// docs/testing.md#the-soak): a leak or a fragmenting pattern shows from
/// the second.
const CYCLES: usize = 3;

/// Bytes the kernel's show stage takes at boot and keeps: the 320x200
/// frame and a depth value (`i32`) per pixel.
const STAGE_BYTES: usize = 320 * 200 + 320 * 200 * 4;

/// The control for `PING`'s heap figures: the stage keeps the still page
/// it built last (`kept`: after boot, the demo's first page), so showing
/// the show's still of the most polygons in its place must leave more
/// bytes in use and a smaller largest free block. Figures that never move
/// fail here. Returns the heap with that page kept.
fn a_kept_page_moves_the_heap(console: &mut Console, kept: &str) -> Result<HeapState> {
    let polygons = |name| builtin::named(name).map_or(0, |page| page.scene().ops.len());
    let stills = || ENTRIES_IN_ORDER.iter().filter(|entry| !entry.is_animated());
    let largest = stills().max_by_key(|entry| polygons(entry.name)).context("the show has no still")?;
    ensure!(polygons(largest.name) > polygons(kept), "no still page is larger than {kept}");
    let before = console.pong()?.heap;
    console.show(largest.name, 0, None)?;
    let after = console.pong()?.heap;
    ensure!(
        after.used > before.used && after.free_largest < before.free_largest,
        "with {} ({} polygons) kept in place of {} ({}), PING says {after}, and {before} before: its figures do not move",
        largest.name,
        polygons(largest.name),
        kept,
        polygons(kept)
    );
    Ok(after)
}

#[test]
fn ping_reports_the_heap_and_a_dump_gives_back_what_it_took() -> Result<()> {
    let mut qemu = Qemu::boot(QemuOptions::default())?;
    let at_boot = qemu.console.pong()?.heap;
    ensure!(at_boot.used >= STAGE_BYTES, "PING says the heap holds {} bytes, less than the stage", at_boot.used);
    ensure!(at_boot.free_largest > 0, "PING says no block is free: {at_boot}");
    let first_still = ENTRIES_IN_ORDER.iter().find(|entry| !entry.is_animated()).context("the show has no still")?;
    let before = a_kept_page_moves_the_heap(&mut qemu.console, first_still.name)?;
    // A dump is a 64,768-byte buffer, freed once sent.
    qemu.console.dump()?;
    let after = qemu.console.pong()?.heap;
    ensure!(after == before, "the heap was {before} before a DUMP and {after} after it");
    Ok(())
}

#[test]
fn the_whole_show_with_every_method_leaves_the_heap_where_it_was_cycle_after_cycle() -> Result<()> {
    let plan = plan(1);
    let mut qemu = Qemu::boot(QemuOptions::default())?;
    let settled = settle(&mut qemu.console, &plan)?;
    let mut cycles = Vec::new();
    let mut failures = Vec::new();
    for number in 1..=CYCLES {
        let cycle = play(&mut qemu.console, &plan, || {})?;
        eprintln!("cycle {number}: {} frames in {:.1} s; {}", plan.len(), cycle.elapsed.as_secs_f64(), cycle.heap);
        let first = cycles.first().unwrap_or(&cycle);
        failures.extend(problems(&plan, settled, first, &cycle, number, 20));
        cycles.push(cycle);
    }
    ensure!(failures.is_empty(), "settled at {settled}; {} problems:\n{}", failures.len(), failures.join("\n"));
    // The control comes last, so that the page it keeps never shapes the
    // heap the cycles are held to.
    let last_still = plan.iter().rev().find(|shot| !shot.entry.is_animated()).context("the plan has no still")?;
    a_kept_page_moves_the_heap(&mut qemu.console, last_still.entry.name)?;
    Ok(())
}
