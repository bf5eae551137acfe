//! `cargo xtask dump`: the kernel's picture of a scene and QEMU's.

use anyhow::Result;
use harness::checks::{screen_matches_dump, source_matches_host_render};
use harness::client::{pack_for_upload, transfer_time, Uploaded, BAUD};
use harness::sources::SceneSource;
use harness::{Qemu, QemuOptions};
use protocol::Command;
use scenes::{file, Op, Scene, FILE_METHOD};

use crate::opt::DumpOpt;

pub fn dump(opt: &DumpOpt) -> Result<()> {
    // Check the scene (a whole scene file, every line, or a whole SVG)
    // before spending a boot.
    let source = opt.drawing.source()?;
    let method = source.scene().method_or(opt.method);
    if let SceneSource::File(file) = &source {
        pack_for_upload(&file.scene)?;
    }
    let mut qemu = Qemu::boot(QemuOptions::default())?;
    let dump = source_matches_host_render(&mut qemu.console, &source, method)?;
    if let Some(uploaded) = qemu.console.last_upload() {
        eprintln!("xtask: {}", upload_cost(uploaded, &source.scene()));
    }
    eprintln!("xtask: the kernel's dump equals the host render of {} with {method}", source.name());
    let screen = qemu.screendump()?;
    let dump_path = opt.out.join(format!("{}.png", source.name()));
    let screen_path = opt.out.join(format!("{}.screen.png", source.name()));
    dump.image().write_png(&dump_path)?;
    screen.write_png(&screen_path)?;
    println!("{}", dump_path.display());
    println!("{}", screen_path.display());
    let video = qemu.ready.video;
    qemu.quit()?;
    screen_matches_dump(source.name(), &dump, &screen, &video)?;
    eprintln!("xtask: QEMU's screendump agrees pixel for pixel (each pixel a 2x2 block on QEMU's screen)");
    Ok(())
}

/// What uploading `scene` cost on the line, in bytes and in seconds at
/// the kernel's 115,200 baud (10 bits a byte), and per 1,000 vertices;
/// beside it, what the same scene costs as text, one `CLEAR` or `POLY`
/// command line per operation (the way a person can type it, a polygon
/// that fits in one line).
fn upload_cost(uploaded: &Uploaded, scene: &Scene) -> String {
    let vertices: usize = scene.polygons().map(raster::Polygon::vertex_count).sum();
    let as_text: usize = scene
        .ops
        .iter()
        .map(|op| match op {
            Op::Clear(color) => Command::Clear(*color).to_string().len() + 1,
            Op::Fill(polygon) => {
                let line = file::poly_line(polygon);
                let spec = line.strip_prefix("poly ").unwrap_or(&line);
                Command::Poly { method: FILE_METHOD, spec }.to_string().len() + 1
            }
        })
        .sum();
    let seconds = |bytes: usize| transfer_time(bytes as u64, BAUD).as_secs_f64();
    let per_1000 = |bytes: usize| bytes * 1000 / vertices.max(1);
    format!(
        "uploaded {vertices} vertices as {} packed bytes: {} bytes of command lines, {:.1} s at {BAUD} baud \
         ({} bytes and {:.2} s per 1,000 vertices); as POLY lines, {as_text} bytes, {:.1} s ({} bytes and {:.2} s \
         per 1,000 vertices)",
        uploaded.packed,
        uploaded.sent,
        seconds(uploaded.sent),
        per_1000(uploaded.sent),
        seconds(per_1000(uploaded.sent)),
        seconds(as_text),
        per_1000(as_text),
        seconds(per_1000(as_text)),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::opt::{parse_command, Action};
    use crate::source::svg_fixture;

    /// `cargo xtask dump ARGS --out DIR`.
    fn dump_with(args: &[&str], out: &std::path::Path) -> Result<()> {
        let out = out.to_str().expect("a UTF-8 temporary path");
        match parse_command("dump", &[args, &["--out", out]].concat())? {
            Action::Dump(opt) => dump(&opt),
            other => panic!("parsed as {other:?}"),
        }
    }

    fn dump_of(scene: &str) -> String {
        format!("{:#}", dump_with(&["--scene", scene], &std::env::temp_dir()).unwrap_err())
    }

    #[test]
    fn a_bad_scene_file_is_refused_whole_before_any_boot_naming_its_line() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("bad.scene");
        std::fs::write(&path, "clear 0\npoly color=2 0,0 10,0 0,10\npoly color=2 0,0 10,0 nan,10\n").unwrap();
        let error = dump_of(path.to_str().unwrap());
        assert!(error.ends_with("bad.scene: bad scene file: line 3: bad vertex `nan` (expected x,y)"), "{error}");
        // 130,000 vertices unpack to 1,040,000 bytes: with their packed
        // bytes, past the kernel's budget of 1 MiB.
        let long: Vec<String> = (0..130_000).map(|i| format!("{}.25,{}.75", i % 300, i % 190)).collect();
        std::fs::write(&path, format!("poly color=2 0,0 10,0 0,10\npoly color=9 {}\n", long.join(" "))).unwrap();
        let error = dump_of(path.to_str().unwrap());
        assert!(error.starts_with("bad is too large for the kernel: "), "{error}");
        assert!(error.contains("where the kernel's budget for an uploaded scene is 1048576 bytes"), "{error}");
    }

    #[test]
    fn an_unknown_scene_lists_the_built_in_ones() {
        let error = dump_of("no-such-scene");
        assert!(error.starts_with("`no-such-scene` is neither a built-in scene nor a scene file"), "{error}");
    }

    #[test]
    fn a_bad_svg_is_refused_before_any_boot_and_nothing_is_written() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("out");
        for (name, expected) in [
            ("bad/text.svg", "not imported: <text id=\"caption\"> at line 4 cannot be imported: text is not drawn"),
            ("bad/huge.svg", "not imported: shape #far reaches 100000000 pixels once fitted to the screen"),
        ] {
            let svg = svg_fixture(name);
            let error = format!("{:#}", dump_with(&["--svg", svg.to_str().unwrap()], &out).unwrap_err());
            assert!(error.contains(expected), "{error}");
            assert!(!out.exists(), "{name}: {} was written", out.display());
        }
    }

    /// Boots QEMU once per SVG: the kernel draws each uploaded, and `dump`
    /// holds its picture to the host render and QEMU's screendump.
    #[test]
    fn svgs_are_drawn_by_the_kernel_as_on_the_host() -> Result<()> {
        let dir = tempfile::tempdir()?;
        let holes = svg_fixture("holes.svg");
        dump_with(&["--svg", holes.to_str().unwrap()], dir.path())?;
        let icon = svg_fixture("icon.svg");
        dump_with(&["--svg", icon.to_str().unwrap(), "--palette", "vga", "--tolerance", "0.5"], dir.path())?;
        let mut written: Vec<String> =
            std::fs::read_dir(dir.path())?.map(|entry| entry.unwrap().file_name().to_string_lossy().into()).collect();
        written.sort();
        assert_eq!(written, ["holes.png", "holes.screen.png", "icon.png", "icon.screen.png"]);
        Ok(())
    }
}
