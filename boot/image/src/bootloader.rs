//! The boot stages the image is built with: the registry's `bootloader`
//! with its BIOS stage 2 and its UEFI loader patched.
//!
//! Why stage 2: `bootloader` 0.11's BIOS stage 2 asks the card's VBE BIOS
//! for a linear-framebuffer mode and switches to it before the kernel runs
//! (and panics when the card has no VBE). Undoing that takes card-specific
//! steps: on QEMU's Cirrus card, for one, the standard VGA registers read
//! back as programmed while the screen stays garbage, because an extended
//! sequencer register keeps the VBE mode. A card that never left text mode
//! needs no undoing, on any VGA-compatible adapter. (Under UEFI the kernel
//! undoes the firmware's mode itself, card by card, see kernel/src/card.rs.)
//!
//! Why the UEFI loader: under Secure Boot shim starts it only if it carries
//! an `.sbat` section, and once started it would boot any kernel beside it
//! on the stick; the patched loader has the section and checks the
//! SHA-256 of the kernel and of `boot.json` against digests the image
//! build writes into it before signing it ([`crate::secure_boot`],
//! boot/image/loader/verify.rs).
//!
//! How: nothing of the bootloader lives in this repository. At build time
//! [`prepare`] has cargo fetch `bootloader`, `bootloader-x86_64-bios-stage-2`
//! and `bootloader-x86_64-uefi` of [`VERSION`] from the registry, checks
//! their archives against the SHA-256 pinned in [`crate::sources`],
//! unpacks `bootloader` into a folder under the nightly target directory
//! with the stage-2 crate at `bios/stage-2` and the loader at `uefi`
//! inside it (where `bootloader`'s build script builds them from when
//! those folders exist; the other stages still come from the registry),
//! and applies [`STAGE_2_EDITS`] and [`LOADER_EDITS`], each of which must
//! match exactly once or the build stops saying which. The image writer
//! (`boot`) is then built against that copy through a cargo `[patch]`
//! given on the command line ([`PatchedBootloader::cargo_args`]), with a
//! lock file of its own under `target/`, so the tracked `Cargo.lock` and
//! the working tree stay as they are.
//!
//! Built once per change of its inputs: the copy is made again only when
//! the stamp beside it (the pinned digests, every edit and every added
//! file) changes, and `bootloader`'s build script, which rebuilds the
//! stages, reruns only when a folder it watches changes. It watches
//! `bios/stage-2` and `bios/common`, `uefi` and `common`: the copy has
//! empty `bios/common` and `common` folders (a missing one counts as
//! changed on every build), and the stages' own build folders lie outside
//! the watched ones ([`PatchedBootloader::stages_target_dir`]).

use std::path::{Path, PathBuf};
use std::process::Command;

use anyhow::{ensure, Context, Result};

use crate::sources::{self, PinnedCrate, BOOTLOADER, STAGE_2, UEFI_LOADER};
use crate::{tree, workspace};

pub use crate::sources::VERSION;

/// One change to a file of a patched crate: `find` must occur exactly
/// once and becomes `replace`.
pub struct Edit {
    /// The file, relative to the crate.
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

/// Everything the image's UEFI loader changes from the registry's, and
/// why; the code it calls is [`LOADER_FILES`].
pub const LOADER_EDITS: &[Edit] = &[
    Edit {
        file: "Cargo.toml",
        purpose: "make the copy a workspace of its own, as stage 2's",
        find: "\n[[bin]]\n",
        replace: "\n[workspace]\n\n[[bin]]\n",
    },
    Edit {
        file: "src/main.rs",
        purpose: "add the modules that check the kernel and boot.json and carry the .sbat section",
        find: "\nmod memory_descriptor;\n",
        replace: "\nmod memory_descriptor;\nmod polylab_sha256;\nmod polylab_verify;\n",
    },
    Edit {
        file: "src/main.rs",
        purpose: "check the kernel's SHA-256 before anything reads it, whether it came from the disk or over TFTP",
        find: "    let kernel_slice = load_file_from_boot_method(&KERNEL_FILE, boot_mode)?;\n",
        replace: "    let kernel_slice = load_file_from_boot_method(&KERNEL_FILE, boot_mode)?;\n    \
                  polylab_verify::check_kernel(kernel_slice);\n",
    },
    Edit {
        file: "src/main.rs",
        purpose: "check boot.json's SHA-256 before it is parsed (a missing one is refused too)",
        find: "fn load_config_file(boot_mode: BootMode) -> Option<&'static mut [u8]> {
    load_file_from_boot_method(&CONFIG_FILE, boot_mode)
}
",
        replace: "fn load_config_file(boot_mode: BootMode) -> Option<&'static mut [u8]> {
    let config = load_file_from_boot_method(&CONFIG_FILE, boot_mode);
    polylab_verify::check_config(config.as_deref());
    config
}
",
    },
    Edit {
        file: "src/main.rs",
        purpose: "refuse a ramdisk on the volume: nothing checks it, and the loader would map it for the kernel",
        find: "fn load_ramdisk(boot_mode: BootMode) -> Option<&'static mut [u8]> {
    load_file_from_boot_method(&RAMDISK_FILE, boot_mode)
}
",
        replace: "fn load_ramdisk(boot_mode: BootMode) -> Option<&'static mut [u8]> {
    let ramdisk = load_file_from_boot_method(&RAMDISK_FILE, boot_mode);
    polylab_verify::check_no_ramdisk(ramdisk.is_some());
    ramdisk
}
",
    },
    Edit {
        file: "src/main.rs",
        purpose: "refuse an empty file on the disk before the loader asks for a zero-byte allocation, which panics",
        find: "    let file_size = usize::try_from(file_info.file_size()).unwrap();\n",
        replace: "    let file_size = usize::try_from(file_info.file_size()).unwrap();\n    \
                  polylab_verify::check_not_empty(&name, file_size);\n",
    },
    Edit {
        file: "src/main.rs",
        purpose: "refuse an empty file over TFTP as on the disk",
        find: "    let kernel_size = usize::try_from(file_size).expect(\"The file size should fit into usize\");\n",
        replace:
            "    let kernel_size = usize::try_from(file_size).expect(\"The file size should fit into usize\");\n    \
                  polylab_verify::check_not_empty(&name, kernel_size);\n",
    },
    Edit {
        file: "Cargo.toml",
        purpose: "let the loader's profile trim paths (a nightly cargo feature)",
        find: "\n[package]\n",
        replace: "\ncargo-features = [\"trim-paths\"]\n\n[package]\n",
    },
    Edit {
        file: "Cargo.toml",
        purpose: "write no path of the build machine into the loader: cargo remaps the sources of the toolchain \
                  and of every crate to names without the builder's home folder",
        find: "\n[[bin]]\n",
        replace: "\n[profile.release]\ntrim-paths = \"all\"\n\n[[bin]]\n",
    },
];

/// Files added to the UEFI loader's source: (path in the crate, text).
pub const LOADER_FILES: &[(&str, &str)] = &[
    ("src/polylab_sha256.rs", include_str!("../loader/sha256.rs")),
    ("src/polylab_verify.rs", include_str!("../loader/verify.rs")),
];

/// One crate put into the copy of `bootloader`, patched.
pub struct Patch {
    pub source: PinnedCrate,
    /// Where in the copy: the folder `bootloader`'s build script builds
    /// that stage from when it exists.
    pub folder: &'static str,
    pub edits: &'static [Edit],
    pub added_files: &'static [(&'static str, &'static str)],
}

/// Both patched crates.
pub const PATCHES: [Patch; 2] = [
    Patch { source: STAGE_2, folder: "bios/stage-2", edits: STAGE_2_EDITS, added_files: &[] },
    Patch { source: UEFI_LOADER, folder: "uefi", edits: LOADER_EDITS, added_files: LOADER_FILES },
];

/// Folders `bootloader`'s build script watches (`cargo:rerun-if-changed`)
/// that the copy has no crate in: they exist, empty, so that cargo does not
/// take their absence for a change on every build.
const WATCHED_EMPTY_FOLDERS: [&str; 2] = ["bios/common", "common"];

/// `text` with every edit of `edits` for `file` applied, in order; fails
/// naming the first edit whose `find` does not occur exactly once.
pub fn apply_edits(crate_name: &str, file: &str, text: &str, edits: &[Edit]) -> Result<String> {
    let mut text = text.to_string();
    for edit in edits.iter().filter(|edit| edit.file == file) {
        let found = text.matches(edit.find).count();
        ensure!(
            found == 1,
            "cannot patch {crate_name} {VERSION}'s {file}: the text to change occurs {found} times, not once \
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
        let root = workspace::nightly_target_dir().join("patched-bootloader");
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

/// The patched copy, made unless one made from the same sources by the
/// same edits is there (which is then checked file by file against a copy
/// made afresh: a hand edit stops the build), and the lock file for a
/// build against it, fresh from the workspace's.
pub fn prepare() -> Result<PatchedBootloader> {
    let patched = PatchedBootloader::in_target_dir();
    let fingerprint = fingerprint();
    if is_current(&patched, &fingerprint) {
        check_copy(&patched.dir)?;
    } else {
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
        let to = match PATCHES.iter().find(|patch| patch.source == *pinned) {
            Some(patch) => to.join(patch.folder),
            None if *pinned == BOOTLOADER => to.to_path_buf(),
            None => unreachable!("every pinned crate is bootloader or patched"),
        };
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

    #[test]
    fn the_image_builder_asks_for_exactly_the_patched_version() {
        let manifest = include_str!("../../Cargo.toml");
        assert!(
            manifest.contains(&format!("bootloader = {{ version = \"={VERSION}\"")),
            "boot/Cargo.toml must pin bootloader ={VERSION}, the version the edits are written for"
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
        assert_eq!(apply_edits("x", "src/main.rs", source, &edits).unwrap(), "fn main() {\n    a();\n    b();\n}\n");
        assert_eq!(apply_edits("x", "Cargo.toml", source, &edits).unwrap(), source, "edits of other files");
        let error = apply_edits("x", "src/main.rs", "fn main() {}\n", &edits).unwrap_err().to_string();
        assert_eq!(
            error,
            format!(
                "cannot patch x {VERSION}'s src/main.rs: the text to change occurs 0 times, not once \
                 (the edit is to drop the mode set); its first line: `vesa_mode.enable().unwrap();`"
            )
        );
        let twice = format!("{source}{source}");
        assert!(apply_edits("x", "src/main.rs", &twice, &edits).unwrap_err().to_string().contains("occurs 2 times"));
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
    fn the_loader_edits_call_both_checks_and_add_their_modules() {
        let added: String = LOADER_EDITS.iter().map(|edit| edit.replace).collect();
        assert!(added.contains("polylab_verify::check_kernel(kernel_slice);"), "{added}");
        assert!(added.contains("polylab_verify::check_config(config.as_deref());"), "{added}");
        for (file, _) in LOADER_FILES {
            let module = file.trim_start_matches("src/").trim_end_matches(".rs");
            assert!(added.contains(&format!("mod {module};")), "{file} is added but not declared");
        }
    }

    #[test]
    fn the_stamp_names_every_fetched_archives_digest_and_every_change() {
        let stamp = fingerprint();
        for pinned in sources::PINNED {
            assert!(stamp.contains(&format!("{} sha256:{}", pinned.name, pinned.sha256)), "{stamp}");
        }
        for edit in STAGE_2_EDITS.iter().chain(LOADER_EDITS) {
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
