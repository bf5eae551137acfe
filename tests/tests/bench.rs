//! `BENCH` answers for every demo scene with one cycle count per method,
//! in the order of `raster::MethodId::ALL`, with the polygons each declined
//! (the host's draw of the same scene declines as many), and under
//! instruction counting its figures repeat exactly from run to run, where
//! without it they do not. Only the shape and the repetition are checked:
//! speed is never asserted.

use std::collections::BTreeSet;

use anyhow::{bail, ensure, Context, Result};
use harness::{Qemu, QemuOptions, Reply, TimeBase};
use protocol::{BenchRow, Command, ErrorReply};
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
            let host = page.scene().draw(row.method, &mut Framebuffer::new(SCREEN));
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
        Reply::Err(text) if ErrorReply::parse(&text)? == ErrorReply::UnknownScene("no-such-scene") => {}
        other => bail!("BENCH of an unknown scene answered {other:?}, expected an ERR naming it"),
    }
    let losses = qemu.console.ping()?;
    ensure!(losses.none(), "PING after BENCH says the serial line lost bytes: {losses}");
    Ok(())
}

/// The scene the repetition is checked on, and the draws per method.
const REPEATED: (&str, u8) = ("abrash38-3", 3);

/// The control's `BENCH`: page 1 (two polygons), one draw per method, so
/// the control adds little to the test's time.
const CONTROL: (&str, u8) = ("abrash38-1", 1);

/// Under instruction counting (`TimeBase::InstructionCount`, as `cargo xtask
/// kbench` and `record` run) the figures count emulated instructions, so
/// two QEMUs booted side by side, each slowing the other down, time
/// `abrash38-3` to the same number for every method, and the methods to
/// different numbers. The control, booted beside them without counting:
/// its figures follow the host's clock, so the same `BENCH` asked twice
/// gives different figures.
/// A kernel whose figures never change, or a harness that dropped the
/// counting option, fails here.
#[test]
fn two_runs_under_instruction_counting_give_identical_bench_figures() -> Result<()> {
    let (scene, repeats) = REPEATED;
    let counted = QemuOptions { clock: TimeBase::InstructionCount, ..QemuOptions::default() };
    let bench = |options: QemuOptions, (scene, repeats): (&str, u8), times: usize| -> Result<Vec<Vec<BenchRow>>> {
        let mut qemu = Qemu::boot(options)?;
        (0..times).map(|_| qemu.console.bench(scene, repeats)).collect()
    };
    let (first, second, control) = std::thread::scope(|scope| {
        let first = scope.spawn(|| bench(counted, REPEATED, 1));
        let second = scope.spawn(|| bench(counted, REPEATED, 1));
        let control = scope.spawn(|| bench(QemuOptions::default(), CONTROL, 2));
        (first.join(), second.join(), control.join())
    });
    let first = first.ok().context("the first run panicked")??.concat();
    let second = second.ok().context("the second run panicked")??.concat();
    let control = control.ok().context("the control run panicked")??;
    let command = format!("BENCH {scene} {repeats}");
    ensure!(first == second, "{command} gave {first:?} in one run and {second:?} in the other");
    let counts: BTreeSet<u64> = first.iter().map(|row| row.cycles).collect();
    ensure!(counts.len() > 1, "{command} under instruction counting gave every method the same count: {first:?}");
    ensure!(
        control[0] != control[1],
        "without instruction counting, BENCH {} {} gave {:?} twice: figures that do not follow the clock prove \
         nothing by repeating",
        CONTROL.0,
        CONTROL.1,
        control[0]
    );
    Ok(())
}
