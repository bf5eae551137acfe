//! The VGA as a real PC presents it, as far as QEMU can show it: the
//! window mapped the way the kernel reports it, the palette registers read
//! back without leaving the screen blank, and, with a second display
//! device ahead of the VGA in bus order, the VGA found by the legacy VGA
//! decoding rather than by its place on the bus.

use anyhow::{ensure, Result};
use harness::checks::{dump_matches_host_render, screen_matches_dump};
use harness::{Adapter, Qemu, QemuOptions};
use protocol::{Command, Firmware, PciAddress, Video};
use scenes::builtin;

/// `VGACHECK` reads back how the kernel mapped the VGA window: 16 pages of
/// 4 KiB, uncacheable by the PAT (the bootloader's map had it in one 2 MiB
/// write-back page). TCG ignores memory types, so this is the page
/// tables' word, not a measurement.
#[test]
fn vgacheck_reports_the_window_in_4_kib_uncacheable_pages() -> Result<()> {
    let mut qemu = Qemu::boot(QemuOptions::default())?;
    let text = qemu.console.ok(&Command::VgaCheck)?;
    let expected = "vga: 0 mismatches; window 0xa0000-0xaffff: 16 pages of 4 KiB, uncacheable (UC), PAT entry 3";
    ensure!(text == expected, "VGACHECK answered \"{text}\", expected \"{expected}\"");
    Ok(())
}

/// Reading the palette registers back blanks the screen (the palette
/// address source bit cleared, as the VGA references require); `VGACHECK`
/// must turn it on again: the page drawn before it is still on QEMU's
/// screen after it, pixel for pixel.
#[test]
fn vgacheck_leaves_the_picture_on_the_screen() -> Result<()> {
    let mut qemu = Qemu::boot(QemuOptions::default())?;
    let page = builtin::ABRASH38_3;
    let dump = dump_matches_host_render(&mut qemu.console, page.name, page.method)?;
    qemu.console.ok(&Command::VgaCheck)?;
    screen_matches_dump(&format!("{}.after-vgacheck", page.name), &dump, &qemu.screendump()?, &qemu.ready.video)
}

/// QEMU's std VGA in slot 5 behind a bochs-display (a display controller
/// with no VGA, and the same PCI IDs) in slot 2: `READY` must name the VGA
/// by its place, the page must reach the VGA's screen exactly, and every
/// register read back.
fn the_vga_behind_another_display_shows_the_page(firmware: Firmware) -> Result<()> {
    let options = QemuOptions { firmware, adapter: Adapter::Std, display_ahead: true, ..QemuOptions::default() };
    let mut qemu = Qemu::boot(options)?;
    let ready = qemu.ready;
    let on = format!("{} std behind bochs-display", firmware.name());
    eprintln!("harness: {on}: {ready}");
    let slot_5 = Some(PciAddress { bus: 0, device: 5, function: 0 });
    ensure!(ready.display_at == slot_5, "{on}: READY names the display at {:?}, not 00:05.0", ready.display_at);
    ensure!(ready.display == Adapter::Std.pci_id(), "{on}: READY names the display {:?}", ready.display);
    ensure!(ready.video == Video::Vga13h { mismatches: 0 }, "{on}: READY names the video path {:?}", ready.video);
    let page = builtin::ABRASH38_1;
    let dump = dump_matches_host_render(&mut qemu.console, page.name, page.method)?;
    screen_matches_dump(&format!("{}.behind.{}", firmware.name(), page.name), &dump, &qemu.screendump()?, &ready.video)
}

#[test]
fn bios_finds_the_vga_behind_another_display_device() -> Result<()> {
    the_vga_behind_another_display_shows_the_page(Firmware::Bios)
}

#[test]
fn uefi_finds_the_vga_behind_another_display_device() -> Result<()> {
    the_vga_behind_another_display_shows_the_page(Firmware::Uefi)
}
