//! The demo pages, drawn by the kernel in QEMU, against the host render
//! (QEMU's own view of the screen is checked on every adapter in
//! `adapters.rs`).

use anyhow::{ensure, Result};
use harness::checks::dump_matches_host_render;
use harness::picture::compare::compare_palettes;
use harness::{Qemu, QemuOptions};
use protocol::{Command, LogEvent, Machine};
use raster::MethodId;
use scenes::builtin;
use scenes::palette::VGA_DEFAULT;

#[test]
fn every_page_with_every_method_dumps_what_the_host_renders() -> Result<()> {
    let mut qemu = Qemu::boot(QemuOptions::default())?;
    // Every combination runs, so one failure does not hide the others.
    let failures: Vec<String> = builtin::ALL
        .iter()
        .flat_map(|page| MethodId::ALL.map(move |method| (page.name, method)))
        .filter_map(|(scene, method)| dump_matches_host_render(&mut qemu.console, scene, method).err())
        .map(|error| format!("{error:#}"))
        .collect();
    ensure!(failures.is_empty(), "{} mismatches:\n{}", failures.len(), failures.join("\n"));
    Ok(())
}

/// What this proves, and no more: after boot the DAC, read back by the
/// kernel's own `DUMP` (index to 0x3C7, then 0x3C9), holds the table the
/// kernel loaded, `scenes::palette::VGA_DEFAULT`, entry for entry. Kernel
/// and host take that table from the same source, so an error in the
/// table itself passes here (its unit tests pin a few entries); and a
/// read-back shows what the DAC holds, not what reaches the screen, which
/// `adapters.rs` judges by QEMU's screendump.
#[test]
fn the_dac_reads_back_the_vga_default_table_the_kernel_loaded_at_boot() -> Result<()> {
    let mut qemu = Qemu::boot(QemuOptions::default())?;
    let dump = qemu.console.dump()?;
    compare_palettes("the DAC after boot against the VGA default", &VGA_DEFAULT, &dump.palette)
}

#[test]
fn kernel_lists_the_scenes_and_methods_the_host_knows() -> Result<()> {
    let mut qemu = Qemu::boot(QemuOptions::default())?;
    let listing = qemu.console.list()?;
    let methods = MethodId::ALL.map(MethodId::name);
    let scenes = builtin::ALL.map(|page| page.name);
    ensure!(listing.scenes == scenes, "kernel lists scenes {:?}, host has {scenes:?}", listing.scenes);
    ensure!(listing.methods == methods, "kernel lists methods {:?}, host has {methods:?}", listing.methods);
    Ok(())
}

/// At boot the kernel logs the machine it found, and nothing else: a
/// register or DAC entry that does not read back would be a `LOG` line.
#[test]
fn vga_registers_read_back_as_programmed() -> Result<()> {
    let mut qemu = Qemu::boot(QemuOptions::default())?;
    let logs = qemu.console.logs();
    let only_the_machine = matches!(logs, [LogEvent::Machine(evidence)] if evidence.machine == Machine::Qemu);
    ensure!(only_the_machine, "the kernel logged at boot: {logs:?}");
    qemu.console.ok(&Command::VgaCheck)?;
    Ok(())
}
