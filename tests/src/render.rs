//! The host side of every comparison: scenes, show entries and methods
//! looked up by name (errors list the valid names), drawn with the same
//! `raster` code the kernel runs.

use std::path::Path;

use anyhow::{anyhow, bail, Context, Result};
use raster::{Framebuffer, Method, SCREEN};
use scenes::palette::VGA_DEFAULT;
use scenes::show::{self, Entry, Stage, ENTRIES_IN_ORDER};
use scenes::{builtin, file, Scene};

use crate::picture::Image;

/// The show entry called `name`.
pub fn show_entry(name: &str) -> Result<&'static Entry> {
    show::entry(name).with_context(|| {
        let valid: Vec<&str> = ENTRIES_IN_ORDER.iter().map(|e| e.name).collect();
        format!("unknown show entry `{name}`; valid entries: {}", valid.join(", "))
    })
}

/// The names of the built-in scenes, `, `-separated, for error messages.
fn builtin_names() -> String {
    builtin::ALL.map(|page| page.name).join(", ")
}

/// The built-in scene called `name`.
pub fn builtin_scene(name: &str) -> Result<Scene> {
    builtin::scene(name).with_context(|| format!("unknown scene `{name}`; valid scenes: {}", builtin_names()))
}

/// A built-in scene by name or, failing that, a scene file by path.
pub fn scene_named_or_file(name_or_path: &str) -> Result<Scene> {
    if let Some(scene) = builtin::scene(name_or_path) {
        return Ok(scene);
    }
    let path = Path::new(name_or_path);
    if !path.is_file() {
        bail!(
            "`{name_or_path}` is neither a built-in scene nor a scene file; valid scenes: {}, or the path of a scene file",
            builtin_names()
        );
    }
    let text =
        std::fs::read_to_string(path).with_context(|| format!("failed to read scene file {}", path.display()))?;
    let name = path.file_stem().map_or_else(|| name_or_path.to_string(), |s| s.to_string_lossy().into_owned());
    file::parse(&name, &text).map_err(|error| anyhow!("{}: bad scene file: {error}", path.display()))
}

/// `scene` drawn with `method` on a black 320x200 screen, as an indexed
/// image with the VGA default palette (the one the kernel loads).
pub fn render(scene: &Scene, method: &dyn Method) -> Image {
    let mut framebuffer = Framebuffer::new(SCREEN);
    scene.draw(method, &mut framebuffer);
    Image::from_dac(SCREEN.width as u32, SCREEN.height as u32, framebuffer.pixels().to_vec(), &VGA_DEFAULT)
        .expect("a framebuffer has width x height pixels")
}

/// Frame `frame` of show entry `entry` drawn with `method` and labelled
/// with `cycles` (the kernel's measurement, from its `SHOW` reply), as an
/// indexed image with the show's palette: what `SHOW` puts on the screen.
pub fn render_show(entry: &Entry, frame: u32, method: &dyn Method, cycles: u64) -> Image {
    let mut stage = Stage::new();
    stage.draw(entry, frame, method);
    stage.label(entry, frame, method, cycles);
    Image::from_dac(SCREEN.width as u32, SCREEN.height as u32, stage.pixels().to_vec(), &show::PALETTE)
        .expect("a stage has width x height pixels")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::picture::Pixels;

    #[test]
    fn unknown_names_list_the_valid_ones() {
        let error = format!("{:#}", builtin_scene("nope").unwrap_err());
        assert!(error.starts_with("unknown scene `nope`; valid scenes: abrash38-1, abrash38-2, "), "{error}");
        assert!(error.ends_with(", wgt-triangle"), "{error}");
        let error = format!("{:#}", show_entry("nope").unwrap_err());
        assert!(error.starts_with("unknown show entry `nope`; valid entries: abrash38-1, "), "{error}");
        assert!(error.ends_with(", race"), "{error}");
        let error = format!("{:#}", scene_named_or_file("nope").unwrap_err());
        assert!(
            error.starts_with("`nope` is neither a built-in scene nor a scene file; valid scenes: abrash38-1,"),
            "{error}"
        );
    }

    #[test]
    fn a_show_frame_is_drawn_in_the_show_palette() {
        let entry = show_entry("abrash38-1").unwrap();
        let shown = render_show(entry, 0, entry.method_at(0).method(), 1234);
        let Pixels::Indexed { indices, palette } = shown.pixels() else { panic!("a show frame is indexed") };
        let expected: Vec<[u8; 3]> = show::PALETTE.iter().map(|rgb| rgb.map(scenes::palette::c6_to_8)).collect();
        assert_eq!(palette, &expected);
        assert!(indices.iter().any(|&i| i != 0), "the page is drawn");
    }

    #[test]
    fn scene_file_errors_name_the_line() {
        let path = std::env::temp_dir().join(format!("harness-render-{}.scene", std::process::id()));
        std::fs::write(&path, "clear 1\n# fine\npoly color=300 0,0 1,0 0,1\n").unwrap();
        let error = format!("{:#}", scene_named_or_file(path.to_str().unwrap()).unwrap_err());
        std::fs::remove_file(&path).unwrap();
        assert!(error.ends_with("bad scene file: line 3: bad colour `300` (expected 0-255)"), "{error}");
    }

    #[test]
    fn a_scene_file_renders_its_clear_colour() {
        let path = std::env::temp_dir().join(format!("harness-render-{}-ok.scene", std::process::id()));
        std::fs::write(&path, "clear 4\n").unwrap();
        let scene = scene_named_or_file(path.to_str().unwrap()).unwrap();
        std::fs::remove_file(&path).unwrap();
        let image = render(&scene, scene.method.method());
        assert_eq!(image.color(0), [168, 0, 0]);
        assert_eq!(image.pixel_count(), 64_000);
    }
}
