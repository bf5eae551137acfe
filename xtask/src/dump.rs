//! `cargo xtask dump`: the kernel's picture of a scene and QEMU's.

use anyhow::Result;
use harness::checks::screen_matches_dump;
use harness::render::builtin_scene;
use harness::{Qemu, QemuOptions};

use crate::opt::DumpOpt;

pub fn dump(opt: &DumpOpt) -> Result<()> {
    // Check the names before spending a boot on them.
    let scene = builtin_scene(&opt.scene)?;
    let method = opt.method.unwrap_or(scene.method);
    let mut qemu = Qemu::boot(QemuOptions::default())?;
    qemu.console.draw(&opt.scene, Some(method))?;
    let dump = qemu.console.dump()?;
    let screen = qemu.screendump()?;
    let dump_path = opt.out.join(format!("{}.png", opt.scene));
    let screen_path = opt.out.join(format!("{}.screen.png", opt.scene));
    dump.image().write_png(&dump_path)?;
    screen.write_png(&screen_path)?;
    println!("{}", dump_path.display());
    println!("{}", screen_path.display());
    qemu.quit()?;
    screen_matches_dump(&opt.scene, &dump, &screen)?;
    eprintln!("xtask: the two agree pixel for pixel (each pixel a 2x2 block on QEMU's screen)");
    Ok(())
}
