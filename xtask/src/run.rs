//! `cargo xtask run`: the demo, in a window or headless.

use std::path::Path;

use anyhow::Result;
use harness::workspace::target_dir;
use harness::{build_image, Display, Qemu, QemuOptions};
use raster::scenes::NAMES;

use crate::opt::RunOpt;

pub fn run(opt: &RunOpt) -> Result<()> {
    let has_display =
        ["DISPLAY", "WAYLAND_DISPLAY"].iter().any(|var| std::env::var_os(var).is_some_and(|v| !v.is_empty()));
    if has_display && !opt.headless {
        in_a_window()
    } else {
        headless(&target_dir().join("run"))
    }
}

/// QEMU in a window, the kernel running its demo with nobody talking to it
/// (pages change on a timer, or on a key press), until the window closes.
fn in_a_window() -> Result<()> {
    let options = QemuOptions { display: Display::Window, ..QemuOptions::default() };
    let mut qemu = Qemu::spawn(&build_image()?, options)?;
    eprintln!("xtask: the demo runs in the QEMU window; close it to finish");
    qemu.wait_until_closed()
}

/// No display: draws every page and writes the kernel's dump of each as
/// `<page>.png` in `out`, printing each path.
fn headless(out: &Path) -> Result<()> {
    eprintln!("xtask: no display (DISPLAY and WAYLAND_DISPLAY unset): running headless");
    let mut qemu = Qemu::boot(QemuOptions::default())?;
    for page in NAMES {
        qemu.console.draw(page, None)?;
        let path = out.join(format!("{page}.png"));
        qemu.console.dump()?.image().write_png(&path)?;
        println!("{}", path.display());
    }
    qemu.quit()?;
    Ok(())
}
