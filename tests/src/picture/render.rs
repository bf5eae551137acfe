//! The host side of every comparison: scenes, show entries and methods
//! looked up by name (errors list the valid names), drawn with the same
//! `raster` code the kernel runs.

use std::path::{Path, PathBuf};

use anyhow::{anyhow, bail, ensure, Context, Result};
use protocol::{Command, MAX_LINE};
use raster::{Framebuffer, MethodId, SCREEN};
use scenes::builtin::{self, Builtin};
use scenes::palette::VGA_DEFAULT;
use scenes::show::{self, Entry, Stage, ENTRIES_IN_ORDER};
use scenes::{file, Op, Scene};

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
    Builtin(&'static Builtin),
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

/// A scene file, read and parsed, with each operation's line kept so the
/// kernel can be sent the same operations and a problem can name its line.
#[derive(Clone)]
pub struct SceneFile {
    pub path: PathBuf,
    pub scene: Scene,
    /// Per operation: its line and what a protocol command carries for it
    /// (the colour of a `clear`, the text after `poly`).
    lines: Vec<(usize, String)>,
}

impl SceneFile {
    /// Reads and parses the scene file at `path`; a bad file is an error
    /// naming its line.
    pub fn read(path: &Path) -> Result<Self> {
        let text =
            std::fs::read_to_string(path).with_context(|| format!("failed to read scene file {}", path.display()))?;
        let name = path.file_stem().map_or_else(|| "scene".to_string(), |s| s.to_string_lossy().into_owned());
        let bad = |error: file::SceneFileError| anyhow!("{}: bad scene file: {error}", path.display());
        let parsed = file::parse_lines(&text).map_err(bad)?;
        let lines = parsed.iter().map(|line| (line.number, line.spec.to_string())).collect();
        let ops = parsed.into_iter().map(|line| line.op).collect();
        Ok(Self { path: path.to_path_buf(), scene: Scene { name, ops, method: MethodId::Exact }, lines })
    }

    /// The protocol commands that draw the file with `method`, in order,
    /// each with its line. Fails, naming the line, if a polygon does not
    /// fit in one command line ([`MAX_LINE`] bytes): nothing is sent then,
    /// so nothing is drawn half.
    pub fn commands(&self, method: MethodId) -> Result<Vec<(usize, Command<'_>)>> {
        let commands: Vec<(usize, Command<'_>)> = self
            .scene
            .ops
            .iter()
            .zip(&self.lines)
            .map(|(op, (line, spec))| match op {
                Op::Clear(color) => (*line, Command::Clear(*color)),
                Op::Fill(_) => (*line, Command::Poly { method, spec }),
            })
            .collect();
        for (line, command) in &commands {
            let len = command.to_string().len();
            ensure!(
                len <= MAX_LINE,
                "{}:{line}: this polygon makes a POLY command of {len} bytes; the kernel takes at most {MAX_LINE} \
                 (split it into several `poly` lines, or use fewer digits)",
                self.path.display()
            );
        }
        Ok(commands)
    }
}

/// `scene` drawn with `method` on a black 320x200 screen, as an indexed
/// image with the VGA default palette (the one the kernel loads).
pub fn render(scene: &Scene, method: MethodId) -> Image {
    let mut framebuffer = Framebuffer::new(SCREEN);
    scene.draw(method, &mut framebuffer);
    Image::from_dac(SCREEN.width as u32, SCREEN.height as u32, framebuffer.pixels().to_vec(), &VGA_DEFAULT)
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
        assert!(error.ends_with(", wgt-triangle"), "{error}");
        let error = format!("{:#}", show_entry("nope").unwrap_err());
        assert!(error.starts_with("unknown show entry `nope`; valid entries: abrash38-1, "), "{error}");
        assert!(error.ends_with(", race"), "{error}");
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
    fn a_scene_file_becomes_the_commands_that_draw_it_each_with_its_line() {
        let text = "clear 2\n# a hole\npoly color=5 0,0 9,0 9,9 0,9 | 2,2 2,7 7,7 # square\n\npoly color=1 rule=nonzero 1,1 3.5,1 1,3\n";
        let SceneSource::File(file) = from_file("cmds", text).unwrap() else { panic!("not a file") };
        let lines: Vec<(usize, String)> = file
            .commands(MethodId::Wgt)
            .unwrap()
            .into_iter()
            .map(|(line, command)| (line, command.to_string()))
            .collect();
        assert_eq!(
            lines,
            [
                (1, "CLEAR 2".to_string()),
                (3, "POLY wgt color=5 0,0 9,0 9,9 0,9 | 2,2 2,7 7,7".to_string()),
                (5, "POLY wgt color=1 rule=nonzero 1,1 3.5,1 1,3".to_string()),
            ]
        );
    }

    #[test]
    fn a_polygon_too_long_for_one_command_is_refused_naming_its_line() {
        let vertices: Vec<String> = (0..700).map(|i| format!("{}.5,{}", i % 320, i % 200)).collect();
        let text = format!("clear 0\npoly color=1 0,0 1,0 0,1\npoly color=3 {}\n", vertices.join(" "));
        let SceneSource::File(file) = from_file("long", &text).unwrap() else { panic!("not a file") };
        let error = format!("{:#}", file.commands(MethodId::Exact).unwrap_err());
        assert!(error.contains(".scene:3: this polygon makes a POLY command of "), "{error}");
        assert!(error.contains("the kernel takes at most 4096"), "{error}");
    }
}
