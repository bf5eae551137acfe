//! Scenes and show entries named on the command line or in a test,
//! looked up by name (errors list the valid names): a built-in page, a
//! scene file read and parsed whole, a show entry.

use std::path::{Path, PathBuf};

use anyhow::{anyhow, bail, Context, Result};
use scenes::builtin::{self, BuiltinPage};
use scenes::show::{self, Entry, ENTRIES_IN_ORDER};
use scenes::{file, Scene};

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
