//! The VGA as a real PC presents it, as far as QEMU can show it: the
//! window mapped the way the kernel reports it, the palette registers read
//! back without leaving the screen blank, and, with a second display
//! device ahead of the VGA in bus order, the VGA found by the legacy VGA
//! decoding rather than by its place on the bus.

use anyhow::{bail, ensure, Result};
use harness::checks::{dump_matches_host_render, screen_matches_dump};
use harness::{Adapter, DisplayAhead, Qemu, QemuOptions};
use protocol::{Command, Firmware, FramebufferCheck, MemoryType, PageMapping, PciAddress, VgaCheck, Video, Window};
use scenes::builtin;

/// The PAT as a CPU starts with it: write-back, write-through, UC-,
/// uncacheable, twice (Intel's manual, volume 3, "Page Attribute Table").
const PAT_AT_RESET: u64 = 0x0007_0406_0007_0406;

/// `VGACHECK` reads back how the kernel mapped the VGA window: 16 pages of
/// 4 KiB, uncacheable by the PAT (the bootloader's map had it in one 2 MiB
/// write-back page), and the PAT as the CPU starts with it (the kernel
/// reprograms an entry only for a firmware's framebuffer). `READY` names
/// the type. TCG ignores memory types, so this is the page tables' word,
/// not a measurement.
#[test]
fn vgacheck_reports_the_window_in_4_kib_uncacheable_pages() -> Result<()> {
    let mut qemu = Qemu::boot(QemuOptions::default())?;
    ensure!(qemu.ready.memory == Some(MemoryType::Uncacheable), "READY names the memory {:?}", qemu.ready.memory);
    let check = VgaCheck::parse(&qemu.console.ok(&Command::VgaCheck)?)?;
    let uncacheable_4k =
        PageMapping { pages: 16, page_size: 4096, pat_entry: 3, memory: Some(MemoryType::Uncacheable), uniform: true };
    let expected = VgaCheck::Vga {
        mismatches: Vec::new(),
        window: Some(Window { start: 0xa0000, end: 0xaffff, mapping: uncacheable_4k }),
        pat: PAT_AT_RESET,
    };
    ensure!(check == expected, "VGACHECK answered {check:?}, expected {expected:?}");
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
/// with no VGA, and the same PCI IDs) in slot 2, under SeaBIOS: `READY`
/// must name the VGA by its place, the page must reach the VGA's screen
/// exactly, and every register read back.
#[test]
fn bios_finds_the_vga_behind_another_display_device() -> Result<()> {
    let ahead = Some(DisplayAhead::BochsDisplay);
    let options = QemuOptions { adapter: Adapter::Std, display_ahead: ahead, ..QemuOptions::default() };
    let mut qemu = Qemu::boot(options)?;
    let ready = qemu.ready;
    let on = "bios std behind bochs-display";
    eprintln!("harness: {on}: {ready}");
    let slot_5 = Some(PciAddress { bus: 0, device: 5, function: 0 });
    ensure!(ready.display_at == slot_5, "{on}: READY names the display at {:?}, not 00:05.0", ready.display_at);
    ensure!(ready.display == Adapter::Std.pci_id(), "{on}: READY names the display {:?}", ready.display);
    ensure!(ready.video == Video::Vga13h { mismatches: 0 }, "{on}: READY names the video path {:?}", ready.video);
    let page = builtin::ABRASH38_1;
    let dump = dump_matches_host_render(&mut qemu.console, page.name, page.method)?;
    screen_matches_dump(&format!("bios.behind.{}", page.name), &dump, &qemu.screendump()?, &ready.video)
}

/// Under OVMF with a display controller ahead of the std VGA, OVMF shows
/// its screen on the one ahead and hands its framebuffer over: the frame
/// must go there, the head a user looks at, not into mode 13h on the VGA
/// behind. `READY` must name that device and its place, the framebuffer
/// path and write-combining, `VGACHECK` write-combining on both of the
/// framebuffer's mappings (the kernel's own and its alias in the map of
/// all physical memory: a write-combining page aliased to a cacheable one
/// is what the manual forbids), and the page must reach that device's
/// screen exactly (QMP's screendump of it).
fn uefi_shows_the_frame_on_the_head_the_firmware_used(ahead: DisplayAhead, slot: u8) -> Result<()> {
    let options = QemuOptions {
        firmware: Firmware::Uefi,
        adapter: Adapter::Std,
        display_ahead: Some(ahead),
        ..QemuOptions::default()
    };
    let mut qemu = Qemu::boot(options)?;
    let ready = qemu.ready;
    let on = format!("uefi std behind {ahead:?}");
    eprintln!("harness: {on}: {ready}");
    let head = Some(PciAddress { bus: 0, device: slot, function: 0 });
    ensure!(ready.display_at == head, "{on}: READY names the display at {:?}, not 00:{slot:02x}.0", ready.display_at);
    ensure!(matches!(ready.video, Video::Framebuffer(_)), "{on}: READY names the video path {:?}", ready.video);
    ensure!(ready.memory == Some(MemoryType::WriteCombining), "{on}: READY names the memory {:?}", ready.memory);
    let check = VgaCheck::parse(&qemu.console.ok(&Command::VgaCheck)?)?;
    let VgaCheck::Framebuffer(FramebufferCheck { mapping, alias, .. }) = check else {
        bail!("{on}: VGACHECK answered {check:?}, not the framebuffer path")
    };
    for (name, mapping) in [("the framebuffer", mapping), ("its alias", alias)] {
        let memory = mapping.and_then(|mapping| mapping.memory_type());
        ensure!(memory == Some(MemoryType::WriteCombining), "{on}: VGACHECK maps {name} {mapping:?}");
    }
    let page = builtin::ABRASH38_1;
    let dump = dump_matches_host_render(&mut qemu.console, page.name, page.method)?;
    screen_matches_dump(&format!("uefi.{ahead:?}.{}", page.name), &dump, &qemu.screendump_ahead()?, &ready.video)
}

#[test]
fn uefi_shows_the_frame_on_bochs_display_ahead_of_the_vga() -> Result<()> {
    uefi_shows_the_frame_on_the_head_the_firmware_used(DisplayAhead::BochsDisplay, 2)
}

#[test]
fn uefi_shows_the_frame_on_secondary_vga_ahead_of_the_vga() -> Result<()> {
    uefi_shows_the_frame_on_the_head_the_firmware_used(DisplayAhead::SecondaryVga, 4)
}
