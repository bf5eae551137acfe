//! A user's own scene file drawn by the kernel: sent line by line with
//! `CLEAR` and `POLY` (what `cargo xtask dump --scene FILE` does), dumped,
//! and compared byte for byte with the host render of the same file, and
//! with QEMU's own screendump.

use anyhow::{ensure, Result};
use harness::checks::{screen_matches_dump, source_matches_host_render};
use harness::render::SceneSource;
use harness::{Qemu, QemuOptions};
use raster::MethodId;
use scenes::Op;

/// Holes (a second contour), both fill rules (a self-overlapping star under
/// non-zero, the same star under even-odd), subpixel vertices, a comment
/// and a blank line.
const SCENE: &str = "\
# a frame with a hole, a star both ways, a sliver at quarter pixels
clear 1
poly color=14 10,10 150,10 150,120 10,120 | 40,40 40,90.5 120.25,90.5 120.25,40

poly color=12 rule=nonzero 230,15 262.5,110 180,50.75 285,50.75 197.5,110
poly color=10 rule=evenodd 230,95 262.5,190 180,130.75 285,130.75 197.5,190 # the same star, lower
poly color=4 20.25,150.75 140.5,140.125 60.875,195.5
";

#[test]
fn a_scene_file_with_holes_both_rules_and_subpixel_vertices_dumps_what_the_host_renders() -> Result<()> {
    let path = std::env::temp_dir().join(format!("polylab-scene-files-{}.scene", std::process::id()));
    std::fs::write(&path, SCENE)?;
    let source = SceneSource::find(path.to_str().expect("a UTF-8 temporary path"));
    std::fs::remove_file(&path)?;
    let source = source?;
    let polygons = source.scene().ops.iter().filter(|op| matches!(op, Op::Fill(_))).count();
    ensure!(polygons == 4, "the scene has {polygons} polygons, not 4");

    let mut qemu = Qemu::boot(QemuOptions::default())?;
    // exact takes every polygon; abrash_aet is the book's general filler
    // (odd/even only); abrash_float refuses the frame's two contours, and
    // the host render refuses it alike.
    for method in [MethodId::Exact, MethodId::AbrashAet, MethodId::AbrashFloat] {
        let dump = source_matches_host_render(&mut qemu.console, &source, method)?;
        let screen = qemu.screendump()?;
        screen_matches_dump(&format!("{}.{method}", source.name()), &dump, &screen, &qemu.ready.video)?;
    }
    Ok(())
}
