//! The adapter matrix: the one image under both firmwares, on every
//! display card each firmware can drive (`Adapter::proven_under`), each
//! judged by QEMU's own view of the screen. On each, READY must name the
//! firmware, the card (so the run really was on it) and the video path the
//! card allows: mode 13h by register writes wherever the kernel can put
//! the card there (under SeaBIOS every VGA-compatible card; under OVMF
//! the cards whose firmware mode it knows how to undo), else the frame
//! presented in OVMF's framebuffer, scaled and centred. Then every demo
//! page (with its own method) and the first frame of every show entry
//! must reach the screen: the kernel's dump equal to the host render of
//! the same page or frame, and QEMU's screendump equal to that dump seen
//! through its palette (mode 13h: 640x400, pixel (x,y) at (2x,2y);
//! framebuffer: at the scale and offset READY states). The image must
//! boot from the emulated USB stick under both firmwares too. With no
//! card at all the kernel still boots and says so over serial. The list
//! of tests is held to `Adapter::proven_under`: a card proven under a
//! firmware has its test here, and a test here is on a proven card.

use anyhow::{ensure, Result};
use harness::checks::{dump_matches_host_render, screen_matches_dump, show_matches_host_render};
use harness::{Adapter, Medium, Qemu, QemuOptions};
use protocol::{ErrorReply, Firmware, LogEvent, Presentation, VgaCheck, Video};
use raster::SCREEN;
use scenes::builtin;
use scenes::show::ENTRIES_IN_ORDER;

/// `firmware` on `adapter`, for messages.
fn label(firmware: Firmware, adapter: Adapter) -> String {
    format!("{} {}", firmware.name(), adapter.name())
}

/// Whether the kernel must put `adapter` in mode 13h under `firmware`
/// (else it must present its frame in the firmware's framebuffer).
fn takes_mode_13h(firmware: Firmware, adapter: Adapter) -> bool {
    match firmware {
        Firmware::Bios => true,
        Firmware::Uefi => !matches!(adapter, Adapter::BochsDisplay | Adapter::Ramfb),
    }
}

/// Boots the image from `medium` under `firmware` with `adapter` and
/// checks READY: the firmware, the card, and the path, with every mode-13h
/// register and DAC entry read back as written, or the frame at the
/// largest whole scale that fits, centred.
fn boot_on(firmware: Firmware, adapter: Adapter, medium: Medium) -> Result<Qemu> {
    let qemu = Qemu::boot(QemuOptions { firmware, adapter, medium, ..QemuOptions::default() })?;
    let (ready, on) = (qemu.ready, label(firmware, adapter));
    ensure!(ready.firmware == firmware, "{on}: READY names the firmware {:?}", ready.firmware);
    ensure!(
        ready.display == adapter.pci_id(),
        "{on}: READY names the display {:?}, not {:?}",
        ready.display,
        adapter.pci_id()
    );
    match ready.video {
        Video::Vga13h { mismatches } => {
            ensure!(takes_mode_13h(firmware, adapter), "{on}: READY says mode 13h, not the framebuffer");
            ensure!(mismatches == 0, "{on}: READY counts {mismatches} VGA mismatches");
        }
        Video::Framebuffer(presentation) => {
            ensure!(!takes_mode_13h(firmware, adapter), "{on}: READY says framebuffer, not mode 13h");
            ensure!(
                presentation == centred(presentation.width, presentation.height),
                "{on}: READY's {presentation:?} is not the frame at the largest scale that fits, centred"
            );
        }
        Video::None => anyhow::bail!("{on}: READY says nothing shows the frame"),
    }
    Ok(qemu)
}

/// The 320x200 frame at the largest whole scale that fits a `width` x
/// `height` framebuffer, centred.
fn centred(width: u32, height: u32) -> Presentation {
    let scale = (width / SCREEN.width as u32).min(height / SCREEN.height as u32);
    let (left, top) = ((width - SCREEN.width as u32 * scale) / 2, (height - SCREEN.height as u32 * scale) / 2);
    Presentation { width, height, scale, left, top }
}

/// Every page drawn, and the first frame of every show entry shown, each
/// checked on QEMU's screendump; one failure does not hide the others.
fn every_page_and_every_entry_reach_the_screen(firmware: Firmware, adapter: Adapter) -> Result<()> {
    let mut qemu = boot_on(firmware, adapter, Medium::Disk)?;
    let video = qemu.ready.video;
    let on = |name: &str| format!("{}.{}.{name}", firmware.name(), adapter.name());
    let (mut failures, mut screens) = (Vec::new(), Vec::new());
    for page in builtin::ALL {
        let mut drawn = || -> Result<()> {
            let dump = dump_matches_host_render(&mut qemu.console, page.name, page.method)?;
            let screen = qemu.screendump()?;
            screens.push((screen.width(), screen.height()));
            screen_matches_dump(&on(page.name), &dump, &screen, &video)
        };
        failures.extend(drawn().err().map(|error| format!("{error:#}")));
    }
    for entry in ENTRIES_IN_ORDER {
        let mut first_frame = || -> Result<()> {
            let (_, dump) = show_matches_host_render(&mut qemu.console, entry.name, 0, None)?;
            let screen = qemu.screendump()?;
            screens.push((screen.width(), screen.height()));
            screen_matches_dump(&on(&format!("{}.0", entry.name)), &dump, &screen, &video)
        };
        failures.extend(first_frame().err().map(|error| format!("{error:#}")));
    }
    let on = label(firmware, adapter);
    ensure!(failures.is_empty(), "{on}: {} failures:\n{}", failures.len(), failures.join("\n"));
    let pixels: u64 = screens.iter().map(|&(width, height)| u64::from(width) * u64::from(height)).sum();
    let sizes: std::collections::BTreeSet<_> =
        screens.iter().map(|(width, height)| format!("{width}x{height}")).collect();
    eprintln!(
        "harness: {on}: {}; {} dumps equal to the host render, their screendumps ({}) to them, {pixels} pixels, 0 differ",
        qemu.ready,
        screens.len(),
        sizes.into_iter().collect::<Vec<_>>().join(", ")
    );
    Ok(())
}

/// One test per firmware and card of the matrix, and `MATRIX`: the
/// firmware and card of each, in order.
macro_rules! matrix {
    ($($test:ident: $firmware:ident $adapter:ident,)*) => {
        $(
            #[test]
            fn $test() -> Result<()> {
                every_page_and_every_entry_reach_the_screen(Firmware::$firmware, Adapter::$adapter)
            }
        )*
        /// The firmware and card of each test `matrix!` made.
        const MATRIX: &[(Firmware, Adapter)] = &[$((Firmware::$firmware, Adapter::$adapter)),*];
    };
}

matrix! {
    bios_std_shows_every_page_and_the_first_frame_of_every_entry: Bios Std,
    bios_cirrus_shows_every_page_and_the_first_frame_of_every_entry: Bios Cirrus,
    bios_vmware_shows_every_page_and_the_first_frame_of_every_entry: Bios Vmware,
    bios_qxl_vga_shows_every_page_and_the_first_frame_of_every_entry: Bios QxlVga,
    bios_virtio_vga_shows_every_page_and_the_first_frame_of_every_entry: Bios VirtioVga,
    bios_ati_vga_shows_every_page_and_the_first_frame_of_every_entry: Bios AtiVga,
    uefi_std_shows_every_page_and_the_first_frame_of_every_entry: Uefi Std,
    uefi_cirrus_shows_every_page_and_the_first_frame_of_every_entry: Uefi Cirrus,
    uefi_vmware_shows_every_page_and_the_first_frame_of_every_entry: Uefi Vmware,
    uefi_qxl_vga_shows_every_page_and_the_first_frame_of_every_entry: Uefi QxlVga,
    uefi_virtio_vga_shows_every_page_and_the_first_frame_of_every_entry: Uefi VirtioVga,
    uefi_bochs_display_shows_every_page_and_the_first_frame_of_every_entry: Uefi BochsDisplay,
    uefi_ramfb_shows_every_page_and_the_first_frame_of_every_entry: Uefi Ramfb,
}

/// The firmware the test without a display card boots, and the one the
/// test of virtio-gpu's BltOnly mode boots.
const NO_CARD_FIRMWARE: Firmware = Firmware::Bios;
const BLT_ONLY_FIRMWARE: Firmware = Firmware::Uefi;

/// The tests made by `matrix!`, with the one without a card and the one
/// of virtio-gpu, are one per
/// pair of firmware and card that `Adapter::proven_under` names, and none
/// more: a card's test deleted from the list, or a card proven and never
/// tested, fails here.
#[test]
fn the_matrix_is_every_card_each_firmware_can_drive() {
    let others = [(NO_CARD_FIRMWARE, Adapter::None), (BLT_ONLY_FIRMWARE, Adapter::VirtioGpu)];
    let tested: Vec<(Firmware, Adapter)> = MATRIX.iter().copied().chain(others).collect();
    let proven: Vec<(Firmware, Adapter)> = Firmware::ALL
        .into_iter()
        .flat_map(|firmware| Adapter::ALL.into_iter().map(move |adapter| (firmware, adapter)))
        .filter(|&(firmware, adapter)| adapter.proven_under(firmware))
        .collect();
    let names = |pairs: &[(Firmware, Adapter)]| -> Vec<String> {
        let mut names: Vec<String> = pairs.iter().map(|&(firmware, adapter)| label(firmware, adapter)).collect();
        names.sort();
        names
    };
    assert_eq!(names(&tested), names(&proven), "the tests (left) against the cards proven under each firmware");
}

/// The image on the emulated USB stick (xHCI usb-storage, which SeaBIOS
/// and OVMF boot as a PC's firmware does) draws page 1 as the host renders
/// it, and it reaches the screen.
fn usb_stick_boots_and_draws_page_1(firmware: Firmware) -> Result<()> {
    let mut qemu = boot_on(firmware, Adapter::Std, Medium::UsbStick)?;
    let page_1 = builtin::ABRASH38_1;
    let dump = dump_matches_host_render(&mut qemu.console, page_1.name, page_1.method)?;
    let name = format!("{}.std.usb.{}", firmware.name(), page_1.name);
    screen_matches_dump(&name, &dump, &qemu.screendump()?, &qemu.ready.video)
}

#[test]
fn bios_boots_from_the_usb_stick() -> Result<()> {
    usb_stick_boots_and_draws_page_1(Firmware::Bios)
}

#[test]
fn uefi_boots_from_the_usb_stick() -> Result<()> {
    usb_stick_boots_and_draws_page_1(Firmware::Uefi)
}

/// No display card: the boot stages ask the card for nothing, so the
/// kernel boots, READY names no display and no video path, VGACHECK says
/// there is nothing to check, and the kernel serves commands, its frame
/// kept in memory.
#[test]
fn with_no_display_card_the_kernel_boots_and_says_so_over_serial() -> Result<()> {
    let options = QemuOptions { firmware: NO_CARD_FIRMWARE, adapter: Adapter::None, ..QemuOptions::default() };
    let mut qemu = Qemu::boot(options)?;
    let ready = qemu.ready;
    ensure!(ready.display.is_none(), "-vga none: READY names the display {:?}", ready.display);
    ensure!(ready.video == Video::None, "-vga none: READY names the video path {:?}", ready.video);
    let check = qemu.console.refusal(&protocol::Command::VgaCheck)?;
    let check = ErrorReply::parse(&check)?;
    ensure!(check == ErrorReply::VgaCheck(VgaCheck::Nothing), "-vga none: VGACHECK answers ERR {check:?}");
    let page_1 = builtin::ABRASH38_1;
    dump_matches_host_render(&mut qemu.console, page_1.name, page_1.method)?;
    let losses = qemu.console.ping()?;
    ensure!(losses.none(), "-vga none: PING says the serial line lost bytes: {losses}");
    Ok(())
}

/// virtio-gpu under OVMF: its driver offers a BltOnly mode, with no
/// framebuffer to draw in. The loader hands over none (before its edit it
/// panicked there, and the kernel never started); the kernel boots, says
/// so in a `LOG` frame, names the card and no video path, and serves.
#[test]
fn under_uefi_a_blt_only_display_gets_no_framebuffer_and_the_kernel_says_so() -> Result<()> {
    let options = QemuOptions { firmware: BLT_ONLY_FIRMWARE, adapter: Adapter::VirtioGpu, ..QemuOptions::default() };
    let mut qemu = Qemu::boot(options)?;
    let ready = qemu.ready;
    ensure!(ready.display == Adapter::VirtioGpu.pci_id(), "virtio-gpu: READY names the display {:?}", ready.display);
    ensure!(ready.video == Video::None, "virtio-gpu: READY names the video path {:?}", ready.video);
    let said = qemu.console.logs().contains(&LogEvent::NoFramebuffer);
    ensure!(said, "virtio-gpu: no LOG says there is no framebuffer: {:?}", qemu.console.logs());
    let losses = qemu.console.ping()?;
    ensure!(losses.none(), "virtio-gpu: PING says the serial line lost bytes: {losses}");
    Ok(())
}
