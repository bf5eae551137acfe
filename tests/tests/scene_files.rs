//! A user's own scene file drawn by the kernel: uploaded whole (what
//! `cargo xtask dump --scene FILE` does), dumped, and compared byte for
//! byte with the host render of the same file, and with QEMU's own
//! screendump; scenes far past a command line's 4,096 bytes among them,
//! and uploads the kernel must refuse or drop, drawing nothing.

use anyhow::{ensure, Context, Result};
use harness::checks::{screen_matches_dump, source_matches_host_render};
use harness::large_scenes::{large_file, rings};
use harness::sources::{SceneFile, SceneSource};
use harness::{Qemu, QemuOptions};
use protocol::{ChunkReply, Command, ErrorReply, UPLOAD_BUDGET};
use raster::MethodId;
use scenes::packed;

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
    let polygons = source.scene().polygons().count();
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

/// `scene` drawn by the kernel with each of `methods`, each picture equal
/// to the host render and to QEMU's screendump.
fn kernel_draws(qemu: &mut Qemu, source: &SceneSource, methods: &[MethodId]) -> Result<()> {
    for &method in methods {
        let dump = source_matches_host_render(&mut qemu.console, source, method)?;
        let screen = qemu.screendump()?;
        screen_matches_dump(&format!("{}.{method}", source.name()), &dump, &screen, &qemu.ready.video)?;
    }
    Ok(())
}

#[test]
fn a_polygon_of_2000_vertices_in_40_contours_dumps_what_the_host_renders() -> Result<()> {
    let scene = rings(40, 2000 / 40);
    let file = SceneFile { path: "rings.scene".into(), scene };
    let mut qemu = Qemu::boot(QemuOptions::default())?;
    // exact takes several contours; abrash_aet is the book's general filler.
    kernel_draws(&mut qemu, &SceneSource::File(file), &[MethodId::Exact, MethodId::AbrashAet])?;
    let uploaded = qemu.console.last_upload().context("the rings were uploaded")?;
    ensure!(uploaded.sent > 4096, "the upload took {} bytes of lines, one command line's worth", uploaded.sent);
    Ok(())
}

#[test]
fn a_scene_file_of_350_kb_with_its_own_palette_dumps_what_the_host_renders() -> Result<()> {
    let dir = tempfile::tempdir()?;
    let path = dir.path().join("large.scene");
    std::fs::write(&path, large_file(350_000))?;
    let source = SceneSource::find(path.to_str().expect("a UTF-8 temporary path"))?;
    ensure!(std::fs::metadata(&path)?.len() >= 350_000, "the file is smaller than 350 KB");
    let mut qemu = Qemu::boot(QemuOptions::default())?;
    kernel_draws(&mut qemu, &source, &[MethodId::Exact, MethodId::Wgt])?;
    Ok(())
}

#[test]
fn an_upload_over_the_budget_cut_off_or_damaged_draws_nothing_and_the_kernel_serves_on() -> Result<()> {
    let mut qemu = Qemu::boot(QemuOptions::default())?;
    let console = &mut qemu.console;
    let scene = rings(8, 30);
    let bytes = packed::pack(&scene);
    let memory = packed::memory(&scene);
    let crc = crc32fast::hash(&bytes);
    let base64 = |bytes: &[u8]| base64::Engine::encode(&base64::engine::general_purpose::STANDARD, bytes);
    let unknown = |name: &str| ErrorReply::UnknownScene(name).to_string();
    console.clear(5)?;

    // Over the budget: refused by name and size, nothing kept.
    let over = Command::Upload { name: "rings", bytes: bytes.len(), memory: UPLOAD_BUDGET, crc };
    let refused = console.refusal(&over)?;
    let expected = ErrorReply::OverBudget { bytes: bytes.len(), memory: UPLOAD_BUDGET, budget: UPLOAD_BUDGET };
    ensure!(ErrorReply::parse(&refused)? == expected, "`{over}` answered ERR \"{refused}\"");
    ensure!(console.refusal(&Command::Draw { scene: "rings", method: None })? == unknown("rings"));

    // Cut off midway: the first half arrives, then the next upload starts.
    let start = Command::Upload { name: "rings", bytes: bytes.len(), memory, crc };
    console.ok(&start)?;
    let half = bytes.len() / 2;
    let text = console.ok(&Command::Chunk { offset: 0, data: &base64(&bytes[..half]) })?;
    ensure!(ChunkReply::parse(&text)? == ChunkReply { received: half, total: bytes.len() });
    ensure!(console.refusal(&Command::Draw { scene: "rings", method: None })? == unknown("rings"));
    let gap = Command::Chunk { offset: half + 1, data: &base64(&bytes[half + 1..]) };
    let refused = console.refusal(&gap)?;
    ensure!(matches!(ErrorReply::parse(&refused)?, ErrorReply::ChunkOutOfPlace { .. }), "{refused}");

    // Damaged: the CRC-32 declared is not the bytes'. Dropped whole.
    console.ok(&Command::Upload { name: "rings", bytes: bytes.len(), memory, crc: crc ^ 0x10 })?;
    let refused = console.refusal(&Command::Chunk { offset: 0, data: &base64(&bytes) })?;
    ensure!(ErrorReply::parse(&refused)? == ErrorReply::UploadDamaged { declared: crc ^ 0x10, actual: crc });
    ensure!(console.refusal(&Command::Draw { scene: "rings", method: None })? == unknown("rings"));

    // Nothing of any of them reached the screen, and the kernel serves on.
    let dump = console.dump()?;
    ensure!(dump.pixels.iter().all(|&pixel| pixel == 5), "a refused or dropped upload changed the screen");
    console.draw_scene(&scene, MethodId::Exact)?;
    Ok(())
}
