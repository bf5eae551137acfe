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

pub mod apt;
pub mod bootloader;
pub mod cargo;
pub mod once;
pub mod process;
pub mod secure_boot;
pub mod sources;
pub mod toolchain;
pub mod workspace;

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

use anyhow::{ensure, Context, Result};

use crate::bootloader::PatchedBootloader;
use crate::cargo::NightlyBuild;
use crate::once::once_per_process;
use crate::process::run_streaming;
use crate::secure_boot::debian::{self, Unpacked};
use crate::secure_boot::key::{self, SigningKey};
use crate::secure_boot::{loader, CERTIFICATE_PATH, LOADER_PATH, MOK_MANAGER_PATH, SHIM_PATH};
use crate::toolchain::ensure_toolchain;

/// Names a prebuilt image to use instead of building one (`cargo xtask
/// test` builds once and hands it to every test binary this way). A
/// relative path is taken from the workspace root, since test binaries run
/// in their package's directory.
pub const IMAGE_ENV: &str = "POLYLAB_IMAGE";

/// The raw image, built once per process (or taken from [`IMAGE_ENV`]),
/// its loader signed with the user's key ([`SigningKey::users`]).
/// Installs the pinned nightly first when it is missing.
pub fn build_image() -> Result<PathBuf> {
    static IMAGE: OnceLock<Result<PathBuf, String>> = OnceLock::new();
    once_per_process(&IMAGE, || {
        if let Some(image) = std::env::var_os(IMAGE_ENV) {
            let image = workspace::root().join(image);
            ensure!(image.is_file(), "{IMAGE_ENV} names {}, which is not a file", image.display());
            eprintln!("image: using {} from {IMAGE_ENV}", image.display());
            return Ok(image);
        }
        build_image_signed_by(&SigningKey::users(&own_key_dir())?)
    })
}

/// The raw image with its loader signed by `key`.
pub fn build_image_signed_by(key: &SigningKey) -> Result<PathBuf> {
    for mut build in stage_builds()? {
        run_streaming(&mut build).context("failed to build the kernel or the image writer")?;
    }
    PatchedBootloader::in_target_dir().ensure_used()?;
    let image = image_path();
    write_image(key, &image)?;
    eprintln!("image: built {}", image.display());
    Ok(image)
}

/// The builds of the kernel and of the image writer (against the patched
/// bootloader, made first if need be), in order. Both are no-ops when
/// nothing changed: tests/tests/image_build.rs runs them twice.
pub fn stage_builds() -> Result<Vec<Command>> {
    ensure_toolchain()?;
    let patched = bootloader::prepare()?;
    eprintln!("image: building the kernel and the image writer (the first build takes minutes)");
    let mut writer = NightlyBuild::IMAGE_WRITER.command();
    patched.configure(&mut writer)?;
    Ok(vec![NightlyBuild::KERNEL.command(), writer])
}

/// A key of one's own (`cargo xtask image --key --cert`): `key` (PEM)
/// and `cert` (PEM or DER).
pub fn own_signing_key(key: &Path, cert: &Path) -> Result<SigningKey> {
    SigningKey::own(key, cert, &own_key_dir())
}

/// Where a certificate of one's own given in DER is converted to PEM.
fn own_key_dir() -> PathBuf {
    secure_boot_dir().join("own-key")
}

/// Where the Secure Boot pieces are fetched and made.
fn secure_boot_dir() -> PathBuf {
    workspace::nightly_target_dir().join("secure-boot")
}

/// Debian's packages the image takes shim, MokManager and sbsign from.
pub fn debian_packages() -> Unpacked {
    Unpacked::in_dir(secure_boot_dir().join("debian"))
}

/// Writes `image`: the loader out of the writer, the digests in, signed
/// with `key`, then the image with shim, MokManager, the signed loader and
/// the certificate on its FAT. On a machine without apt (and nothing
/// unpacked before), Debian's shim, MokManager and sbsign cannot be had:
/// the loader goes on the FAT unsigned, where a UEFI firmware starts it
/// without shim, and the image boots everywhere but under Secure Boot.
fn write_image(key: &SigningKey, image: &Path) -> Result<()> {
    let debian = debian_packages();
    let work = secure_boot_dir().join("build");
    std::fs::create_dir_all(&work).with_context(|| format!("failed to create {}", work.display()))?;
    let writer = NightlyBuild::IMAGE_WRITER.artifact();
    run_streaming(Command::new(&writer).arg("loader").arg(&work)).context("failed to write the UEFI loader")?;
    let kernel = NightlyBuild::KERNEL.artifact();
    let boot_json = work.join("boot.json");
    let read = |path: &Path| std::fs::read(path).with_context(|| format!("failed to read {}", path.display()));
    let mut loader_bytes = read(&work.join("loader.efi"))?;
    loader::check_sbat(&loader_bytes)?;
    loader::write_digests(&mut loader_bytes, &read(&kernel)?, &read(&boot_json)?)?;
    let unsigned = work.join("grubx64-unsigned.efi");
    std::fs::write(&unsigned, &loader_bytes).with_context(|| format!("failed to write {}", unsigned.display()))?;
    let mut write = Command::new(&writer);
    write.arg("image").arg(&kernel).arg(&boot_json).arg(image);
    let files = if debian.obtainable() {
        secure_boot_files(&debian, key, &work, &unsigned)?
    } else {
        eprintln!(
            "image: no Secure Boot: this machine has no apt-get to take Debian's shim, MokManager and sbsign from, \
             so the loader is on the image unsigned: it boots under a BIOS and under UEFI with Secure Boot off, not \
             on (build the image on a Debian or Ubuntu machine for that)"
        );
        vec![(SHIM_PATH, unsigned)]
    };
    for (fat_path, file) in files {
        let mut arg = std::ffi::OsString::from(format!("{fat_path}="));
        arg.push(file);
        write.arg(arg);
    }
    run_streaming(&mut write).context("failed to write the disk image")
}

/// The files that make the image boot under Secure Boot, by their paths
/// on the FAT: Debian's shim and MokManager, the `unsigned` loader signed
/// with `key` (in `work`), and the certificate to enroll.
fn secure_boot_files(
    debian: &Unpacked,
    key: &SigningKey,
    work: &Path,
    unsigned: &Path,
) -> Result<Vec<(&'static str, PathBuf)>> {
    let (shim, mok_manager, sbsign) =
        (debian.get(debian::SHIM)?, debian.get(debian::MOK_MANAGER)?, debian.get(debian::SBSIGN)?);
    let signed = work.join("grubx64.efi");
    loader::sign(&sbsign, key, unsigned, &signed)?;
    let der = key.certificate_der()?;
    let certificate = work.join(CERTIFICATE_PATH);
    std::fs::write(&certificate, &der).with_context(|| format!("failed to write {}", certificate.display()))?;
    eprintln!(
        "image: UEFI Secure Boot: shim from Debian's shim-signed {}, MokManager from shim-helpers-amd64-signed {}; \
         the loader signed with your key, certificate {} (SHA-256 fingerprint {}), on the image as {CERTIFICATE_PATH}: \
         enroll it once with MokManager (docs/boot.md)",
        debian.version(debian::SHIM.package)?,
        debian.version(debian::MOK_MANAGER.package)?,
        key.cert.display(),
        key::fingerprint(&der)
    );
    Ok(vec![(SHIM_PATH, shim), (LOADER_PATH, signed), (MOK_MANAGER_PATH, mok_manager), (CERTIFICATE_PATH, certificate)])
}

/// Where [`build_image`] writes the image.
fn image_path() -> PathBuf {
    workspace::nightly_target_dir().join("polylab.img")
}
