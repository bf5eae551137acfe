//! The host side of every comparison: scenes and show entries drawn with
//! the same `raster` code the kernel runs (found by name in
//! `sources.rs`).

use raster::{Framebuffer, MethodId, SCREEN};
use scenes::show::{self, Entry, Stage};
use scenes::Scene;

use super::Image;

/// `scene` drawn with `method` on a black 320x200 screen, as an indexed
/// image in the scene's palette (the VGA default with the scene's entries
/// over it, which the kernel loads to draw it).
pub fn render(scene: &Scene, method: MethodId) -> Image {
    let mut framebuffer = Framebuffer::new(SCREEN);
    scene.draw(method, &mut framebuffer);
    Image::from_dac(SCREEN.width as u32, SCREEN.height as u32, framebuffer.pixels().to_vec(), &scene.dac())
        .expect("a framebuffer has width x height pixels")
}

/// Frame `frame` of show entry `entry` drawn with `method` and labelled
/// with `cycles` (the kernel's measurement, from its `SHOW` reply), as an
/// indexed image with the show's palette: what `SHOW` puts on the screen.
pub fn render_show(entry: &Entry, frame: u32, method: MethodId, cycles: u64) -> Image {
    let mut stage = Stage::new();
    stage.draw(entry, frame, method);
    stage.label(entry, frame, method, cycles);
    Image::from_dac(SCREEN.width as u32, SCREEN.height as u32, stage.pixels().to_vec(), &show::PALETTE)
        .expect("a stage has width x height pixels")
}

#[cfg(test)]
mod tests {
    use anyhow::Result;

    use super::*;
    use crate::picture::Pixels;
    use crate::sources::{builtin_scene, show_entry, SceneSource};

    #[test]
    fn unknown_names_list_the_valid_ones() {
        let error = format!("{:#}", builtin_scene("nope").unwrap_err());
        assert!(error.starts_with("unknown scene `nope`; valid scenes: abrash38-1, abrash38-2, "), "{error}");
        assert!(error.ends_with(", wgt-triangle, world"), "{error}");
        let error = format!("{:#}", show_entry("nope").unwrap_err());
        assert!(error.starts_with("unknown show entry `nope`; valid entries: abrash38-1, "), "{error}");
        assert!(error.ends_with(", race, world"), "{error}");
        let Err(error) = SceneSource::find("nope") else { panic!("`nope` is a scene") };
        let error = format!("{error:#}");
        assert!(
            error.starts_with("`nope` is neither a built-in scene nor a scene file; valid scenes: abrash38-1,"),
            "{error}"
        );
    }

    #[test]
    fn a_show_frame_is_drawn_in_the_show_palette() {
        let entry = show_entry("abrash38-1").unwrap();
        let shown = render_show(entry, 0, entry.method_at(0), 1234);
        let Pixels::Indexed { indices, palette } = shown.pixels() else { panic!("a show frame is indexed") };
        let expected: Vec<[u8; 3]> = show::PALETTE.iter().map(|rgb| rgb.map(scenes::palette::c6_to_8)).collect();
        assert_eq!(palette, &expected);
        assert!(indices.iter().any(|&i| i != 0), "the page is drawn");
    }

    /// `text` written to a scene file of its own, found as a source.
    fn from_file(tag: &str, text: &str) -> Result<SceneSource> {
        let path = std::env::temp_dir().join(format!("harness-render-{}-{tag}.scene", std::process::id()));
        std::fs::write(&path, text).unwrap();
        let source = SceneSource::find(path.to_str().unwrap());
        std::fs::remove_file(&path).unwrap();
        source
    }

    #[test]
    fn scene_file_errors_name_the_line() {
        let Err(error) = from_file("bad", "clear 1\n# fine\npoly color=300 0,0 1,0 0,1\n") else { panic!("parsed") };
        let error = format!("{error:#}");
        assert!(error.ends_with("bad scene file: line 3: bad colour `300` (expected 0-255)"), "{error}");
    }

    #[test]
    fn a_scene_file_renders_its_clear_colour() {
        let scene = from_file("ok", "clear 4\n").unwrap().scene();
        let image = render(&scene, scene.method);
        assert_eq!(image.color(0), [168, 0, 0]);
        assert_eq!(image.pixel_count(), 64_000);
    }

    #[test]
    fn a_scene_file_renders_in_its_own_palette() {
        let scene = from_file("palette", "clear 4\npalette 4 1,2,63\n").unwrap().scene();
        let image = render(&scene, scene.method);
        assert_eq!(image.color(0), [7, 8, 255]);
    }
}
