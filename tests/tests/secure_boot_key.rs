//! The image signed with a key (`--enroll key`) under UEFI Secure Boot:
//! a key made for these tests (encrypted under a passphrase, as the build
//! makes the user's), the image built with it, and OVMF's Secure Boot
//! build with Microsoft's keys and shim 16's MOK list holding its
//! certificate, another certificate or none:
//!
//! - the certificate enrolled: READY and page 1 exact on the screen;
//! - another key enrolled, or the loader's signature removed: shim
//!   refuses the loader;
//! - the first boot: MokManager driven with keys enrolls the certificate
//!   from the stick, and after the reboot the kernel says READY and draws.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

use anyhow::{ensure, Context, Result};
use boot_image::secure_boot::key::SigningKey;
use boot_image::secure_boot::{debian, Enrollment, CERTIFICATE_PATH, LOADER_PATH};
use harness::secure_boot::{
    boot, first_boot, ready_and_page_1_exact, refused, scratch, FatImage, MokEntry, Screen, SHIM_REFUSES,
};
use harness::Adapter;
use install::output_of;
use install::{once_per_process, Failure};

/// The passphrase of the tests' key (it signs nothing but these images).
const PASSPHRASE: &str = "polylab Secure Boot tests";

/// The image signed with the tests' key, built once per process in
/// target/secure-boot-key-test (its key made anew each time).
fn key_signed_image() -> Result<PathBuf> {
    static IMAGE: OnceLock<Result<PathBuf, Failure>> = OnceLock::new();
    once_per_process(&IMAGE, || {
        let dir = harness::workspace::target_dir().join("secure-boot-key-test");
        if dir.exists() {
            std::fs::remove_dir_all(&dir).with_context(|| format!("failed to remove {}", dir.display()))?;
        }
        let key = SigningKey::in_folder(&dir.join("key"), Some(PASSPHRASE.into()))?;
        let image = dir.join("polylab-key-signed.img");
        boot_image::build_image_with(&Enrollment::Key(key), &boot_image::debian_packages()?, &image)
    })
}

/// The certificate the image carries, in `dir`.
fn certificate_on(image: &Path, dir: &Path) -> Result<PathBuf> {
    let certificate = dir.join("key.cer");
    std::fs::write(&certificate, FatImage::open(image)?.read(CERTIFICATE_PATH)?)
        .with_context(|| format!("failed to write {}", certificate.display()))?;
    Ok(certificate)
}

#[test]
fn with_the_keys_certificate_enrolled_the_signed_loader_boots_and_draws() -> Result<()> {
    let (image, dir) = (key_signed_image()?, scratch()?);
    let certificate = certificate_on(&image, dir.path())?;
    let mut qemu = boot(&image, &[MokEntry::Certificate(&certificate)], Adapter::Std, false, dir.path())?;
    ready_and_page_1_exact(&mut qemu, "secure-boot.key.abrash38-1")?;
    eprintln!("harness: Secure Boot, the key's certificate enrolled: {}", qemu.ready);
    Ok(())
}

#[test]
fn with_another_key_enrolled_shim_refuses_the_signed_loader() -> Result<()> {
    let (image, dir) = (key_signed_image()?, scratch()?);
    let other = SigningKey::in_folder(&dir.path().join("other-key"), Some(PASSPHRASE.into()))?;
    let said = refused(&image, &[MokEntry::Certificate(&other.cert)], (SHIM_REFUSES, ""), dir.path())?;
    eprintln!("harness: Secure Boot, another key enrolled: shim says `{said}`");
    Ok(())
}

#[test]
fn a_loader_without_its_signature_is_refused_by_shim() -> Result<()> {
    let (image, dir) = (key_signed_image()?, scratch()?);
    let certificate = certificate_on(&image, dir.path())?;
    let mut fat = FatImage::open(&image)?;
    let loader = dir.path().join("loader.efi");
    let signed = fat.read(LOADER_PATH)?;
    std::fs::write(&loader, &signed)?;
    // sbattach strips the signature in place.
    let sbattach = boot_image::debian_packages()?.get(debian::SBATTACH)?;
    output_of(Command::new(sbattach).arg("--remove").arg(&loader))?;
    let unsigned = std::fs::read(&loader)?;
    ensure!(unsigned.len() < signed.len(), "sbattach --remove left the loader's {} bytes", signed.len());
    fat.replace(LOADER_PATH, &unsigned)?;
    let copy = dir.path().join("unsigned-loader.img");
    fat.write(&copy)?;
    let said = refused(&copy, &[MokEntry::Certificate(&certificate)], (SHIM_REFUSES, ""), dir.path())?;
    eprintln!("harness: Secure Boot, the loader's signature removed: shim says `{said}`");
    Ok(())
}

/// The first boot with a key-signed stick: MokManager's "Enroll key from
/// disk" takes the certificate at the stick's root; the screens are saved
/// in target/secure-boot-screens/key.
#[test]
fn the_first_boot_enrolls_the_certificate_with_mokmanager_and_boots_after_the_reboot() -> Result<()> {
    let image = key_signed_image()?;
    let screens: [Screen; 8] = [
        (SHIM_REFUSES, "1-shim-refuses", &["ret"]),
        ("Press any key to perform MOK management", "2-press-any-key", &["ret"]),
        ("Enroll key from disk", "3-mok-management", &["down", "ret"]),
        ("Select Key", "4-select-volume", &["ret"]),
        (CERTIFICATE_PATH, "5-select-certificate", &["ret"]),
        ("View key 0", "6-enroll-mok", &["down", "ret"]),
        ("Enroll the key(s)?", "7-enroll-the-keys", &["down", "ret"]),
        ("Reboot", "8-reboot", &["ret"]),
    ];
    let ready = first_boot(&image, &screens, "key")?;
    eprintln!("harness: Secure Boot, the first boot: the certificate enrolled with MokManager, then {ready}");
    Ok(())
}
