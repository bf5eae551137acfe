//! The image under UEFI Secure Boot: OVMF's Secure Boot build with
//! Microsoft's keys (as a PC ships), which trusts Debian's shim, which
//! trusts the keys in its MOK list. Each test boots the image (or a copy
//! with one file of its FAT replaced) with a variable store whose MOK list
//! holds the user's certificate, another one or none, and says what must
//! happen, reading shim's, MokManager's and the loader's words on COM1
//! (OVMF copies its console there):
//!
//! - the user's key enrolled: the kernel says READY and every page is
//!   exact on QEMU's screendump (std and cirrus);
//! - no key, or another key: shim refuses the loader (and starts
//!   MokManager);
//! - the loader without its signature: shim refuses it;
//! - the kernel or boot.json changed after signing: the signed loader
//!   refuses it;
//! - the first boot as a user lives it: MokManager driven with keys
//!   enrolls the certificate from the stick, and after the reboot the
//!   kernel says READY and draws.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Duration;

use anyhow::{ensure, Context, Result};
use boot_image::secure_boot::key::SigningKey;
use boot_image::secure_boot::{debian, CERTIFICATE_PATH, LOADER_PATH};
use harness::checks::{dump_matches_host_render, screen_matches_dump};
use harness::process::output_of;
use harness::secure_boot::{variables_with_mok_list, FatImage};
use harness::{build_image, Adapter, Qemu, QemuOptions};
use protocol::{Firmware, Video};
use scenes::builtin;

/// Longest wait for the first words of shim, MokManager or the loader:
/// OVMF's Secure Boot build under TCG, with SMM, on a loaded machine.
const FIRMWARE_TIMEOUT: Duration = Duration::from_secs(180);
/// Longest wait for the next screen once a key is pressed.
const SCREEN_TIMEOUT: Duration = Duration::from_secs(60);
/// How long a refused boot is watched for a READY that must not come.
const NO_READY_WATCH: Duration = Duration::from_secs(10);

/// shim's words when the loader's signature is not trusted (none, or a
/// key not in the MOK list).
const SHIM_REFUSES: &str = "Verification failed: (0x1A) Security Violation";
/// The loader's words, start and end, when a file on the stick is not the
/// one it was signed for.
const LOADER_REFUSES: (&str, &str) = ("polylab: refusing to boot.", "write the image again.");

/// A folder of the test's own, removed when it ends.
fn scratch() -> Result<tempfile::TempDir> {
    tempfile::Builder::new().prefix("polylab-secure-boot-").tempdir().context("failed to create a temporary folder")
}

/// The user's certificate, as the image carries it, in `dir`.
fn users_certificate(image: &Path, dir: &Path) -> Result<PathBuf> {
    let certificate = dir.join("user.cer");
    std::fs::write(&certificate, FatImage::open(image)?.read(CERTIFICATE_PATH)?)
        .with_context(|| format!("failed to write {}", certificate.display()))?;
    Ok(certificate)
}

/// Starts `image` under Secure Boot on `adapter`, the MOK list holding
/// `certificates`.
fn boot(image: &Path, certificates: &[&Path], adapter: Adapter, allow_reboot: bool, dir: &Path) -> Result<Qemu> {
    let variables = dir.join("OVMF_VARS_4M.ms.fd");
    variables_with_mok_list(certificates, &variables)?;
    let options =
        QemuOptions { firmware: Firmware::Uefi, secure_boot: true, adapter, allow_reboot, ..QemuOptions::default() };
    Qemu::spawn_with_variables(image, options, &variables)
}

/// Waits for READY and checks it: UEFI, the card, mode 13h with every
/// register read back as written.
fn ready_in_mode_13h(qemu: &mut Qemu, adapter: Adapter) -> Result<()> {
    let ready = qemu.console.wait_ready()?;
    ensure!(ready.firmware == Firmware::Uefi, "READY names the firmware {:?}", ready.firmware);
    ensure!(ready.display == adapter.pci_id(), "READY names the display {:?}", ready.display);
    ensure!(ready.video == Video::Vga13h { mismatches: 0 }, "READY says {:?}", ready.video);
    qemu.ready = ready;
    Ok(())
}

/// `image` with the user's key enrolled: READY, then every demo page
/// drawn as the host renders it and exact on QEMU's screendump.
fn enrolled_key_boots_and_every_page_is_exact(adapter: Adapter) -> Result<()> {
    let (image, dir) = (build_image()?, scratch()?);
    let certificate = users_certificate(&image, dir.path())?;
    let mut qemu = boot(&image, &[&certificate], adapter, false, dir.path())?;
    ready_in_mode_13h(&mut qemu, adapter)?;
    for page in builtin::ALL {
        let dump = dump_matches_host_render(&mut qemu.console, page.name, page.method)?;
        let name = format!("secure-boot.{}.{}", adapter.name(), page.name);
        screen_matches_dump(&name, &dump, &qemu.screendump()?, &qemu.ready.video)?;
    }
    eprintln!(
        "harness: Secure Boot, {}: {}; {} pages exact on the screen",
        adapter.name(),
        qemu.ready,
        builtin::ALL.len()
    );
    Ok(())
}

#[test]
fn with_the_users_key_enrolled_std_boots_and_every_page_is_exact_on_the_screen() -> Result<()> {
    enrolled_key_boots_and_every_page_is_exact(Adapter::Std)
}

#[test]
fn with_the_users_key_enrolled_cirrus_boots_and_every_page_is_exact_on_the_screen() -> Result<()> {
    enrolled_key_boots_and_every_page_is_exact(Adapter::Cirrus)
}

/// Boots `image` with `certificates` enrolled and expects `reason` on
/// COM1, then `until` (the end of what is said, if not empty), with no READY before it,
/// nor for a while after; returns what was said.
fn refused(image: &Path, certificates: &[&Path], (reason, until): (&str, &str), dir: &Path) -> Result<String> {
    let mut qemu = boot(image, certificates, Adapter::Std, false, dir)?;
    let (which, _) = qemu.console.wait_for_first_text(&[reason, "@READY"], FIRMWARE_TIMEOUT)?;
    ensure!(which == 0, "the kernel said READY, and nothing said `{reason}`");
    let rest = if until.is_empty() { String::new() } else { qemu.console.wait_for_text(until, SCREEN_TIMEOUT)? };
    let after = qemu.console.wait_for_text("@READY", NO_READY_WATCH);
    ensure!(after.is_err(), "the kernel said READY after `{reason}`");
    Ok(format!("{reason}{rest}"))
}

#[test]
fn with_no_key_enrolled_shim_refuses_the_loader() -> Result<()> {
    let (image, dir) = (build_image()?, scratch()?);
    let said = refused(&image, &[], (SHIM_REFUSES, ""), dir.path())?;
    eprintln!("harness: Secure Boot, no key enrolled: shim says `{said}`");
    Ok(())
}

#[test]
fn with_another_key_enrolled_shim_refuses_the_loader() -> Result<()> {
    let (image, dir) = (build_image()?, scratch()?);
    let other = SigningKey::in_folder(&dir.path().join("other-key"))?;
    let said = refused(&image, &[&other.cert], (SHIM_REFUSES, ""), dir.path())?;
    eprintln!("harness: Secure Boot, another key enrolled: shim says `{said}`");
    Ok(())
}

#[test]
fn a_loader_without_its_signature_is_refused_by_shim() -> Result<()> {
    let (image, dir) = (build_image()?, scratch()?);
    let certificate = users_certificate(&image, dir.path())?;
    let mut fat = FatImage::open(&image)?;
    let loader = dir.path().join("loader.efi");
    let signed = fat.read(LOADER_PATH)?;
    std::fs::write(&loader, &signed)?;
    // sbattach strips the signature in place.
    let sbattach = boot_image::debian_packages().get(debian::SBATTACH)?;
    output_of(Command::new(sbattach).arg("--remove").arg(&loader))?;
    let unsigned = std::fs::read(&loader)?;
    ensure!(unsigned.len() < signed.len(), "sbattach --remove left the loader's {} bytes", signed.len());
    fat.replace(LOADER_PATH, &unsigned)?;
    let copy = dir.path().join("unsigned-loader.img");
    fat.write(&copy)?;
    let said = refused(&copy, &[&certificate], (SHIM_REFUSES, ""), dir.path())?;
    eprintln!("harness: Secure Boot, the loader's signature removed: shim says `{said}`");
    Ok(())
}

/// `image` with `fat_path` one byte longer (a kernel ELF still loads with
/// a byte after its end; JSON parses with a space after it), the user's
/// key enrolled: the signed loader refuses it.
fn changed_after_signing_is_refused_by_the_loader(fat_path: &str, extra: u8) -> Result<()> {
    let (image, dir) = (build_image()?, scratch()?);
    let certificate = users_certificate(&image, dir.path())?;
    let mut fat = FatImage::open(&image)?;
    let mut changed = fat.read(fat_path)?;
    changed.push(extra);
    fat.replace(fat_path, &changed)?;
    let copy = dir.path().join("changed.img");
    fat.write(&copy)?;
    let said = refused(&copy, &[&certificate], LOADER_REFUSES, dir.path())?;
    ensure!(said.contains(&format!("{fat_path} is not the file this loader was signed for")), "{said}");
    eprintln!("harness: Secure Boot, {fat_path} changed after signing: the loader says `{said}`");
    Ok(())
}

#[test]
fn a_kernel_swapped_after_signing_is_refused_by_the_loader() -> Result<()> {
    changed_after_signing_is_refused_by_the_loader("kernel-x86_64", 0)
}

#[test]
fn a_boot_json_changed_after_signing_is_refused_by_the_loader() -> Result<()> {
    changed_after_signing_is_refused_by_the_loader("boot.json", b' ')
}

/// The first boot of a new stick on a PC with Secure Boot on, as the
/// README tells it: shim refuses the loader, MokManager comes up, and the
/// keys a user presses enroll the certificate from the stick; after the
/// reboot the show plays. Each screen waits for its words on COM1 before
/// its key is pressed, and is saved as a PNG in
/// target/secure-boot-screens (the README's pictures).
#[test]
fn the_first_boot_enrolls_the_key_with_mokmanager_and_boots_after_the_reboot() -> Result<()> {
    let (image, dir) = (build_image()?, scratch()?);
    let mut qemu = boot(&image, &[], Adapter::Std, true, dir.path())?;
    let screens = harness::workspace::target_dir().join("secure-boot-screens");
    std::fs::create_dir_all(&screens).with_context(|| format!("failed to create {}", screens.display()))?;
    // (words on the screen, picture name, keys to press)
    let steps: [(&str, &str, &[&str]); 8] = [
        (SHIM_REFUSES, "1-shim-refuses", &["ret"]),
        ("Press any key to perform MOK management", "2-press-any-key", &["ret"]),
        ("Enroll key from disk", "3-mok-management", &["down", "ret"]),
        ("Select Key", "4-select-volume", &["ret"]),
        (CERTIFICATE_PATH, "5-select-certificate", &["ret"]),
        ("View key 0", "6-enroll-mok", &["down", "ret"]),
        ("Enroll the key(s)?", "7-enroll-the-keys", &["down", "ret"]),
        ("Reboot", "8-reboot", &["ret"]),
    ];
    for (i, (words, picture, keys)) in steps.into_iter().enumerate() {
        let timeout = if i == 0 { FIRMWARE_TIMEOUT } else { SCREEN_TIMEOUT };
        let (which, _) = qemu.console.wait_for_first_text(&[words, "@READY"], timeout)?;
        ensure!(which == 0, "the kernel said READY before `{words}`");
        // Let the screen finish drawing before it is saved and answered.
        std::thread::sleep(Duration::from_secs(1));
        qemu.screendump()?.write_png(&screens.join(format!("{picture}.png")))?;
        for key in keys {
            qemu.send_key(key)?;
            std::thread::sleep(Duration::from_millis(300));
        }
    }
    ready_in_mode_13h(&mut qemu, Adapter::Std)?;
    let page_1 = builtin::ABRASH38_1;
    let dump = dump_matches_host_render(&mut qemu.console, page_1.name, page_1.method)?;
    screen_matches_dump("secure-boot.first-boot.abrash38-1", &dump, &qemu.screendump()?, &qemu.ready.video)?;
    eprintln!("harness: Secure Boot, the first boot: key enrolled with MokManager, then {}", qemu.ready);
    Ok(())
}
