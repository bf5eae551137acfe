//! The registry sources the image build patches, pinned by the SHA-256 of
//! their `.crate` archives: fetched by cargo, checked against the digests
//! written here, and unpacked from the checked archive itself (never taken
//! from cargo's unpacked copy, which anything on the machine could have
//! changed since).
//!
//! Cargo checks a download against the registry index, but the index is
//! trusted the first time it is read; the digests here were read from it
//! once (and `bootloader`'s equals its `checksum` in our `Cargo.lock`, a
//! unit test holds it to that), so a later index or cache that serves
//! other bytes under the same version stops the build.

use std::path::{Path, PathBuf};

use anyhow::{ensure, Context, Result};
use sha2::{Digest, Sha256};

use install::pinned;
use install::workspace;
use install::{output_of, run_streaming};

/// The `bootloader` release the edits are written against. `boot/Cargo.toml`
/// asks for exactly this version (a unit test holds it to that), so a new
/// release is taken only together with edits checked against its source.
pub const VERSION: &str = "0.11.17";

/// One registry crate of [`VERSION`] and the SHA-256 of its `.crate`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PinnedCrate {
    pub name: &'static str,
    pub sha256: &'static str,
}

/// `bootloader` itself: the copy the image writer builds against.
pub const BOOTLOADER: PinnedCrate =
    PinnedCrate { name: "bootloader", sha256: "d861319d747a01da5d4d680500b7f808607f902a286b476bd51f991612e39d8e" };
/// Its BIOS stage 2, patched.
pub const STAGE_2: PinnedCrate = PinnedCrate {
    name: "bootloader-x86_64-bios-stage-2",
    sha256: "755c481005f96cfbe3499d36d4380aa10bb4b4b1a1abaf79a3ba06e15935070e",
};
/// Its UEFI loader, patched.
pub const UEFI_LOADER: PinnedCrate = PinnedCrate {
    name: "bootloader-x86_64-uefi",
    sha256: "a6f5c10daaa697564ff78776f23ff0ae6e401c7ead7af41d980a913869a8b67f",
};
/// Every crate the build fetches.
pub const PINNED: [PinnedCrate; 3] = [BOOTLOADER, STAGE_2, UEFI_LOADER];

/// The `.crate` archives of [`PINNED`], in that order, fetched by cargo
/// through a manifest written into `work_dir` that depends on them all (a
/// manifest of its own, with a copy of the workspace's lock file so that
/// their dependencies resolve as ours do). Fetching also fetches the
/// bin-only crates, which a build would ignore.
pub fn fetch(work_dir: &Path) -> Result<Vec<PathBuf>> {
    let fetch_dir = work_dir.join("fetch");
    std::fs::create_dir_all(&fetch_dir).with_context(|| format!("failed to create {}", fetch_dir.display()))?;
    let manifest = fetch_dir.join("Cargo.toml");
    std::fs::write(&manifest, fetch_manifest()).with_context(|| format!("failed to write {}", manifest.display()))?;
    std::fs::copy(workspace::root().join("Cargo.lock"), fetch_dir.join("Cargo.lock"))
        .context("failed to copy Cargo.lock for fetching the bootloader's sources")?;
    run_streaming(pinned("cargo").arg("fetch").arg("--manifest-path").arg(&manifest))
        .context("failed to fetch the bootloader's sources")?;
    let metadata = output_of(
        pinned("cargo").args(["metadata", "--format-version", "1", "--offline", "--manifest-path"]).arg(&manifest),
    )?;
    // Cargo keeps every archive of a registry side by side, as
    // NAME-VERSION.crate; `cargo metadata` lists only library crates, so
    // the bin-only ones are found beside `bootloader`'s.
    let bootloader = archive_of(&metadata, BOOTLOADER.name)?;
    PINNED
        .iter()
        .map(|pinned| {
            let archive = bootloader.with_file_name(format!("{}-{VERSION}.crate", pinned.name));
            ensure!(
                archive.is_file(),
                "cargo fetched {} {VERSION}, but {} is not there",
                pinned.name,
                archive.display()
            );
            Ok(archive)
        })
        .collect()
}

/// The manifest [`fetch`] fetches with.
fn fetch_manifest() -> String {
    let mut manifest = String::from(
        "# Written by the image build (boot/image/src/sources.rs) to fetch the sources it patches.\n\
         [package]\nname = \"bootloader-sources\"\nversion = \"0.0.0\"\nedition = \"2021\"\npublish = false\n\n\
         [lib]\npath = \"lib.rs\"\n\n[dependencies]\n",
    );
    for pinned in PINNED {
        let features =
            if pinned == BOOTLOADER { ", default-features = false, features = [\"bios\", \"uefi\"]" } else { "" };
        manifest.push_str(&format!("{} = {{ version = \"={VERSION}\"{features} }}\n", pinned.name));
    }
    manifest.push_str("\n[workspace]\n");
    manifest
}

/// Where cargo keeps the downloaded `.crate` of package `name` [`VERSION`],
/// found from its unpacked folder in `cargo metadata` output: cargo keeps
/// `registry/src/INDEX/NAME-VERSION/` and `registry/cache/INDEX/NAME-VERSION.crate`.
fn archive_of(metadata: &str, name: &str) -> Result<PathBuf> {
    let metadata: serde_json::Value = serde_json::from_str(metadata).context("cargo metadata printed no JSON")?;
    let packages = metadata["packages"].as_array().context("cargo metadata lists no packages")?;
    let package = packages
        .iter()
        .find(|package| package["name"] == name && package["version"] == VERSION)
        .with_context(|| format!("cargo metadata does not list {name} {VERSION}"))?;
    let manifest =
        Path::new(package["manifest_path"].as_str().with_context(|| format!("{name} has no manifest_path"))?);
    archive_beside(manifest).with_context(|| format!("cannot tell where cargo keeps {name} {VERSION}'s .crate"))
}

/// `registry/cache/INDEX/NAME-VERSION.crate` for the manifest
/// `registry/src/INDEX/NAME-VERSION/Cargo.toml`.
fn archive_beside(manifest: &Path) -> Option<PathBuf> {
    let unpacked = manifest.parent()?;
    let index = unpacked.parent()?;
    let registry = index.parent()?.parent()?;
    let file = format!("{}.crate", unpacked.file_name()?.to_str()?);
    Some(registry.join("cache").join(index.file_name()?).join(file))
}

/// The lowercase hex SHA-256 of `bytes`.
pub fn sha256_hex(bytes: &[u8]) -> String {
    Sha256::digest(bytes).iter().map(|byte| format!("{byte:02x}")).collect()
}

/// The bytes of `archive`, if their SHA-256 is `pinned`'s; otherwise an
/// error naming both digests.
pub fn read_checked(archive: &Path, pinned: &PinnedCrate) -> Result<Vec<u8>> {
    let bytes = std::fs::read(archive).with_context(|| format!("failed to read {}", archive.display()))?;
    let found = sha256_hex(&bytes);
    ensure!(
        found == pinned.sha256,
        "{} {VERSION} from {} is not the source the image build was written for: its SHA-256 is {found}, \
         the build expects {} (boot/image/src/sources.rs); remove the file to have cargo fetch it again",
        pinned.name,
        archive.display(),
        pinned.sha256
    );
    Ok(bytes)
}

/// Unpacks the checked `.crate` bytes of `pinned` (a gzipped tar of one
/// folder, `NAME-VERSION/`) into `to`, which must not exist yet.
pub fn unpack(archive: &[u8], pinned: &PinnedCrate, to: &Path) -> Result<()> {
    let scratch = to.with_extension("unpacking");
    if scratch.exists() {
        std::fs::remove_dir_all(&scratch).with_context(|| format!("failed to remove {}", scratch.display()))?;
    }
    std::fs::create_dir_all(&scratch).with_context(|| format!("failed to create {}", scratch.display()))?;
    // `unpack` keeps every entry inside the folder (it refuses `..` and
    // absolute paths).
    tar::Archive::new(flate2::read::GzDecoder::new(archive))
        .unpack(&scratch)
        .with_context(|| format!("failed to unpack {} {VERSION}", pinned.name))?;
    let top = scratch.join(format!("{}-{VERSION}", pinned.name));
    ensure!(
        top.join("Cargo.toml").is_file(),
        "{} {VERSION}'s archive has no {}/Cargo.toml",
        pinned.name,
        top.display()
    );
    std::fs::rename(&top, to).with_context(|| format!("failed to move {} to {}", top.display(), to.display()))?;
    std::fs::remove_dir_all(&scratch).with_context(|| format!("failed to remove {}", scratch.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bootloaders_pin_is_the_checksum_in_the_workspace_lock_file() {
        let lock = include_str!("../../../Cargo.lock");
        let entry = format!(
            "name = \"bootloader\"\nversion = \"{VERSION}\"\n\
             source = \"registry+https://github.com/rust-lang/crates.io-index\"\nchecksum = \"{}\"\n",
            BOOTLOADER.sha256
        );
        assert!(lock.contains(&entry), "Cargo.lock's bootloader {VERSION} checksum differs from the pin");
    }

    #[test]
    fn the_archive_is_found_beside_cargos_unpacked_folder() {
        let manifest =
            Path::new("/home/u/.cargo/registry/src/index.crates.io-1949cf8c6b5b557f/bootloader-0.11.17/Cargo.toml");
        assert_eq!(
            archive_beside(manifest).unwrap(),
            Path::new("/home/u/.cargo/registry/cache/index.crates.io-1949cf8c6b5b557f/bootloader-0.11.17.crate")
        );
    }

    #[test]
    fn bytes_other_than_the_pinned_ones_are_refused_naming_both_digests() {
        let dir = tempfile::tempdir().unwrap();
        let archive = dir.path().join("bootloader-x86_64-uefi-0.11.17.crate");
        std::fs::write(&archive, b"abc").unwrap();
        let pinned =
            PinnedCrate { name: "x", sha256: "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad" };
        assert_eq!(read_checked(&archive, &pinned).unwrap(), b"abc", "SHA-256(\"abc\") from FIPS 180-2");
        let error = read_checked(&archive, &UEFI_LOADER).unwrap_err().to_string();
        assert!(
            error.contains("its SHA-256 is ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"),
            "{error}"
        );
        assert!(error.contains(&format!("the build expects {}", UEFI_LOADER.sha256)), "{error}");
    }

    #[test]
    fn a_crate_archive_unpacks_to_its_folder_and_nothing_else() {
        let dir = tempfile::tempdir().unwrap();
        let mut tar = tar::Builder::new(flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast()));
        for (path, text) in [("x-0.11.17/Cargo.toml", "[package]\n"), ("x-0.11.17/src/main.rs", "fn main() {}\n")] {
            let mut header = tar::Header::new_gnu();
            header.set_size(text.len() as u64);
            header.set_mode(0o644);
            header.set_cksum();
            tar.append_data(&mut header, path, text.as_bytes()).unwrap();
        }
        let archive = tar.into_inner().unwrap().finish().unwrap();
        let pinned = PinnedCrate { name: "x", sha256: "" };
        let to = dir.path().join("copy");
        unpack(&archive, &pinned, &to).unwrap();
        assert_eq!(std::fs::read_to_string(to.join("src/main.rs")).unwrap(), "fn main() {}\n");
        let left: Vec<_> = std::fs::read_dir(dir.path()).unwrap().map(|e| e.unwrap().file_name()).collect();
        assert_eq!(left, ["copy"], "the scratch folder is gone");
    }
}
