//! `BENCH` answers for every demo scene with one cycle count per method,
//! in the order of `raster::MethodId::ALL`, with the polygons each declined
//! (the host's draw of the same scene declines as many), and under
//! instruction counting its figures repeat exactly from run to run. Only
//! the shape and the repetition are checked: speed is never asserted.

use anyhow::{bail, ensure, Context, Result};
use harness::{BenchRow, Clock, Qemu, QemuOptions, Reply};
use protocol::Command;
use raster::{Framebuffer, MethodId, SCREEN};
use scenes::builtin;

#[test]
fn bench_answers_one_positive_cycle_count_per_method_for_every_demo_scene() -> Result<()> {
    let mut qemu = Qemu::boot(QemuOptions::default())?;
    for page in builtin::ALL {
        let scene = page.name;
        let rows = qemu.console.bench(scene, 1)?;
        let methods: Vec<MethodId> = rows.iter().map(|row| row.method).collect();
        ensure!(methods == MethodId::ALL, "BENCH {scene} listed methods {methods:?}, expected {:?}", MethodId::ALL);
        for row in &rows {
            ensure!(row.cycles > 0, "BENCH {scene}: {} took {} cycles", row.method, row.cycles);
            let host = page.scene().draw(row.method.method(), &mut Framebuffer::new(SCREEN));
            ensure!(
                (row.refused, row.refusal) == (host.refused, host.first_refusal),
                "BENCH {scene}: {} declined {} ({:?}), the host's draw {} ({:?})",
                row.method,
                row.refused,
                row.refusal,
                host.refused,
                host.first_refusal
            );
        }
    }
    match qemu.console.request(&Command::Bench { scene: "no-such-scene", repeats: 1 })? {
        Reply::Err(text) if text.contains("no-such-scene") => {}
        other => bail!("BENCH of an unknown scene answered {other:?}, expected an ERR naming it"),
    }
    let losses = qemu.console.ping()?;
    ensure!(losses.none(), "PING after BENCH says the serial line lost bytes: {losses}");
    Ok(())
}

/// Under instruction counting (`Clock::InstructionCount`, as `cargo xtask
/// kbench` and `record` run) the figures count emulated instructions, so
/// two QEMUs booted side by side, each slowing the other down, time
/// `abrash38-3` to the same number for every method. Without it they
/// follow the host's clock and differ.
#[test]
fn two_runs_under_instruction_counting_give_identical_bench_figures() -> Result<()> {
    let options = QemuOptions { clock: Clock::InstructionCount, ..QemuOptions::default() };
    let bench = || -> Result<Vec<BenchRow>> { Qemu::boot(options)?.console.bench("abrash38-3", 3) };
    let (first, second) = std::thread::scope(|scope| {
        let (first, second) = (scope.spawn(bench), scope.spawn(bench));
        (first.join(), second.join())
    });
    let first = first.ok().context("the first run panicked")??;
    let second = second.ok().context("the second run panicked")??;
    ensure!(first == second, "BENCH abrash38-3 3 gave {first:?} in one run and {second:?} in the other");
    Ok(())
}
