//! The patched copy of `bootloader` the image writer is built against
//! (what it is made of: [`crate::bootloader`]): made under the nightly
//! target directory from the pinned archives and the edits, made again
//! when those change (its stamp), checked file by file against a copy made
//! afresh on every other build, and handed to cargo through a `[patch]` on
//! the command line with a lock file of its own under `target/`, so the
//! tracked `Cargo.lock` and the working tree stay as they are.
//!
//! Built once per change of its inputs: `bootloader`'s build script, which
//! rebuilds the stages, reruns only when a folder it watches changes. It
//! watches `bios/stage-2` and `bios/common`, `uefi` and `common`: the copy
//! has empty `bios/common` and `common` folders (a missing one counts as
//! changed on every build), and the stages' own build folders lie outside
//! the watched ones ([`PatchedBootloader::stages_target_dir`]).

use std::path::{Path, PathBuf};
use std::process::Command;

use anyhow::{ensure, Context, Result};

use crate::bootloader::{apply_edits, Patch, PATCHES, VERSION};
use crate::sources;
use crate::tree;
use install::workspace;

/// Folders `bootloader`'s build script watches (`cargo:rerun-if-changed`)
/// that the copy has no crate in: they exist, empty, so that cargo does not
/// take their absence for a change on every build.
const WATCHED_EMPTY_FOLDERS: [&str; 2] = ["bios/common", "common"];

/// Where the patched copy lives and the lock file its builds use.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PatchedBootloader {
    /// The copy of `bootloader` with the patched stage 2 at `bios/stage-2`
    /// and the patched UEFI loader at `uefi`.
    pub dir: PathBuf,
    /// The lock file of builds against the copy: cargo rewrites the
    /// `bootloader` entry of whatever lock file a `[patch]` build uses.
    pub lockfile: PathBuf,
}

impl PatchedBootloader {
    /// Under the nightly target directory.
    pub fn in_target_dir() -> Self {
        Self::under(&workspace::nightly_target_dir())
    }

    /// Under the nightly target directory `nightly_target_dir` (a test's
    /// own, for one).
    pub fn under(nightly_target_dir: &Path) -> Self {
        let root = nightly_target_dir.join("patched-bootloader");
        Self { dir: root.join(format!("bootloader-{VERSION}")), lockfile: root.join("lock").join("Cargo.lock") }
    }

    /// Makes `command`, a `cargo build` of the image writer, build
    /// against the copy: `bootloader` patched to it, the lock file under
    /// `target/`, and the stages' builds in [`Self::stages_target_dir`].
    pub fn configure(&self, command: &mut Command) -> Result<()> {
        command.args([
            "--config".to_string(),
            format!("patch.crates-io.bootloader.path={}", toml_string(&self.dir)?),
            "--config".to_string(),
            format!("resolver.lockfile-path={}", toml_string(&self.lockfile)?),
        ]);
        // bootloader's build script builds each stage with `cargo install`,
        // which reads this variable (the UEFI loader's names a folder of its
        // own, `target/uefi_target` in the copy). Stage 2 is a workspace of
        // its own in the copy, so without it its build folder would be
        // `bios/stage-2/target`, inside the folder the script watches, and
        // every build would change it.
        command.env("CARGO_TARGET_DIR", self.stages_target_dir());
        Ok(())
    }

    /// Where the stages build: beside the copy, outside every folder
    /// `bootloader`'s build script watches.
    pub fn stages_target_dir(&self) -> PathBuf {
        self.dir.with_file_name("stages-target")
    }

    /// A fingerprint of the patch, kept beside the copy: a copy made by
    /// other edits is made again.
    pub fn stamp(&self) -> PathBuf {
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

/// The patched copy `patched`, made unless one made from the same sources
/// by the same edits is there (which is then checked file by file against
/// a copy made afresh: a hand edit stops the build), and the lock file for
/// a build against it, fresh from the workspace's.
pub fn prepare(patched: &PatchedBootloader) -> Result<()> {
    let fingerprint = fingerprint();
    if is_current(patched, &fingerprint) {
        check_copy(&patched.dir)?;
    } else {
        make_copy(patched)?;
        std::fs::write(patched.stamp(), &fingerprint)
            .with_context(|| format!("failed to write {}", patched.stamp().display()))?;
    }
    let lock_dir = patched.lockfile.parent().expect("the lock file is in a folder");
    std::fs::create_dir_all(lock_dir).with_context(|| format!("failed to create {}", lock_dir.display()))?;
    let workspace_lock = workspace::root().join("Cargo.lock");
    std::fs::copy(&workspace_lock, &patched.lockfile)
        .with_context(|| format!("failed to copy {} to {}", workspace_lock.display(), patched.lockfile.display()))?;
    Ok(())
}

/// Fails, naming every difference, unless the copy at `dir` holds exactly
/// what the pinned archives and the edits make (besides the loader's
/// build folder, [`COPY_BUILD_FOLDER`]): the stamp says which sources and
/// edits made the copy, not that nobody changed it since.
pub fn check_copy(dir: &Path) -> Result<()> {
    let work_dir = dir.parent().context("the copy is in a folder")?;
    let expected = tempfile::Builder::new()
        .prefix("expected-")
        .tempdir_in(work_dir)
        .with_context(|| format!("failed to create a folder in {}", work_dir.display()))?;
    let expected_tree = expected.path().join("bootloader");
    make_tree(work_dir, &expected_tree)?;
    let differences = tree::differences(&expected_tree, dir, &[COPY_BUILD_FOLDER])?;
    ensure!(
        differences.is_empty(),
        "refusing to build the image: the patched bootloader in {} is not what bootloader {VERSION}'s pinned \
         sources and the edits in boot/image/src/bootloader.rs make ({}). A loader built from it could lack \
         its checks and would be signed all the same. Remove the folder to have it made again: rm -r {}",
        dir.display(),
        differences.join("; "),
        dir.display()
    );
    Ok(())
}

/// The folder in the copy where bootloader's build script builds the UEFI
/// loader (`target/uefi_target`): the only thing in the copy that is not
/// made from the sources.
pub const COPY_BUILD_FOLDER: &str = "target";

/// Whether the copy is there and its stamp says it was made with
/// `fingerprint`.
pub fn is_current(patched: &PatchedBootloader, fingerprint: &str) -> bool {
    patched.dir.is_dir() && std::fs::read_to_string(patched.stamp()).is_ok_and(|stamp| stamp == fingerprint)
}

/// What the copy is made of, as text: the version, the SHA-256 of every
/// fetched archive (checked against it before anything is unpacked),
/// every edit and every added file.
pub fn fingerprint() -> String {
    let mut text = format!("bootloader {VERSION}\n");
    for source in sources::PINNED {
        text.push_str(&format!("{} sha256:{}\n", source.name, source.sha256));
    }
    for patch in &PATCHES {
        text.push_str(&format!("{} at {}\n", patch.source.name, patch.folder));
        for edit in patch.edits {
            text.push_str(&format!("edit {}\n{}\n{}\n", edit.file, edit.find, edit.replace));
        }
        for (file, contents) in patch.added_files {
            text.push_str(&format!("add {file} sha256:{}\n", sources::sha256_hex(contents.as_bytes())));
        }
    }
    for folder in WATCHED_EMPTY_FOLDERS {
        text.push_str(&format!("empty {folder}\n"));
    }
    text
}

/// Makes the copy in a fresh folder beside `patched.dir` and moves it into
/// place, so an interrupted run never leaves a half-patched copy.
fn make_copy(patched: &PatchedBootloader) -> Result<()> {
    eprintln!(
        "image: patching bootloader {VERSION}'s BIOS stage 2 (no VBE mode set, so the card stays in text mode) \
         and UEFI loader (an .sbat section, and a check of the kernel's and boot.json's SHA-256) in {}",
        patched.dir.display()
    );
    let scratch = patched.dir.with_extension("partial");
    for dir in [&scratch, &patched.dir] {
        if dir.exists() {
            std::fs::remove_dir_all(dir).with_context(|| format!("failed to remove {}", dir.display()))?;
        }
    }
    make_tree(patched.dir.parent().expect("the copy is in a folder"), &scratch)?;
    std::fs::rename(&scratch, &patched.dir)
        .with_context(|| format!("failed to move {} to {}", scratch.display(), patched.dir.display()))
}

/// Fetches the pinned archives (cargo works in `work_dir`), checks them,
/// unpacks them into `to` (not there yet) and applies the patches.
fn make_tree(work_dir: &Path, to: &Path) -> Result<()> {
    let archives = sources::fetch(work_dir)?;
    // Every archive is checked before any is unpacked.
    let checked: Vec<Vec<u8>> = sources::PINNED
        .iter()
        .zip(&archives)
        .map(|(pinned, archive)| sources::read_checked(archive, pinned))
        .collect::<Result<_>>()?;
    for (pinned, bytes) in sources::PINNED.iter().zip(&checked) {
        let patch = PATCHES.iter().find(|patch| patch.source == *pinned).expect("every pinned crate is patched");
        let to = to.join(patch.folder);
        if let Some(parent) = to.parent() {
            std::fs::create_dir_all(parent).with_context(|| format!("failed to create {}", parent.display()))?;
        }
        sources::unpack(bytes, pinned, &to)?;
    }
    for patch in &PATCHES {
        apply_patch(patch, &to.join(patch.folder))?;
    }
    for folder in WATCHED_EMPTY_FOLDERS {
        let folder = to.join(folder);
        std::fs::create_dir_all(&folder).with_context(|| format!("failed to create {}", folder.display()))?;
    }
    Ok(())
}

/// Applies `patch`'s edits to the crate in `dir` and adds its files.
fn apply_patch(patch: &Patch, dir: &Path) -> Result<()> {
    let mut files: Vec<&str> = patch.edits.iter().map(|edit| edit.file).collect();
    files.sort_unstable();
    files.dedup();
    for file in files {
        let path = dir.join(file);
        let text = std::fs::read_to_string(&path).with_context(|| format!("failed to read {}", path.display()))?;
        let patched_text = apply_edits(patch.source.name, file, &text, patch.edits)?;
        std::fs::write(&path, patched_text).with_context(|| format!("failed to write {}", path.display()))?;
    }
    for (file, contents) in patch.added_files {
        let path = dir.join(file);
        ensure!(!path.exists(), "{} {VERSION} already has a {file}, which the patch adds", patch.source.name);
        std::fs::write(&path, contents).with_context(|| format!("failed to write {}", path.display()))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bootloader::{BOOTLOADER_EDITS, LOADER_EDITS, STAGE_2_EDITS};

    #[test]
    fn the_stamp_names_every_fetched_archives_digest_and_every_change() {
        let stamp = fingerprint();
        for pinned in sources::PINNED {
            assert!(stamp.contains(&format!("{} sha256:{}", pinned.name, pinned.sha256)), "{stamp}");
        }
        for edit in BOOTLOADER_EDITS.iter().chain(STAGE_2_EDITS).chain(LOADER_EDITS) {
            assert!(stamp.contains(edit.find) && stamp.contains(edit.replace), "{}", edit.purpose);
        }
        let verify = sources::sha256_hex(include_str!("../loader/verify.rs").as_bytes());
        assert!(stamp.contains(&format!("add src/polylab_verify.rs sha256:{verify}")), "{stamp}");
    }

    #[test]
    fn a_copy_with_another_stamp_or_none_is_made_again() {
        let dir = tempfile::tempdir().unwrap();
        let patched =
            PatchedBootloader { dir: dir.path().join("bootloader-0.11.17"), lockfile: dir.path().join("lock") };
        assert!(!is_current(&patched, "a"), "no copy");
        std::fs::create_dir(&patched.dir).unwrap();
        assert!(!is_current(&patched, "a"), "no stamp");
        std::fs::write(patched.stamp(), "b").unwrap();
        assert!(!is_current(&patched, "a"), "another stamp");
        std::fs::write(patched.stamp(), "a").unwrap();
        assert!(is_current(&patched, "a"));
    }

    #[test]
    fn the_build_takes_the_copy_a_lock_file_and_a_stages_folder_under_target() {
        let patched = PatchedBootloader {
            dir: PathBuf::from("/w/target/nightly/patched-bootloader/bootloader-0.11.17"),
            lockfile: PathBuf::from("/w/target/nightly/patched-bootloader/lock/Cargo.lock"),
        };
        let mut command = Command::new("cargo");
        patched.configure(&mut command).unwrap();
        assert_eq!(
            command.get_args().collect::<Vec<_>>(),
            [
                "--config",
                "patch.crates-io.bootloader.path=\"/w/target/nightly/patched-bootloader/bootloader-0.11.17\"",
                "--config",
                "resolver.lockfile-path=\"/w/target/nightly/patched-bootloader/lock/Cargo.lock\"",
            ]
        );
        let stages = Path::new("/w/target/nightly/patched-bootloader/stages-target");
        assert_eq!(command.get_envs().collect::<Vec<_>>(), [("CARGO_TARGET_DIR".as_ref(), Some(stages.as_os_str()))]);
        for patch in &PATCHES {
            assert!(!stages.starts_with(patched.dir.join(patch.folder)), "{} is watched", patch.folder);
        }
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
