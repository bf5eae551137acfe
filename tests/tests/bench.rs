//! `BENCH` answers for every demo scene with one cycle count per method,
//! in the order of `raster::MethodId::ALL`. Only the shape of the answer is
//! checked: the cycles are emulated (QEMU TCG) and speed is never asserted.

use anyhow::{bail, ensure, Result};
use harness::{Qemu, QemuOptions, Reply};
use protocol::Command;
use raster::MethodId;
use scenes::builtin;

#[test]
fn bench_answers_one_positive_cycle_count_per_method_for_every_demo_scene() -> Result<()> {
    let mut qemu = Qemu::boot(QemuOptions::default())?;
    for scene in builtin::ALL.map(|page| page.name) {
        let rows = qemu.console.bench(scene, 1)?;
        let methods: Vec<MethodId> = rows.iter().map(|&(method, _)| method).collect();
        ensure!(methods == MethodId::ALL, "BENCH {scene} listed methods {methods:?}, expected {:?}", MethodId::ALL);
        for (method, cycles) in &rows {
            ensure!(*cycles > 0, "BENCH {scene}: {method} took {cycles} cycles");
        }
    }
    match qemu.console.request(&Command::Bench { scene: "no-such-scene", repeats: 1 })? {
        Reply::Err(text) if text.contains("no-such-scene") => {}
        other => bail!("BENCH of an unknown scene answered {other:?}, expected an ERR naming it"),
    }
    let pong = qemu.console.ok(&Command::Ping)?;
    ensure!(pong == "pong", "PING after BENCH answered OK \"{pong}\"");
    Ok(())
}
