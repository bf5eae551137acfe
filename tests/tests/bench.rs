//! `BENCH` answers for every demo scene with one cycle count per method,
//! in the order of `raster::methods::ALL`. Only the shape of the answer is
//! checked: the cycles are emulated (QEMU TCG) and speed is never asserted.

use anyhow::{bail, ensure, Result};
use harness::{Qemu, QemuOptions, Reply};
use protocol::Command;
use raster::{methods, scenes};

#[test]
fn bench_answers_one_positive_cycle_count_per_method_for_every_demo_scene() -> Result<()> {
    let expected: Vec<&str> = methods::ALL.iter().map(|method| method.info().name).collect();
    let mut qemu = Qemu::boot(QemuOptions::default())?;
    for scene in scenes::NAMES {
        let rows = qemu.console.bench(scene, 1)?;
        let names: Vec<&str> = rows.iter().map(|(name, _)| name.as_str()).collect();
        ensure!(names == expected, "BENCH {scene} listed methods {names:?}, expected {expected:?}");
        for (method, cycles) in &rows {
            ensure!(*cycles > 0, "BENCH {scene}: {method} took {cycles} cycles");
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
