//! What a command draws: `--scene NAME|FILE` or `--svg FILE` (with the
//! import's options), the arguments every command that draws a scene
//! flattens into its own, and their resolution to the harness's
//! [`SceneSource`] or [`SceneFile`]. An SVG is imported here, before
//! anything boots, and its notes are printed; the harness never sees SVG.

use std::path::{Path, PathBuf};

use anyhow::{bail, Result};
use clap::Args;
use harness::client::pack_for_upload;
use harness::sources::{SceneFile, SceneSource};
use svg_import::{import_file, Options, PaletteChoice, ViewBox};

/// `--scene NAME|FILE` or `--svg FILE`, not both.
#[derive(Args, Debug)]
pub struct SceneArgs {
    /// A scene by name (for `run`, an entry of the show; for the others, a
    /// built-in page) or the path of a scene file.
    #[arg(long, value_name = "NAME|FILE", conflicts_with = "svg")]
    pub scene: Option<String>,
    /// An SVG drawing, imported as a scene file would be read
    /// (docs/scenes.md, "From SVG").
    #[arg(long, value_name = "FILE")]
    pub svg: Option<PathBuf>,
    #[command(flatten)]
    pub import: SvgArgs,
}

/// How `--svg` is imported.
#[derive(Args, Debug)]
pub struct SvgArgs {
    /// The most a flattened curve or stroke may stray from the SVG's, in
    /// screen pixels, no finer than 1/256 [default: 0.1].
    #[arg(long, value_name = "PX")]
    pub tolerance: Option<f64>,
    /// The part of the drawing fitted to the 320x200 screen, in the SVG's
    /// user units (default: its viewBox, or else its width and height).
    #[arg(long, value_name = "X,Y,W,H")]
    pub view_box: Option<ViewBox>,
    /// `own`: a palette of the scene's own, the SVG's colours at 6 bits a
    /// channel; `vga`: the nearest entries of the VGA default palette
    /// [default: own].
    #[arg(long, value_name = "own|vga")]
    pub palette: Option<PaletteChoice>,
}

impl SvgArgs {
    /// The import's options, the defaults where none is given (left to
    /// here, so that one given without `--svg` can be told from none).
    pub fn options(&self) -> Options {
        let defaults = Options::default();
        Options {
            tolerance: self.tolerance.unwrap_or(defaults.tolerance),
            view_box: self.view_box,
            palette: self.palette.unwrap_or(defaults.palette),
        }
    }

    /// The SVG at `path` imported as a scene file named after it, its
    /// notes printed (`xtask: note: ...`).
    pub fn import(&self, path: &Path) -> Result<SceneFile> {
        let imported = import_file(path, &self.options())?;
        for note in &imported.notes {
            eprintln!("xtask: note: {note}");
        }
        Ok(SceneFile { path: path.to_path_buf(), scene: imported.scene })
    }
}

impl SceneArgs {
    /// The scene asked for: the SVG imported, or the built-in scene or
    /// scene file `--scene` names; an error when neither is given.
    pub fn source(&self) -> Result<SceneSource> {
        match (&self.scene, self.svg_file()?) {
            (_, Some(file)) => Ok(SceneSource::File(file)),
            (Some(name), None) => SceneSource::find(name),
            (None, None) => bail!("no scene: give --scene NAME|FILE or --svg FILE"),
        }
    }

    /// The scene asked for, if one is: as [`SceneArgs::source`], but `None`
    /// when neither `--scene` nor `--svg` is given.
    pub fn optional_source(&self) -> Result<Option<SceneSource>> {
        match (&self.scene, &self.svg) {
            (None, None) => self.svg_file().map(|_| None),
            _ => self.source().map(Some),
        }
    }

    /// The SVG imported, if `--svg` is given; an error if the import's
    /// options are given without it.
    pub fn svg_file(&self) -> Result<Option<SceneFile>> {
        let SvgArgs { tolerance, view_box, palette } = &self.import;
        match &self.svg {
            Some(path) => self.import.import(path).map(Some),
            None if tolerance.is_some() || view_box.is_some() || palette.is_some() => {
                bail!("--tolerance, --view-box and --palette go with --svg")
            }
            None => Ok(None),
        }
    }
}

/// Scene files and SVGs a command takes several of (`--scene FILE` and
/// `--svg FILE`, each as often as wanted), with the import's options.
#[derive(Args, Debug)]
pub struct SceneFiles {
    /// A scene file (may be given several times).
    #[arg(long, value_name = "FILE")]
    pub scene: Vec<PathBuf>,
    /// An SVG drawing, imported as `--svg` is elsewhere (may be given
    /// several times).
    #[arg(long, value_name = "FILE")]
    pub svg: Vec<PathBuf>,
    #[command(flatten)]
    pub import: SvgArgs,
}

impl SceneFiles {
    /// Every file read (the scene files, then the SVGs imported, notes
    /// printed), each checked against the kernel's budget for an upload:
    /// all of it before anything boots or opens a line.
    pub fn read(&self) -> Result<Vec<SceneFile>> {
        let SvgArgs { tolerance, view_box, palette } = &self.import;
        if self.svg.is_empty() && (tolerance.is_some() || view_box.is_some() || palette.is_some()) {
            bail!("--tolerance, --view-box and --palette go with --svg");
        }
        let files = self.scene.iter().map(|path| SceneFile::read(path));
        let svgs = self.svg.iter().map(|path| self.import.import(path));
        let files = files.chain(svgs).collect::<Result<Vec<SceneFile>>>()?;
        for file in &files {
            pack_for_upload(&file.scene)?;
        }
        Ok(files)
    }
}

/// The SVG `name` of the import's test drawings (`xtask/svg-import/tests/svg/`).
#[cfg(test)]
pub fn svg_fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("svg-import/tests/svg").join(name)
}
