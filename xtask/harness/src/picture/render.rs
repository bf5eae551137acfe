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
    use super::*;
    use crate::picture::Pixels;
    use crate::sources::show_entry;
    use crate::sources::tests::from_file;

    #[test]
    fn a_show_frame_is_drawn_in_the_show_palette() {
        let entry = show_entry("abrash38-1").unwrap();
        let shown = render_show(entry, 0, entry.method_at(0), 1234);
        let Pixels::Indexed { indices, palette } = shown.pixels() else { panic!("a show frame is indexed") };
        let expected: Vec<[u8; 3]> = show::PALETTE.iter().map(|rgb| rgb.map(scenes::palette::c6_to_8)).collect();
        assert_eq!(palette, &expected);
        assert!(indices.iter().any(|&i| i != 0), "the page is drawn");
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
