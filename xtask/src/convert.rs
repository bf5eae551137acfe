//! `cargo xtask convert`: an SVG written as a scene file.

use std::fs::Permissions;
use std::io::Write;
use std::os::unix::fs::PermissionsExt;
use std::path::Path;

use anyhow::{Context, Result};
use scenes::{file, Scene};

use crate::opt::ConvertOpt;

pub fn convert(opt: &ConvertOpt) -> Result<()> {
    let scene = opt.import.import(&opt.svg)?.scene;
    write_atomically(&opt.out, &file::write(&scene))?;
    eprintln!("xtask: {}", summary(&scene));
    println!("{}", opt.out.display());
    Ok(())
}

/// Writes `text` to a temporary file beside `path`, then renames it to
/// `path`: `path` is the whole text or untouched. Creates the folder.
fn write_atomically(path: &Path, text: &str) -> Result<()> {
    let dir = match path.parent() {
        Some(dir) if !dir.as_os_str().is_empty() => dir,
        _ => Path::new("."),
    };
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let mut temporary = tempfile::Builder::new()
        .prefix(".convert-")
        .suffix(".scene.partial")
        // What `File::create` asks for: the umask decides.
        .permissions(Permissions::from_mode(0o666))
        .tempfile_in(dir)
        .with_context(|| format!("cannot write in {}", dir.display()))?;
    temporary.write_all(text.as_bytes()).with_context(|| format!("cannot write beside {}", path.display()))?;
    temporary.persist(path).with_context(|| format!("cannot write {}", path.display()))?;
    Ok(())
}

/// The scene's size: polygons, their contours and vertices, the
/// palette's entries.
fn summary(scene: &Scene) -> String {
    let polygons: Vec<&raster::Polygon> = scene.polygons().collect();
    let contours: usize = polygons.iter().map(|polygon| polygon.contours.len()).sum();
    let vertices: usize = polygons.iter().map(|polygon| polygon.vertex_count()).sum();
    format!(
        "{}: {} polygons, {contours} contours, {vertices} vertices, {} palette entries",
        scene.name,
        polygons.len(),
        scene.palette.len()
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::opt::{parse_command, Action};
    use crate::source::svg_fixture;

    /// `cargo xtask convert --svg SVG ARGS --out OUT`.
    fn convert_svg(svg: &str, args: &[&str], out: &Path) -> Result<()> {
        let svg = svg_fixture(svg);
        let head = ["--svg", svg.to_str().unwrap(), "--out", out.to_str().unwrap()];
        match parse_command("convert", &[&head[..], args].concat())? {
            Action::Convert(opt) => convert(&opt),
            other => panic!("parsed as {other:?}"),
        }
    }

    #[test]
    fn the_scene_file_written_reads_back_as_the_import() -> Result<()> {
        let dir = tempfile::tempdir()?;
        let out = dir.path().join("new/holes.scene");
        convert_svg("holes.svg", &["--tolerance", "0.25"], &out)?;
        let text = std::fs::read_to_string(&out)?;
        let options = svg_import::Options { tolerance: 0.25, ..svg_import::Options::default() };
        let imported = svg_import::import_file(&svg_fixture("holes.svg"), &options)?;
        assert_eq!(file::parse("holes", &text).unwrap(), imported.scene);
        assert!(text.starts_with("palette 1 55,40,8 47,8,8 8,24,47\nclear 0\npoly color=1 rule=nonzero "), "{text}");
        assert_eq!(summary(&imported.scene), "holes: 3 polygons, 8 contours, 128 vertices, 3 palette entries");
        // Made as `File::create` makes a file, not private as a temporary one.
        let created = dir.path().join("created");
        std::fs::File::create(&created)?;
        let mode = |path: &Path| std::fs::metadata(path).map(|m| m.permissions().mode());
        assert_eq!(mode(&out)?, mode(&created)?);
        // In the VGA palette: no palette line.
        convert_svg("holes.svg", &["--palette", "vga"], &out)?;
        assert!(std::fs::read_to_string(&out)?.starts_with("clear 0\npoly color=43 rule=nonzero "));
        Ok(())
    }

    #[test]
    fn a_bad_svg_writes_nothing_and_leaves_an_old_file_as_it_was() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("out.scene");
        for svg in ["bad/text.svg", "bad/malformed.svg", "bad/huge.svg", "bad/empty.svg", "no-such.svg"] {
            let error = format!("{:#}", convert_svg(svg, &[], &out).unwrap_err());
            assert!(error.contains(&format!("{}", svg_fixture(svg).display())), "{svg}: {error}");
            assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0, "{svg} wrote something");
        }
        std::fs::write(&out, "clear 3\n").unwrap();
        assert!(convert_svg("bad/nan.svg", &[], &out).is_err());
        assert_eq!(std::fs::read_to_string(&out).unwrap(), "clear 3\n");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1, "no temporary file is left");
    }

    /// The show's world (`kernel/scenes/art/`) is the committed SVG as
    /// `convert --palette vga` writes it today: the kernel's page cannot
    /// drift from its source, nor the import from what the kernel draws.
    #[test]
    fn the_world_the_kernel_draws_is_its_svg_converted() -> Result<()> {
        let art = Path::new(env!("CARGO_MANIFEST_DIR")).join("../kernel/scenes/art");
        let dir = tempfile::tempdir()?;
        let out = dir.path().join("world.scene");
        let svg = art.join("world.svg");
        let args = ["--svg", svg.to_str().unwrap(), "--palette", "vga", "--out", out.to_str().unwrap()];
        let Action::Convert(opt) = parse_command("convert", &args)? else { panic!("not convert") };
        convert(&opt)?;
        let committed = std::fs::read_to_string(art.join("world.scene"))?;
        assert!(
            std::fs::read_to_string(&out)? == committed,
            "kernel/scenes/art/world.scene is not world.svg converted"
        );
        Ok(())
    }
}
