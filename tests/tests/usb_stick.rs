//! The image written to a USB stick boots too (rehearsed on QEMU's xHCI
//! usb-storage, which SeaBIOS boots like a PC's BIOS does).

use anyhow::Result;
use harness::checks::dump_matches_host_render;
use harness::{Medium, Qemu, QemuOptions};
use raster::scenes::{self, NAMES};

#[test]
fn usb_stick_boot_draws_page_1_like_the_host() -> Result<()> {
    let mut qemu = Qemu::boot(QemuOptions { medium: Medium::UsbStick, ..QemuOptions::default() })?;
    let page_1 = scenes::by_name(NAMES[0]).expect("page 1 is built in");
    dump_matches_host_render(&mut qemu.console, NAMES[0], page_1.method())?;
    Ok(())
}
