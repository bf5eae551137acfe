//! The host side of every comparison: scenes, show entries and methods
//! looked up by name (errors list the valid names), drawn with the same
//! `raster` code the kernel runs.

use std::path::{Path, PathBuf};

use anyhow::{anyhow, bail, Context, Result};
use raster::{Framebuffer, MethodId, SCREEN};
use scenes::builtin::{self, BuiltinPage};
use scenes::show::{self, Entry, Stage, ENTRIES_IN_ORDER};
use scenes::{file, Scene};

use super::Image;

/// The show entry called `name`.
pub fn show_entry(name: &str) -> Result<&'static Entry> {
    show::entry(name).with_context(|| format!("unknown show entry `{name}`; valid entries: {}", entry_names()))
}

/// The names of the show's entries, in demo order, `, `-separated, for
/// error messages.
pub fn entry_names() -> String {
    ENTRIES_IN_ORDER.iter().map(|entry| entry.name).collect::<Vec<_>>().join(", ")
}

/// The names of the built-in scenes, `, `-separated, for error messages.
fn builtin_names() -> String {
    builtin::ALL.map(|page| page.name).join(", ")
}

/// The built-in scene called `name`.
pub fn builtin_scene(name: &str) -> Result<Scene> {
    builtin::scene(name).with_context(|| format!("unknown scene `{name}`; valid scenes: {}", builtin_names()))
}

/// A scene named on the command line: a built-in page, or a scene file.
pub enum SceneSource {
    Builtin(&'static BuiltinPage),
    File(SceneFile),
}

impl SceneSource {
    /// The built-in scene called `name_or_path` or, failing that, the scene
    /// file at that path, read and parsed whole: a bad file is an error
    /// naming its line.
    pub fn find(name_or_path: &str) -> Result<Self> {
        if let Some(page) = builtin::named(name_or_path) {
            return Ok(SceneSource::Builtin(page));
        }
        let path = Path::new(name_or_path);
        if !path.is_file() {
            bail!(
                "`{name_or_path}` is neither a built-in scene nor a scene file; valid scenes: {}, or the path of a scene file",
                builtin_names()
            );
        }
        SceneFile::read(path).map(SceneSource::File)
    }

    /// The scene, built or parsed.
    pub fn scene(&self) -> Scene {
        match self {
            SceneSource::Builtin(page) => page.scene(),
            SceneSource::File(file) => file.scene.clone(),
        }
    }

    /// A name for files and messages: the page's, or the file's stem.
    pub fn name(&self) -> &str {
        match self {
            SceneSource::Builtin(page) => page.name,
            SceneSource::File(file) => &file.scene.name,
        }
    }
}

/// A scene file, read and parsed whole, with where it came from.
#[derive(Clone)]
pub struct SceneFile {
    pub path: PathBuf,
    pub scene: Scene,
}

impl SceneFile {
    /// Reads and parses the scene file at `path`; a bad file is an error
    /// naming its line.
    pub fn read(path: &Path) -> Result<Self> {
        let text =
            std::fs::read_to_string(path).with_context(|| format!("failed to read scene file {}", path.display()))?;
        let name = path.file_stem().map_or_else(|| "scene".to_string(), |s| s.to_string_lossy().into_owned());
        let scene =
            file::parse(&name, &text).map_err(|error| anyhow!("{}: bad scene file: {error}", path.display()))?;
        Ok(Self { path: path.to_path_buf(), scene })
    }
}

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
