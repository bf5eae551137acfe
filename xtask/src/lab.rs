//! `cargo xtask lab`: runs the lab crate's binary in release, since the
//! xtask itself is built unoptimised and the lab measures speed, after
//! installing the C libraries its peers build against (libcairo, Allegro
//! 4, SDL2 with SDL2_gfx, GD).
//!
//! The lab is built for the machine it runs on (`-C target-cpu=native`),
//! our code and the Rust peers alike, so that every contender may use the
//! widest stores the CPU has (the framebuffer's span store takes 64-byte
//! blocks where there is AVX2; the host's baseline, SSE2, has 16-byte
//! ones); in a target directory of its own (`target/native`), so that the
//! other builds keep theirs. With `--build v3` it is built for x86-64-v3
//! instead (AVX2 and its companions, no AVX-512: the machines most people
//! have), in `target/x86-64-v3`; with `--build both`, both, one after the
//! other, each measured whole into a folder of its own under the output
//! directory, and the lab then sets the two side by side in that
//! directory's report.md. Cairo is the system's library, built by Debian
//! for the baseline, which picks its SIMD at run time.
//!
//! On x86-64 it is also built with no jump straddling or ending on a
//! 32-byte boundary (LLVM's `-x86-branches-within-32B-boundaries`, the
//! padding Intel advises against the jump-conditional-code erratum of its
//! Skylake-derived cores, whose microcode fix makes such a jump miss the
//! decoded-instruction cache). Without it, where the loops of a fill
//! happen to fall moves their time from one build to the next on those
//! cores with no change to their code, our code's and the Rust peers'
//! alike (docs/lab.md#how-it-is-built-and-timed gives what was measured);
//! with it every build lays its jumps out the same way.
//! Other x86-64 cores get the same padding; the lab has been timed with
//! and without it on Cascade Lake only.
//!
//! With `--scene FILE` or `--svg FILE` the lab measures the polygons of
//! the user's scene instead of the corpus. The scene is read (or the SVG
//! imported by `svg_import`) here, into a [`Scene`], before anything is
//! installed, built or written, so a bad file costs no build; the lab is
//! handed that scene as a scene file of its own ([`scenes::file::write`],
//! which it reads back to the same polygons), with what the report says it
//! came from.

use std::path::{absolute, Path, PathBuf};

use anyhow::{bail, Context, Result};
use harness::sources::SceneFile;
use install::ensure_all;
use install::ensure_lab_art;
use install::ensure_lab_libraries;
use install::run_streaming;
use scenes::Scene;

use crate::opt::{LabBuild, LabOpt};

/// A build of the lab: its name (the report's, and its folder's under the
/// output directory with `--build both`), the CPU it is compiled for and
/// where it is built, apart from the other builds (whose flags differ).
struct Flavour {
    name: &'static str,
    cpu: &'static str,
    target_dir: &'static str,
}

const NATIVE: Flavour = Flavour { name: "native", cpu: "native", target_dir: "target/native" };
const V3: Flavour = Flavour { name: "x86-64-v3", cpu: "x86-64-v3", target_dir: "target/x86-64-v3" };

impl Flavour {
    /// What it is built with: code for its CPU, its jumps kept within
    /// 32-byte blocks on x86-64.
    fn rustflags(&self) -> String {
        let cpu = format!("-C target-cpu={}", self.cpu);
        if cfg!(target_arch = "x86_64") {
            format!("{cpu} -C llvm-args=-x86-branches-within-32B-boundaries")
        } else {
            cpu
        }
    }

    /// `cargo run` of the lab binary built as this flavour, in release.
    fn lab(&self) -> std::process::Command {
        let mut command = install::host();
        command.env("RUSTFLAGS", self.rustflags());
        command.args(["run", "--quiet", "--release", "--package", "lab", "--target-dir", self.target_dir, "--"]);
        command
    }
}

pub fn lab(opt: &LabOpt) -> Result<()> {
    let user = user_scene(opt)?;
    let flavours: &[Flavour] = match opt.build {
        LabBuild::Native => &[NATIVE],
        LabBuild::V3 => &[V3],
        LabBuild::Both => &[NATIVE, V3],
    };
    if opt.build != LabBuild::Native && !cfg!(target_arch = "x86_64") {
        bail!("--build {:?} is a build for x86-64; this host is not one", opt.build);
    }
    // The Cairo peer builds against the system libcairo; the Allegro,
    // SDL2_gfx and GD peers against theirs; the corpus (not a scene) has
    // Debian's flags.
    if user.is_some() {
        ensure_lab_libraries()?;
    } else {
        ensure_all(&[ensure_lab_libraries, ensure_lab_art])?;
    }
    let default_out = if user.is_some() { "target/lab-scene" } else { "target/lab" };
    let out = opt.out.clone().unwrap_or_else(|| PathBuf::from(default_out));
    let out = absolute(&out).with_context(|| format!("bad output directory {}", out.display()))?;
    // Held until the lab is done with the scene file in it.
    let scene_dir = tempfile::tempdir().context("failed to make a folder for the scene")?;
    let scene = match &user {
        Some(user) => Some((handed_over(&user.scene, scene_dir.path())?, &user.from)),
        None => None,
    };
    let both = flavours.len() > 1;
    for flavour in flavours {
        let mut command = flavour.lab();
        if opt.quick {
            command.arg("--quick");
        }
        if let Some(launches) = opt.launches {
            command.arg("--launches").arg(launches.to_string());
        }
        command.arg("--build").arg(flavour.name);
        command.arg("--out").arg(if both { out.join(flavour.name) } else { out.clone() });
        if let Some((path, from)) = &scene {
            command.arg("--scene").arg(path).arg("--scene-from").arg(from);
        }
        eprintln!("xtask: the lab, built as {} ({})", flavour.name, flavour.rustflags());
        run_streaming(&mut command)?;
    }
    if both {
        let mut command = NATIVE.lab();
        for flavour in flavours {
            command.arg("--compare").arg(format!("{}={}", flavour.name, out.join(flavour.name).display()));
        }
        command.arg("--out").arg(&out);
        run_streaming(&mut command)?;
    }
    Ok(())
}

/// The user's shapes, as the lab is to measure them: the scene, and what
/// the user gave, as the report names it.
struct UserScene {
    scene: Scene,
    from: String,
}

/// The scene the user asked the lab to measure: a scene file read whole (a
/// bad file is an error naming its line), or an SVG imported (what it
/// drew otherwise than the SVG asks is printed, and named in the report);
/// `None` for the corpus.
fn user_scene(opt: &LabOpt) -> Result<Option<UserScene>> {
    if let Some(path) = &opt.scene {
        let file = SceneFile::read(path)?;
        return Ok(Some(UserScene { scene: file.scene, from: path.display().to_string() }));
    }
    let Some(path) = &opt.svg else { return Ok(None) };
    let imported = svg_import::import_file(path, &svg_import::Options::default())?;
    for note in &imported.notes {
        eprintln!("xtask: {}: {note}", path.display());
    }
    let mut from = format!("{}, imported by svg_import", path.display());
    if !imported.notes.is_empty() {
        from = format!("{from}: {}", imported.notes.join("; "));
    }
    Ok(Some(UserScene { scene: imported.scene, from }))
}

/// Writes `scene` into `dir` as the scene file the lab reads, named after
/// the scene (the lab names the scene by the file's stem); returns its path.
fn handed_over(scene: &Scene, dir: &Path) -> Result<PathBuf> {
    let path = dir.join(format!("{}.scene", scene.name));
    std::fs::write(&path, scenes::file::write(scene)).with_context(|| format!("failed to write {}", path.display()))?;
    Ok(path)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn opt(scene: Option<PathBuf>) -> LabOpt {
        LabOpt { quick: true, launches: None, build: LabBuild::Native, out: None, scene, svg: None }
    }

    fn svg(path: PathBuf) -> LabOpt {
        LabOpt { svg: Some(path), ..opt(None) }
    }

    /// An SVG's polygons as `svg_import` makes them, named after the file,
    /// with what it drew otherwise in the report's words.
    #[test]
    fn an_svg_is_imported_for_the_lab() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("ring.svg");
        std::fs::write(
            &path,
            r##"<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 32 20"><path fill="#c00" fill-opacity="0.5" fill-rule="evenodd" d="M2 2h28v16H2z M8 6h16v8H8z"/></svg>"##,
        )
        .unwrap();
        let user = user_scene(&svg(path.clone())).unwrap().unwrap();
        let expected = svg_import::import_file(&path, &svg_import::Options::default()).unwrap();
        assert_eq!(user.scene, expected.scene);
        assert_eq!(user.scene.name, "ring");
        assert!(!expected.notes.is_empty());
        assert!(user.from.starts_with(&format!("{}, imported by svg_import: ", path.display())), "{}", user.from);
        assert!(expected.notes.iter().all(|note| user.from.contains(note.as_str())), "{}", user.from);
    }

    #[test]
    fn a_bad_svg_is_refused_naming_the_file() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("broken.svg");
        std::fs::write(&path, "<svg xmlns=\"http://www.w3.org/2000/svg\"><path d=\"M0 0 L").unwrap();
        let error = format!("{:#}", user_scene(&svg(path)).err().unwrap());
        assert!(error.contains("broken.svg: not imported"), "{error}");
    }

    /// The scene handed to the lab reads back to the user's, palette,
    /// clears, rules and subpixel vertices alike, under the user's name.
    #[test]
    fn the_scene_handed_over_is_the_users() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("mine.scene");
        std::fs::write(
            &path,
            "palette 16 63,0,0 0,63,0\nclear 1\npoly color=16 rule=nonzero 0.5,0 10.00390625,0 5,-8.25 | 1,1 2,1 \
             1,2\nclear 2\npoly color=17 1,0 0,1 1,1\n",
        )
        .unwrap();
        let user = user_scene(&opt(Some(path.clone()))).unwrap().unwrap();
        assert_eq!(user.from, path.display().to_string());
        let lab_dir = tempfile::tempdir().unwrap();
        let handed = handed_over(&user.scene, lab_dir.path()).unwrap();
        assert_eq!(handed.file_stem().unwrap(), "mine");
        let text = std::fs::read_to_string(&handed).unwrap();
        assert_eq!(scenes::file::parse("mine", &text).unwrap(), user.scene);
    }

    #[test]
    fn a_bad_scene_is_refused_naming_its_line() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("bad.scene");
        std::fs::write(&path, "clear 0\npoly color=300 0,0 1,0 0,1\n").unwrap();
        let error = user_scene(&opt(Some(path))).err().unwrap().to_string();
        assert!(error.contains("bad.scene: bad scene file: line 2: bad colour `300`"), "{error}");
    }
}
