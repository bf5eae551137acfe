//! `cargo xtask run`: the demo, in a window or headless.

use std::path::Path;

use anyhow::Result;
use harness::checks::show_matches_host_render;
use harness::workspace::target_dir;
use harness::{build_image, Display, Qemu, QemuOptions};
use scenes::show::ENTRIES_IN_ORDER;

use crate::opt::RunOpt;
use crate::record::{summary, Frames, Recording};

/// Show frames from one recorded frame to the next when running headless:
/// a loop of 256 frames becomes a GIF of 64.
const HEADLESS_STEP: u32 = 4;

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

/// No display: plays the show through `SHOW` as the demo would, entry by
/// entry, into `out`: a still as `<entry>.png`, an animation as
/// `<entry>.gif` (every [`HEADLESS_STEP`]-th frame of one loop), each
/// checked against the host render, printing each path and the cycles.
fn headless(out: &Path) -> Result<()> {
    eprintln!(
        "xtask: no display (DISPLAY and WAYLAND_DISPLAY unset): playing the show headless into {}",
        out.display()
    );
    let mut qemu = Qemu::boot(QemuOptions::default())?;
    for entry in ENTRIES_IN_ORDER {
        if entry.is_animated() {
            let path = out.join(format!("{}.gif", entry.name));
            let frames = Frames { start: 0, step: HEADLESS_STEP, count: entry.frames.div_ceil(HEADLESS_STEP) };
            let shown = Recording::new(entry, frames, None, true, &path)?.film(&mut qemu.console)?;
            println!("{}", path.display());
            print!("{}", summary(&shown));
        } else {
            let path = out.join(format!("{}.png", entry.name));
            let (shown, dump) = show_matches_host_render(&mut qemu.console, entry.name, 0, None)?;
            dump.image().write_png(&path)?;
            println!("{}", path.display());
            print!("{}", summary(&[shown]));
        }
    }
    qemu.quit()?;
    Ok(())
}
