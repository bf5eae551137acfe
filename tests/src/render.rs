//! The host side of every comparison: scenes and methods looked up by name
//! (errors list the valid names), drawn with the same `raster` code the
//! kernel runs.

use std::path::Path;

use anyhow::{anyhow, bail, Context, Result};
use raster::methods;
use raster::palette::VGA_DEFAULT;
use raster::{scene_file, scenes, Framebuffer, Method, Scene, SCREEN};

use crate::picture::Image;

/// The method called `name`, or for `None` the scene's own (the method its
/// source uses; `exact` for scene files).
pub fn method_for(scene: &Scene, name: Option<&str>) -> Result<&'static dyn Method> {
    let Some(name) = name else { return Ok(scene.method()) };
    methods::by_name(name).with_context(|| {
        let valid: Vec<&str> = methods::ALL.iter().map(|m| m.info().name).collect();
        format!("unknown method `{name}`; valid methods: {}", valid.join(", "))
    })
}

/// The built-in scene called `name`.
pub fn builtin_scene(name: &str) -> Result<Scene> {
    scenes::by_name(name).with_context(|| format!("unknown scene `{name}`; valid scenes: {}", scenes::NAMES.join(", ")))
}

/// A built-in scene by name or, failing that, a scene file by path.
pub fn scene_named_or_file(name_or_path: &str) -> Result<Scene> {
    if let Some(scene) = scenes::by_name(name_or_path) {
        return Ok(scene);
    }
    let path = Path::new(name_or_path);
    if !path.is_file() {
        bail!(
            "`{name_or_path}` is neither a built-in scene nor a scene file; valid scenes: {}, or the path of a scene file",
            scenes::NAMES.join(", ")
        );
    }
    let text =
        std::fs::read_to_string(path).with_context(|| format!("failed to read scene file {}", path.display()))?;
    let name = path.file_stem().map_or_else(|| name_or_path.to_string(), |s| s.to_string_lossy().into_owned());
    scene_file::parse(&name, &text).map_err(|error| anyhow!("{}: bad scene file: {error}", path.display()))
}

/// `scene` drawn with `method` on a black 320x200 screen, as an indexed
/// image with the VGA default palette (the one the kernel loads).
pub fn render(scene: &Scene, method: &dyn Method) -> Image {
    let mut framebuffer = Framebuffer::new(SCREEN);
    scene.draw(method, &mut framebuffer);
    Image::from_dac(SCREEN.width as u32, SCREEN.height as u32, framebuffer.pixels().to_vec(), &VGA_DEFAULT)
        .expect("a framebuffer has width x height pixels")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unknown_names_list_the_valid_ones() {
        let Err(error) = method_for(&Scene::default(), Some("nope")) else { panic!("`nope` is a method") };
        let error = format!("{error:#}");
        assert!(error.starts_with("unknown method `nope`; valid methods: abrash_float"), "{error}");
        let error = format!("{:#}", builtin_scene("nope").unwrap_err());
        assert_eq!(error, format!("unknown scene `nope`; valid scenes: {}", scenes::NAMES.join(", ")));
        let error = format!("{:#}", scene_named_or_file("nope").unwrap_err());
        assert!(
            error.starts_with("`nope` is neither a built-in scene nor a scene file; valid scenes: abrash38-1,"),
            "{error}"
        );
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
        let image = render(&scene, scene.method());
        assert_eq!(image.color(0), [168, 0, 0]);
        assert_eq!(image.pixel_count(), 64_000);
    }
}
