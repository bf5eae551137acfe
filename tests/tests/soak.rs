//! The kernel heap in the open and over time: `PING` reports it, and the
//! whole show played through `SHOW` with every method, cycle after cycle,
//! leaves it where it was (`harness::soak`; `cargo xtask soak` plays more
//! cycles).

use anyhow::{ensure, Result};
use harness::soak::{plan, play, problems, settle};
use harness::{Qemu, QemuOptions};

/// Full cycles this test plays: one full cycle takes about 20 s under TCG
/// here, and a leak or a fragmenting pattern shows from the second.
const CYCLES: usize = 3;

/// Bytes the kernel's show stage takes at boot and keeps: the 320x200
/// frame and a depth value (`i32`) per pixel.
const STAGE_BYTES: usize = 320 * 200 + 320 * 200 * 4;

#[test]
fn ping_reports_the_heap_and_a_dump_gives_back_what_it_took() -> Result<()> {
    let mut qemu = Qemu::boot(QemuOptions::default())?;
    let before = qemu.console.pong()?.heap;
    ensure!(before.used >= STAGE_BYTES, "PING says the heap holds {} bytes, less than the stage", before.used);
    ensure!(before.free_largest > 0, "PING says no block is free: {before}");
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
    Ok(())
}
