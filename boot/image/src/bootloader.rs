//! The boot stages the image is built with: the registry's `bootloader`
//! with its BIOS stage 2 patched, so that the display card is still in the
//! BIOS's text mode when the kernel programs mode 13h. (The UEFI loader is
//! the registry's, unchanged: under UEFI the kernel undoes the firmware's
//! mode itself, card by card, see kernel/src/card.rs.)
//!
//! Why: `bootloader` 0.11's BIOS stage 2 asks the card's VBE BIOS for a
//! linear-framebuffer mode and switches to it before the kernel runs (and
//! panics when the card has no VBE). Undoing that takes card-specific
//! steps: on QEMU's Cirrus card, for one, the standard VGA registers read
//! back as programmed while the screen stays garbage, because an extended
//! sequencer register keeps the VBE mode. A card that never left text mode
//! needs no undoing, on any VGA-compatible adapter.
//!
//! How: nothing of the bootloader lives in this repository. At build time
//! [`prepare`] has cargo fetch `bootloader` and `bootloader-x86_64-bios-stage-2`
//! of [`VERSION`] from the registry, copies `bootloader` to a folder under
//! the nightly target directory, puts the stage-2 crate at `bios/stage-2`
//! inside it (where `bootloader`'s build script builds stage 2 from when
//! that folder exists; the other stages still come from the registry),
//! and applies [`STAGE_2_EDITS`], each of which must match exactly once or
//! the build stops saying which. The image writer (`boot`) is then built against
//! that copy through a cargo `[patch]` given on the command line
//! ([`PatchedBootloader::cargo_args`]), with a lock file of its own under
//! `target/`, so the tracked `Cargo.lock` and the working tree stay as they
//! are.

use std::path::{Path, PathBuf};

use anyhow::{ensure, Context, Result};

use crate::cargo::pinned;
use crate::process::{output_of, run_streaming};
use crate::workspace;

/// The `bootloader` release the edits are written against. `boot/Cargo.toml`
/// asks for exactly this version (a unit test holds it to that), so a new
/// release is taken only together with edits checked against its source.
pub const VERSION: &str = "0.11.17";

/// The registry crate whose source is `bootloader`'s BIOS stage 2.
const STAGE_2_CRATE: &str = "bootloader-x86_64-bios-stage-2";

/// One change to a file of the stage-2 crate: `find` must occur exactly
/// once and becomes `replace`.
pub struct Edit {
    /// The file, relative to the stage-2 crate.
    pub file: &'static str,
    /// What the edit does and why, for the error when `find` is missing.
    pub purpose: &'static str,
    pub find: &'static str,
    pub replace: &'static str,
}

/// Everything the image's stage 2 changes from the registry's, and why.
pub const STAGE_2_EDITS: &[Edit] = &[
    Edit {
        file: "Cargo.toml",
        purpose: "make the copy a workspace of its own: cargo would otherwise take it for a member of ours, \
                  since it lies inside our workspace's folder",
        find: "\n[profile.stage-2]\n",
        replace: "\n[workspace]\n\n[profile.stage-2]\n",
    },
    Edit {
        file: "src/main.rs",
        purpose: "drop the VBE query and mode set (`vesa_mode.enable().unwrap();`): the card stays in the \
                  BIOS's text mode, and a machine without VBE boots too",
        find: "    // TODO: load these from the kernel's config instead of hardcoding
    let max_width = 1280;
    let max_height = 720;

    let mut vesa_info = vesa::VesaInfo::query(disk_buffer).unwrap();
    let vesa_mode = vesa_info
        .get_best_mode(max_width, max_height)
        .unwrap()
        .expect(\"no suitable VESA mode found\");
    writeln!(
        screen::Writer,
        \"VESA MODE: {}x{}\",
        vesa_mode.width,
        vesa_mode.height
    )
    .unwrap();
    vesa_mode.enable().unwrap();
",
        replace: "",
    },
    Edit {
        file: "src/main.rs",
        purpose: "describe the mode-13h window instead of the VBE mode's framebuffer: the later stages log \
                  there (one byte a pixel, a format their logger takes), which text mode does not show, and \
                  the kernel finds it in its boot info",
        find: "        framebuffer: BiosFramebufferInfo {
            region: Region {
                start: vesa_mode.framebuffer_start.into(),
                len: u64::from(vesa_mode.height) * u64::from(vesa_mode.bytes_per_scanline),
            },
            width: vesa_mode.width,
            height: vesa_mode.height,
            bytes_per_pixel: vesa_mode.bytes_per_pixel,
            stride: vesa_mode.bytes_per_scanline / u16::from(vesa_mode.bytes_per_pixel),
            pixel_format: vesa_mode.pixel_format,
        },
",
        replace: "        framebuffer: BiosFramebufferInfo {
            region: Region { start: 0xA0000, len: 320 * 200 },
            width: 320,
            height: 200,
            bytes_per_pixel: 1,
            stride: 320,
            pixel_format: bootloader_x86_64_bios_common::PixelFormat::Rgb,
        },
",
    },
];

/// `text` with every edit of `edits` for `file` applied, in order; fails
/// naming the first edit whose `find` does not occur exactly once.
pub fn apply_edits(file: &str, text: &str, edits: &[Edit]) -> Result<String> {
    let mut text = text.to_string();
    for edit in edits.iter().filter(|edit| edit.file == file) {
        let found = text.matches(edit.find).count();
        ensure!(
            found == 1,
            "cannot patch {STAGE_2_CRATE} {VERSION}'s {file}: the text to change occurs {found} times, not once \
             (the edit is to {}); its first line: `{}`",
            edit.purpose,
            edit.find.trim_start_matches('\n').lines().next().unwrap_or_default().trim()
        );
        text = text.replacen(edit.find, edit.replace, 1);
    }
    Ok(text)
}

/// Where the patched copy lives and the lock file its builds use.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PatchedBootloader {
    /// The copy of `bootloader` with the patched stage 2 at `bios/stage-2`.
    pub dir: PathBuf,
    /// The lock file of builds against the copy: cargo rewrites the
    /// `bootloader` entry of whatever lock file a `[patch]` build uses.
    pub lockfile: PathBuf,
}

impl PatchedBootloader {
    /// Under the nightly target directory.
    pub fn in_target_dir() -> Self {
        let root = workspace::nightly_target_dir().join("patched-bootloader");
        Self { dir: root.join(format!("bootloader-{VERSION}")), lockfile: root.join("lock").join("Cargo.lock") }
    }

    /// Arguments to a `cargo build` of the image writer: `bootloader`
    /// from the copy, and the lock file under `target/`.
    pub fn cargo_args(&self) -> Result<Vec<String>> {
        Ok(vec![
            "--config".to_string(),
            format!("patch.crates-io.bootloader.path={}", toml_string(&self.dir)?),
            "--config".to_string(),
            format!("resolver.lockfile-path={}", toml_string(&self.lockfile)?),
        ])
    }

    /// A fingerprint of the patch, kept beside the copy: a copy made by
    /// other edits is made again.
    fn stamp(&self) -> PathBuf {
        self.dir.with_extension("stamp")
    }

    /// Fails unless the lock file of a build shows `bootloader` taken from
    /// the copy (a path package has no `source`): cargo ignores a `[patch]`
    /// whose version does not match, with only a warning.
    pub fn ensure_used(&self) -> Result<()> {
        let lock = std::fs::read_to_string(&self.lockfile)
            .with_context(|| format!("failed to read {}", self.lockfile.display()))?;
        ensure!(
            patched_in_lock(&lock),
            "cargo built the image writer with the registry's bootloader, not the patched copy in {} \
             (see {}): boot/Cargo.toml must ask for bootloader ={VERSION}",
            self.dir.display(),
            self.lockfile.display()
        );
        Ok(())
    }
}

/// Whether the lock file `lock` has `bootloader` [`VERSION`] as a path
/// package.
fn patched_in_lock(lock: &str) -> bool {
    let entry = format!("name = \"bootloader\"\nversion = \"{VERSION}\"\n");
    lock.split("[[package]]\n").any(|package| package.starts_with(&entry) && !package.contains("\nsource = "))
}

/// `path` as a TOML basic string, for `--config KEY=VALUE`.
fn toml_string(path: &Path) -> Result<String> {
    let path = path.to_str().with_context(|| format!("{} is not UTF-8", path.display()))?;
    let mut quoted = String::from("\"");
    for c in path.chars() {
        match c {
            '"' | '\\' => {
                quoted.push('\\');
                quoted.push(c);
            }
            c if c.is_control() => quoted.push_str(&format!("\\u{:04X}", u32::from(c))),
            c => quoted.push(c),
        }
    }
    quoted.push('"');
    Ok(quoted)
}

/// The patched copy, made unless one made by the same edits is there, and
/// the lock file for a build against it, fresh from the workspace's.
pub fn prepare() -> Result<PatchedBootloader> {
    let patched = PatchedBootloader::in_target_dir();
    let fingerprint = fingerprint();
    let current = std::fs::read_to_string(patched.stamp()).is_ok_and(|stamp| stamp == fingerprint);
    if !current || !patched.dir.is_dir() {
        make_copy(&patched)?;
        std::fs::write(patched.stamp(), &fingerprint)
            .with_context(|| format!("failed to write {}", patched.stamp().display()))?;
    }
    let lock_dir = patched.lockfile.parent().expect("the lock file is in a folder");
    std::fs::create_dir_all(lock_dir).with_context(|| format!("failed to create {}", lock_dir.display()))?;
    let workspace_lock = workspace::root().join("Cargo.lock");
    std::fs::copy(&workspace_lock, &patched.lockfile)
        .with_context(|| format!("failed to copy {} to {}", workspace_lock.display(), patched.lockfile.display()))?;
    Ok(patched)
}

/// The version and every edit, as text.
fn fingerprint() -> String {
    let mut text = format!("{STAGE_2_CRATE} {VERSION}\n");
    for edit in STAGE_2_EDITS {
        text.push_str(&format!("{}\n{}\n{}\n", edit.file, edit.find, edit.replace));
    }
    text
}

/// Fetches both crates, copies them into a fresh folder beside
/// `patched.dir`, applies the edits and moves the result into place, so
/// an interrupted run never leaves a half-patched copy.
fn make_copy(patched: &PatchedBootloader) -> Result<()> {
    let (bootloader, stage_2) = fetch_sources(patched.dir.parent().expect("the copy is in a folder"))?;
    eprintln!(
        "image: patching bootloader {VERSION}'s BIOS stage 2 (no VBE mode set, so the card stays in text mode) \
         in {}",
        patched.dir.display()
    );
    let scratch = patched.dir.with_extension("partial");
    for dir in [&scratch, &patched.dir] {
        if dir.exists() {
            std::fs::remove_dir_all(dir).with_context(|| format!("failed to remove {}", dir.display()))?;
        }
    }
    copy_dir(&bootloader, &scratch)?;
    let stage_2_copy = scratch.join("bios").join("stage-2");
    copy_dir(&stage_2, &stage_2_copy)?;
    let mut files: Vec<&str> = STAGE_2_EDITS.iter().map(|edit| edit.file).collect();
    files.dedup();
    for file in files {
        let path = stage_2_copy.join(file);
        let text = std::fs::read_to_string(&path).with_context(|| format!("failed to read {}", path.display()))?;
        let patched_text = apply_edits(file, &text, STAGE_2_EDITS)?;
        std::fs::write(&path, patched_text).with_context(|| format!("failed to write {}", path.display()))?;
    }
    std::fs::rename(&scratch, &patched.dir)
        .with_context(|| format!("failed to move {} to {}", scratch.display(), patched.dir.display()))
}

/// The registry sources of `bootloader` and its stage-2 crate, both
/// [`VERSION`], fetched by cargo through a manifest written into
/// `work_dir` that depends on both (a manifest of its own, with a copy of
/// the workspace's lock file so that their dependencies resolve as ours do).
fn fetch_sources(work_dir: &Path) -> Result<(PathBuf, PathBuf)> {
    let fetch_dir = work_dir.join("fetch");
    std::fs::create_dir_all(&fetch_dir).with_context(|| format!("failed to create {}", fetch_dir.display()))?;
    let manifest = fetch_dir.join("Cargo.toml");
    std::fs::write(&manifest, fetch_manifest()).with_context(|| format!("failed to write {}", manifest.display()))?;
    std::fs::copy(workspace::root().join("Cargo.lock"), fetch_dir.join("Cargo.lock"))
        .context("failed to copy Cargo.lock for fetching the bootloader's sources")?;
    // Fetching unpacks both crates into cargo's registry sources, the
    // bin-only stage-2 crate too (a build would ignore it; fetch does not).
    run_streaming(pinned("cargo").arg("fetch").arg("--manifest-path").arg(&manifest))
        .context("failed to fetch the bootloader's sources")?;
    let metadata = output_of(
        pinned("cargo").args(["metadata", "--format-version", "1", "--offline", "--manifest-path"]).arg(&manifest),
    )?;
    let bootloader = registry_source(&metadata, "bootloader")?;
    // Cargo unpacks every crate of a registry side by side, as NAME-VERSION.
    let stage_2 = bootloader.with_file_name(format!("{STAGE_2_CRATE}-{VERSION}"));
    ensure!(
        stage_2.join("src").join("main.rs").is_file(),
        "cargo fetched {STAGE_2_CRATE} {VERSION}, but it is not beside bootloader at {}",
        stage_2.display()
    );
    Ok((bootloader, stage_2))
}

/// The manifest [`fetch_sources`] fetches with.
fn fetch_manifest() -> String {
    format!(
        "# Written by the image build (boot/image/src/bootloader.rs) to fetch the sources it patches.\n\
         [package]\nname = \"bootloader-sources\"\nversion = \"0.0.0\"\nedition = \"2021\"\npublish = false\n\n\
         [lib]\npath = \"lib.rs\"\n\n\
         [dependencies]\n\
         bootloader = {{ version = \"={VERSION}\", default-features = false, features = [\"bios\", \"uefi\"] }}\n\
         {STAGE_2_CRATE} = \"={VERSION}\"\n\n\
         [workspace]\n"
    )
}

/// The folder of package `name` [`VERSION`] in `cargo metadata` output.
fn registry_source(metadata: &str, name: &str) -> Result<PathBuf> {
    let metadata: serde_json::Value = serde_json::from_str(metadata).context("cargo metadata printed no JSON")?;
    let packages = metadata["packages"].as_array().context("cargo metadata lists no packages")?;
    let package = packages
        .iter()
        .find(|package| package["name"] == name && package["version"] == VERSION)
        .with_context(|| format!("cargo metadata does not list {name} {VERSION}"))?;
    let manifest = package["manifest_path"].as_str().with_context(|| format!("{name} has no manifest_path"))?;
    Ok(Path::new(manifest).parent().with_context(|| format!("{manifest} has no folder"))?.to_path_buf())
}

/// Copies the folder `from` to `to` (created), files and subfolders.
fn copy_dir(from: &Path, to: &Path) -> Result<()> {
    std::fs::create_dir_all(to).with_context(|| format!("failed to create {}", to.display()))?;
    for entry in std::fs::read_dir(from).with_context(|| format!("failed to list {}", from.display()))? {
        let entry = entry.with_context(|| format!("failed to list {}", from.display()))?;
        let (source, target) = (entry.path(), to.join(entry.file_name()));
        if entry.file_type()?.is_dir() {
            copy_dir(&source, &target)?;
        } else {
            // Read and write rather than `fs::copy`: registry files may be
            // read-only, and the edited ones are rewritten.
            let bytes = std::fs::read(&source).with_context(|| format!("failed to read {}", source.display()))?;
            std::fs::write(&target, bytes).with_context(|| format!("failed to write {}", target.display()))?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_image_builder_asks_for_exactly_the_patched_version() {
        let manifest = include_str!("../../Cargo.toml");
        assert!(
            manifest.contains(&format!("bootloader = {{ version = \"={VERSION}\"")),
            "boot/Cargo.toml must pin bootloader ={VERSION}, the version the stage-2 edits are written for"
        );
    }

    #[test]
    fn every_edit_applies_once_and_a_missing_text_is_an_error_naming_it() {
        let source = "fn main() {\n    a();\n    vesa_mode.enable().unwrap();\n    b();\n}\n";
        let edits = [Edit {
            file: "src/main.rs",
            purpose: "drop the mode set",
            find: "    vesa_mode.enable().unwrap();\n",
            replace: "",
        }];
        assert_eq!(apply_edits("src/main.rs", source, &edits).unwrap(), "fn main() {\n    a();\n    b();\n}\n");
        assert_eq!(apply_edits("Cargo.toml", source, &edits).unwrap(), source, "edits of other files");
        let error = apply_edits("src/main.rs", "fn main() {}\n", &edits).unwrap_err().to_string();
        assert_eq!(
            error,
            format!(
                "cannot patch {STAGE_2_CRATE} {VERSION}'s src/main.rs: the text to change occurs 0 times, not once \
                 (the edit is to drop the mode set); its first line: `vesa_mode.enable().unwrap();`"
            )
        );
        let twice = format!("{source}{source}");
        assert!(apply_edits("src/main.rs", &twice, &edits).unwrap_err().to_string().contains("occurs 2 times"));
    }

    #[test]
    fn the_edits_remove_the_mode_set_and_every_use_of_the_vbe_mode() {
        let removed: String = STAGE_2_EDITS.iter().map(|edit| edit.find).collect();
        let added: String = STAGE_2_EDITS.iter().map(|edit| edit.replace).collect();
        assert!(removed.contains("vesa_mode.enable().unwrap();"));
        assert!(removed.contains("vesa::VesaInfo::query("));
        assert!(!added.contains("vesa"), "{added}");
    }

    #[test]
    fn the_build_takes_the_copy_and_a_lock_file_under_target() {
        let patched = PatchedBootloader {
            dir: PathBuf::from("/w/target/nightly/patched-bootloader/bootloader-0.11.17"),
            lockfile: PathBuf::from("/w/target/nightly/patched-bootloader/lock/Cargo.lock"),
        };
        assert_eq!(
            patched.cargo_args().unwrap(),
            [
                "--config",
                "patch.crates-io.bootloader.path=\"/w/target/nightly/patched-bootloader/bootloader-0.11.17\"",
                "--config",
                "resolver.lockfile-path=\"/w/target/nightly/patched-bootloader/lock/Cargo.lock\"",
            ]
        );
        assert_eq!(toml_string(Path::new("/a \"b\"\\c")).unwrap(), r#""/a \"b\"\\c""#);
    }

    #[test]
    fn only_a_path_bootloader_in_the_lock_file_counts_as_patched() {
        let registry = "[[package]]\nname = \"bootloader\"\nversion = \"0.11.17\"\n\
                        source = \"registry+https://github.com/rust-lang/crates.io-index\"\nchecksum = \"d8\"\n\
                        dependencies = [\n \"anyhow\",\n]\n\n";
        let path = "[[package]]\nname = \"bootloader\"\nversion = \"0.11.17\"\ndependencies = [\n \"anyhow\",\n]\n\n";
        let other = "[[package]]\nname = \"anyhow\"\nversion = \"1.0.0\"\n\n";
        assert!(patched_in_lock(&format!("version = 4\n\n{other}{path}")));
        assert!(!patched_in_lock(&format!("version = 4\n\n{other}{registry}")));
        assert!(!patched_in_lock(&format!("version = 4\n\n{other}")));
    }
}
