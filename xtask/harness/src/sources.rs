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

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

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

    /// `text` written to a scene file of its own, found as a source.
    pub(crate) fn from_file(tag: &str, text: &str) -> Result<SceneSource> {
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
}
