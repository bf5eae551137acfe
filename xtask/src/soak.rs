//! `cargo xtask soak [--cycles N] [--step K]`: boots the kernel and plays
//! the whole show through `SHOW` with every method, N times over
//! (`harness::soak`), printing the heap (`PING`) and the time after each
//! cycle; fails if a cycle leaves the heap holding more or with a smaller
//! largest free block than the first did, or if any frame's figures
//! (allocations, polygons, refusals, strays) differ from the first
//! cycle's.

use anyhow::{ensure, Result};
use harness::soak::{plan, play, problems, settle, Cycle};
use harness::{Qemu, QemuOptions};
use indicatif::{ProgressBar, ProgressStyle};

use crate::opt::SoakOpt;

/// Most differing frames named per cycle.
const NAMED: usize = 20;

pub fn soak(opt: &SoakOpt) -> Result<()> {
    let plan = plan(opt.step);
    let mut qemu = Qemu::boot(QemuOptions::default())?;
    let boot = qemu.console.pong()?.heap;
    println!("after boot: {boot}");
    let settled = settle(&mut qemu.console, &plan)?;
    println!("settled (the plan's last still and last frame shown): {settled}");
    let bar = ProgressBar::new(plan.len() as u64 * u64::from(opt.cycles));
    bar.set_style(
        ProgressStyle::with_template("soak [{bar:30}] {pos}/{len} frames, {elapsed_precise} (eta {eta})  {msg}")
            .expect("the template is valid")
            .progress_chars("=> "),
    );
    let mut cycles: Vec<Cycle> = Vec::new();
    let mut failures = Vec::new();
    for number in 1..=opt.cycles as usize {
        bar.set_message(format!("cycle {number}"));
        let cycle = play(&mut qemu.console, &plan, || bar.inc(1))?;
        bar.suspend(|| {
            println!(
                "cycle {number}: {} frames in {:.1} s, {} allocations; {}",
                plan.len(),
                cycle.elapsed.as_secs_f64(),
                cycle.allocations(),
                cycle.heap
            )
        });
        if number == 1 {
            if let Some((shot, figures)) = plan.iter().zip(&cycle.figures).max_by_key(|(_, figures)| figures.allocs) {
                bar.suspend(|| {
                    println!(
                        "most allocations in one frame: {} ({} frame {} with {}, {} polygons)",
                        figures.allocs, shot.entry.name, shot.frame, shot.method, figures.polygons
                    )
                });
            }
        }
        let first = cycles.first().unwrap_or(&cycle);
        failures.extend(problems(&plan, settled, first, &cycle, number, NAMED));
        cycles.push(cycle);
    }
    bar.finish_and_clear();
    ensure!(failures.is_empty(), "the soak failed:\n{}", failures.join("\n"));
    println!(
        "{} cycles of {} frames: the heap ended every cycle where it was before the first, every frame's figures repeated",
        opt.cycles,
        plan.len()
    );
    Ok(())
}
