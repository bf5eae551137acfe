//! The adapter matrix: the image on every display card QEMU offers with a
//! VGA BIOS (`Adapter::WITH_VGA`: std, cirrus, vmware), each judged by
//! QEMU's own view of the screen. On each card the kernel must name the
//! card in READY (so the run really was on it), every demo page and the
//! first frame of every show entry must reach the screen (QEMU's
//! screendump equal to the kernel's dump seen through the read-back DAC,
//! the dump equal to the host render), and the image must boot from the
//! emulated USB stick too. With no card at all the kernel still boots and
//! says so over serial.

use anyhow::{ensure, Result};
use harness::checks::{dump_matches_host_render, screen_matches_dump, show_matches_host_render};
use harness::{Adapter, Medium, Qemu, QemuOptions};
use scenes::builtin;
use scenes::show::ENTRIES_IN_ORDER;

/// Boots the image from `medium` with `adapter` and checks that READY
/// names the card and every mode-13h register and DAC entry read back as
/// written.
fn boot_on(adapter: Adapter, medium: Medium) -> Result<Qemu> {
    let qemu = Qemu::boot(QemuOptions { adapter, medium, ..QemuOptions::default() })?;
    let ready = qemu.ready;
    ensure!(
        ready.display == adapter.pci_id(),
        "-vga {}: READY names the display {:?}, expected {:?}",
        adapter.qemu_name(),
        ready.display,
        adapter.pci_id()
    );
    ensure!(
        ready.vga_mismatches == 0,
        "-vga {}: READY counts {} VGA mismatches",
        adapter.qemu_name(),
        ready.vga_mismatches
    );
    Ok(qemu)
}

/// Every page drawn, and the first frame of every show entry shown, each
/// checked on QEMU's screendump; one failure does not hide the others.
fn every_page_and_every_entry_reach_the_screen(adapter: Adapter) -> Result<()> {
    let mut qemu = boot_on(adapter, Medium::Disk)?;
    let on = |name: &str| format!("{}.{name}", adapter.qemu_name());
    let mut failures = Vec::new();
    for scene in builtin::ALL.map(|page| page.name) {
        let mut page = || -> Result<()> {
            qemu.console.draw(scene, None)?;
            let dump = qemu.console.dump()?;
            screen_matches_dump(&on(scene), &dump, &qemu.screendump()?)
        };
        failures.extend(page().err().map(|error| format!("{error:#}")));
    }
    for entry in ENTRIES_IN_ORDER {
        let mut first_frame = || -> Result<()> {
            let (_, dump) = show_matches_host_render(&mut qemu.console, entry.name, 0, None)?;
            screen_matches_dump(&on(&format!("{}.0", entry.name)), &dump, &qemu.screendump()?)
        };
        failures.extend(first_frame().err().map(|error| format!("{error:#}")));
    }
    ensure!(failures.is_empty(), "-vga {}: {} failures:\n{}", adapter.qemu_name(), failures.len(), failures.join("\n"));
    Ok(())
}

#[test]
fn std_vga_shows_every_page_and_the_first_frame_of_every_entry() -> Result<()> {
    every_page_and_every_entry_reach_the_screen(Adapter::Std)
}

#[test]
fn cirrus_vga_shows_every_page_and_the_first_frame_of_every_entry() -> Result<()> {
    every_page_and_every_entry_reach_the_screen(Adapter::Cirrus)
}

#[test]
fn vmware_vga_shows_every_page_and_the_first_frame_of_every_entry() -> Result<()> {
    every_page_and_every_entry_reach_the_screen(Adapter::Vmware)
}

/// The image on the emulated USB stick (xHCI usb-storage, which SeaBIOS
/// boots as a PC's BIOS does) draws page 1 as the host renders it, and it
/// reaches the screen.
fn usb_stick_boots_and_draws_page_1(adapter: Adapter) -> Result<()> {
    let mut qemu = boot_on(adapter, Medium::UsbStick)?;
    let page_1 = builtin::ABRASH38_1;
    let dump = dump_matches_host_render(&mut qemu.console, page_1.name, page_1.method)?;
    let name = format!("{}.usb.{}", adapter.qemu_name(), page_1.name);
    screen_matches_dump(&name, &dump, &qemu.screendump()?)
}

#[test]
fn std_vga_boots_from_the_usb_stick() -> Result<()> {
    usb_stick_boots_and_draws_page_1(Adapter::Std)
}

#[test]
fn cirrus_vga_boots_from_the_usb_stick() -> Result<()> {
    usb_stick_boots_and_draws_page_1(Adapter::Cirrus)
}

#[test]
fn vmware_vga_boots_from_the_usb_stick() -> Result<()> {
    usb_stick_boots_and_draws_page_1(Adapter::Vmware)
}

/// No display card: the boot stages ask the card for nothing, so the
/// kernel boots, READY names no display and counts the VGA registers that
/// did not read back (there is nothing to read), and it serves commands.
#[test]
fn with_no_display_card_the_kernel_boots_and_says_so_over_serial() -> Result<()> {
    let mut qemu = Qemu::boot(QemuOptions { adapter: Adapter::None, ..QemuOptions::default() })?;
    let ready = qemu.ready;
    ensure!(ready.display.is_none(), "-vga none: READY names the display {:?}", ready.display);
    ensure!(ready.vga_mismatches > 0, "-vga none: READY counts no VGA mismatches, yet there is no VGA");
    let losses = qemu.console.ping()?;
    ensure!(losses.none(), "-vga none: PING says the serial line lost bytes: {losses}");
    Ok(())
}
