//! The bootable image's build, for the xtask (`cargo xtask image`) and the
//! test harness alike: the kernel built with the pinned nightly, and
//! `boot` (the image writer, `boot/src/main.rs`) built against the copy of
//! `bootloader` whose BIOS stage 2 leaves the card in text mode and whose
//! UEFI loader checks the kernel ([`bootloader`]), then run to write one
//! raw image that boots under a BIOS (or a UEFI firmware's CSM), under
//! UEFI, and under UEFI Secure Boot through shim ([`secure_boot`]).
//!
//! ```no_run
//! # fn main() -> anyhow::Result<()> {
//! let image = boot_image::build_image()?;
//! println!("dd if={} of=/dev/sdX bs=4M", image.display());
//! # Ok(())
//! # }
//! ```

pub mod bootloader;
pub mod cargo;
pub mod patched_copy;
pub mod provenance;
pub mod secure_boot;
pub mod sources;
pub mod tree;

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

use anyhow::{Context, Result};

use crate::cargo::NightlyBuild;
use crate::patched_copy::PatchedBootloader;
use crate::secure_boot::debian::{self, Unpacked};
use crate::secure_boot::key::{self, SigningKey};
use crate::secure_boot::{
    loader, shim, Enrollment, CERTIFICATE_PATH, HASH_ENROLL_PATH, LOADER_PATH, MOK_MANAGER_PATH, SHIM_PATH,
};
use install::ensure_toolchain;
use install::run_streaming;
use install::workspace;
use install::{once_per_process, Failure};

pub use provenance::IMAGE_ENV;

/// The raw image, built once per process (or taken from [`IMAGE_ENV`] if
/// it is this tree's build, or [`provenance::MEANT_ENV`] says it is
/// meant), its loader to be enrolled by its hash ([`Enrollment::Hash`]).
/// Installs the pinned nightly first when it is missing.
pub fn build_image() -> Result<PathBuf> {
    static IMAGE: OnceLock<Result<PathBuf, Failure>> = OnceLock::new();
    once_per_process(&IMAGE, || {
        let given = provenance::image_given(std::env::var_os(IMAGE_ENV), std::env::var_os(provenance::MEANT_ENV))?;
        if let Some(image) = given {
            return Ok(image);
        }
        build_image_with(&Enrollment::Hash, &debian_packages()?, &image_path())
    })
}

/// Builds the raw image at `image`: the loader enrolled as `enrollment`
/// says, shim and MokManager from `debian`.
pub fn build_image_with(enrollment: &Enrollment, debian: &Unpacked, image: &Path) -> Result<PathBuf> {
    key::warn_of_old_key();
    let _turn = image_build_turn()?;
    let sources = provenance::sources_digest(workspace::root())?;
    for mut build in stage_builds()? {
        run_streaming(&mut build).context("failed to build the kernel or the image writer")?;
    }
    PatchedBootloader::in_target_dir().ensure_used()?;
    write_image(enrollment, debian, image)?;
    provenance::record(image, &sources)?;
    eprintln!("image: built {}", image.display());
    Ok(image.to_path_buf())
}

/// Waits until no other process of the workspace is building an image
/// (test binaries run side by side, and each build writes the patched
/// bootloader and its lock file in the one target folder), then holds the
/// turn until the file returned is dropped. [`build_image_with`] takes
/// it; a caller of [`stage_builds`] takes it itself.
pub fn image_build_turn() -> Result<std::fs::File> {
    install::turn("image-build")
}

/// The builds of the kernel and of the image writer (against the patched
/// bootloader, made first if need be, else checked), in order. Both are
/// no-ops when nothing changed: tests/tests/image_build.rs runs them twice.
pub fn stage_builds() -> Result<Vec<Command>> {
    stage_builds_with(&PatchedBootloader::in_target_dir())
}

/// [`stage_builds`] against the patched copy `patched` (a test's, for
/// one): it is made first if need be, else checked file by file, and a
/// copy edited by hand stops the build here, before anything compiles.
pub fn stage_builds_with(patched: &PatchedBootloader) -> Result<Vec<Command>> {
    ensure_toolchain()?;
    patched_copy::prepare(patched)?;
    eprintln!("image: building the kernel and the image writer (the first build takes minutes)");
    let mut writer = NightlyBuild::IMAGE_WRITER.command();
    patched.configure(&mut writer)?;
    Ok(vec![NightlyBuild::KERNEL.command(), writer])
}

/// The key `--enroll key` signs with ([`SigningKey::users`]), unlocked
/// with `passphrase` if given, else asked for.
pub fn users_signing_key(passphrase: Option<String>) -> Result<SigningKey> {
    SigningKey::users(&own_key_dir(), passphrase)
}

/// A key of one's own (`cargo xtask image --key --cert`): `key` (PEM,
/// encrypted) and `cert` (PEM or DER), unlocked with `passphrase` if
/// given, else asked for.
pub fn own_signing_key(key: &Path, cert: &Path, passphrase: Option<String>) -> Result<SigningKey> {
    SigningKey::own(key, cert, passphrase, &own_key_dir())
}

/// Where a certificate of one's own given in DER is converted to PEM.
fn own_key_dir() -> PathBuf {
    secure_boot_dir().join("own-key")
}

/// Where the Secure Boot pieces are fetched and made.
fn secure_boot_dir() -> PathBuf {
    workspace::nightly_target_dir().join("secure-boot")
}

/// Debian's packages the image takes shim, MokManager and sbsign from, in
/// the state folder (root runs the unpacked sbsign: [`workspace::state_dir`]).
pub fn debian_packages() -> Result<Unpacked> {
    Ok(Unpacked::in_dir(workspace::state_dir()?.join("secure-boot-debian")))
}

/// Writes `image`: the loader out of the writer, checked, the digests in,
/// then signed with the user's key or left for its hash to be enrolled;
/// then the image with shim, MokManager, the loader and the certificate
/// (or a copy of the loader to enroll) on its FAT ([`image_files`]).
fn write_image(enrollment: &Enrollment, debian: &Unpacked, image: &Path) -> Result<()> {
    std::fs::create_dir_all(secure_boot_dir())
        .with_context(|| format!("failed to create {}", secure_boot_dir().display()))?;
    let work = tempfile::Builder::new()
        .prefix("build-")
        .tempdir_in(secure_boot_dir())
        .with_context(|| format!("failed to create a folder in {}", secure_boot_dir().display()))?;
    let work = work.path();
    let writer = NightlyBuild::IMAGE_WRITER.artifact();
    run_streaming(Command::new(&writer).arg("loader").arg(work)).context("failed to write the UEFI loader")?;
    let kernel = NightlyBuild::KERNEL.artifact();
    let boot_json = work.join("boot.json");
    let mut loader_bytes = read(&work.join("loader.efi"))?;
    loader::check_sbat(&loader_bytes)?;
    loader::check_refusals(&loader_bytes)?;
    loader::write_digests(&mut loader_bytes, &read(&kernel)?, &read(&boot_json)?)?;
    let unsigned = work.join("grubx64-unsigned.efi");
    std::fs::write(&unsigned, &loader_bytes).with_context(|| format!("failed to write {}", unsigned.display()))?;
    let (files, said) = image_files(enrollment, debian, work, &unsigned)?;
    let mut write = Command::new(&writer);
    write.arg("image").arg(&kernel).arg(&boot_json).arg(image);
    for (fat_path, file) in &files {
        let mut arg = std::ffi::OsString::from(format!("{fat_path}="));
        arg.push(file);
        write.arg(arg);
    }
    run_streaming(&mut write).context("failed to write the disk image")?;
    eprintln!("{said}");
    Ok(())
}

/// The bytes of `path`.
fn read(path: &Path) -> Result<Vec<u8>> {
    std::fs::read(path).with_context(|| format!("failed to read {}", path.display()))
}

/// The files on the image's FAT, by their paths there, and what the build
/// says of them: those of [`secure_boot_files`]; or, where Debian's shim
/// and MokManager cannot be had ([`debian::Unobtainable`]: no apt-get, no
/// network, and nothing fetched before), for a loader enrolled by its hash,
/// the `unsigned` loader alone, where a UEFI firmware starts it without
/// shim (the image boots under a BIOS and under UEFI with Secure Boot off,
/// and says so). A loader asked to be signed with a key is never handed
/// out unsigned: that is an error, as is any other failure (lists or a
/// package that fail their check, for one).
fn image_files(
    enrollment: &Enrollment,
    debian: &Unpacked,
    work: &Path,
    unsigned: &Path,
) -> Result<(Vec<(&'static str, PathBuf)>, String)> {
    let error = match secure_boot_files(enrollment, debian, work, unsigned) {
        Ok((files, said)) => return Ok((files, format!("image: UEFI Secure Boot: {said}"))),
        Err(error) => error,
    };
    match (enrollment, error.downcast_ref::<debian::Unobtainable>()) {
        (Enrollment::Hash, Some(why)) => {
            let said = format!(
                "image: no Secure Boot: Debian's shim and MokManager cannot be had ({why}), so the loader is on \
                 the image alone: it boots under a BIOS and under UEFI with Secure Boot off, not on (build again \
                 where apt-get can reach Debian's archive for that)"
            );
            Ok((vec![(SHIM_PATH, unsigned.to_path_buf())], said))
        }
        (Enrollment::Key(_), Some(_)) => Err(error.context(
            "refusing to build the image: --enroll key asks for a loader signed with your key, and Debian's shim, \
             MokManager and sbsign cannot be had",
        )),
        _ => Err(error),
    }
}

/// The files that make the image boot under Secure Boot, by their paths
/// on the FAT: Debian's shim and MokManager, and the `unsigned` loader
/// with its copy to enroll by hash, or signed with the user's key (in
/// `work`) with the certificate to enroll; and what the build says of
/// them.
fn secure_boot_files(
    enrollment: &Enrollment,
    debian: &Unpacked,
    work: &Path,
    unsigned: &Path,
) -> Result<(Vec<(&'static str, PathBuf)>, String)> {
    let (shim, mok_manager) = (debian.get(debian::SHIM)?, debian.get(debian::MOK_MANAGER)?);
    let shim_bytes = read(&shim)?;
    let shim_version = shim::version(&shim_bytes)?;
    let mut files = vec![(SHIM_PATH, shim), (MOK_MANAGER_PATH, mok_manager)];
    let source = format!(
        "shim {}.{} from Debian's shim-signed {}, MokManager from shim-helpers-amd64-signed {}",
        shim_version.0,
        shim_version.1,
        debian.version(debian::SHIM.package)?,
        debian.version(debian::MOK_MANAGER.package)?
    );
    let enroll = match enrollment {
        Enrollment::Hash => {
            let hash = loader::authenticode_sha256(&read(unsigned)?)?;
            files.extend([(LOADER_PATH, unsigned.to_path_buf()), (HASH_ENROLL_PATH, unsigned.to_path_buf())]);
            format!(
                "the loader is enrolled by its SHA-256 {}: on a PC with Secure Boot on, choose MokManager's \
                 \"Enroll hash from disk\", then {HASH_ENROLL_PATH}, and check that the hash it shows is this \
                 one; each build is enrolled anew (docs/secure-boot.md)",
                hex(&hash)
            )
        }
        Enrollment::Key(key) => {
            shim::ensure_boots_key_signed_loader(&shim_bytes, &source)?;
            let signed = work.join("grubx64.efi");
            loader::sign(&debian.get(debian::SBSIGN)?, key, unsigned, &signed)?;
            let der = key.certificate_der()?;
            let certificate = work.join(CERTIFICATE_PATH);
            std::fs::write(&certificate, &der).with_context(|| format!("failed to write {}", certificate.display()))?;
            files.extend([(LOADER_PATH, signed), (CERTIFICATE_PATH, certificate)]);
            format!(
                "the loader is signed with your key, certificate {} (SHA-256 fingerprint {}), on the image as \
                 {CERTIFICATE_PATH}: enroll it once with MokManager's \"Enroll key from disk\" (docs/secure-boot.md)",
                key.cert.display(),
                key::fingerprint(&der)
            )
        }
    };
    Ok((files, format!("{source}; {enroll}")))
}

/// Bytes as lowercase hex.
pub fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|byte| format!("{byte:02x}")).collect()
}

/// Where [`build_image`] writes the image.
pub fn image_path() -> PathBuf {
    workspace::nightly_target_dir().join("polylab.img")
}

#[cfg(test)]
mod tests {
    use install::PrivateApt;

    use super::*;

    #[test]
    fn without_debians_shim_an_image_enrolled_by_hash_is_built_without_secure_boot_and_one_signed_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        // Port 9 (discard) of this machine: nothing answers there.
        let offline =
            PrivateApt::sources_only(dir.path().join("apt"), &["deb http://127.0.0.1:9/debian bookworm main"]);
        let debian = Unpacked::from_archive(dir.path().join("debian"), offline);
        let unsigned = dir.path().join("grubx64-unsigned.efi");
        std::fs::write(&unsigned, "a loader").unwrap();
        let (files, said) = image_files(&Enrollment::Hash, &debian, dir.path(), &unsigned).unwrap();
        assert_eq!(files, [(SHIM_PATH, unsigned.clone())]);
        assert!(said.starts_with("image: no Secure Boot: Debian's shim and MokManager cannot be had"), "{said}");
        let key = SigningKey::in_folder(&dir.path().join("key"), Some("a passphrase for the tests".into())).unwrap();
        let error = image_files(&Enrollment::Key(key), &debian, dir.path(), &unsigned).unwrap_err();
        assert!(format!("{error:#}").starts_with("refusing to build the image: --enroll key asks for"), "{error:#}");
    }
}
