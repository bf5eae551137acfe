//! The image written to a USB stick boots too (rehearsed on QEMU's xHCI
//! usb-storage, which SeaBIOS boots like a PC's BIOS does).

use anyhow::Result;
use harness::checks::dump_matches_host_render;
use harness::{Medium, Qemu, QemuOptions};
use scenes::builtin;

#[test]
fn usb_stick_boot_draws_page_1_like_the_host() -> Result<()> {
    let mut qemu = Qemu::boot(QemuOptions { medium: Medium::UsbStick, ..QemuOptions::default() })?;
    let page_1 = builtin::ABRASH38_1;
    dump_matches_host_render(&mut qemu.console, page_1.name, page_1.method)?;
    Ok(())
}
