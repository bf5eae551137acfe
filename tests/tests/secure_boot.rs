//! The image under UEFI Secure Boot, its loader enrolled by its hash (the
//! default, `--enroll hash`): OVMF's Secure Boot build with Microsoft's
//! keys (as a PC ships), which trusts Debian's shim, which trusts the
//! hashes in its MOK list. Each test boots the image (or a copy with one
//! file of its FAT changed) with a variable store whose MOK list holds the
//! loader's Authenticode SHA-256 or nothing, and says what must happen,
//! reading shim's, MokManager's and the loader's words on COM1 (OVMF
//! copies its console there):
//!
//! - the loader's hash enrolled: the kernel says READY and every page is
//!   exact on QEMU's screendump (std and cirrus);
//! - nothing enrolled: shim refuses the loader (and starts MokManager);
//! - the loader changed after its hash was enrolled: shim refuses it;
//! - the first boot as a user lives it: MokManager driven with keys
//!   enrolls the loader's hash from the stick, and after the reboot the
//!   kernel says READY and draws.
//!
//! What the loader refuses on the stick is in loader_refusals.rs, the
//! image signed with a key in secure_boot_key.rs, Debian 12's shim 15.8 in
//! shim_15.rs.

use anyhow::{ensure, Result};
use boot_image::build_image;
use boot_image::secure_boot::loader::DIGESTS_MARKER;
use boot_image::secure_boot::{HASH_ENROLL_PATH, LOADER_PATH};
use harness::checks::{dump_matches_host_render, screen_matches_dump};
use harness::secure_boot::{
    boot, first_boot, loader_hash, ready_in_mode_13h, refused, scratch, FatImage, MokEntry, Screen, SHIM_REFUSES,
};
use harness::Adapter;
use scenes::builtin;

/// The image with its loader's hash enrolled: READY, then every demo page
/// drawn as the host renders it and exact on QEMU's screendump.
fn enrolled_hash_boots_and_every_page_is_exact(adapter: Adapter) -> Result<()> {
    let (image, dir) = (build_image()?, scratch()?);
    let hash = loader_hash(&image)?;
    let mut qemu = boot(&image, &[MokEntry::Hash(&hash)], adapter, false, dir.path())?;
    ready_in_mode_13h(&mut qemu, adapter)?;
    for page in builtin::ALL {
        let dump = dump_matches_host_render(&mut qemu.console, page.name, page.method)?;
        let name = format!("secure-boot.{}.{}", adapter.name(), page.name);
        screen_matches_dump(&name, &dump, &qemu.screendump()?, &qemu.ready.video)?;
    }
    eprintln!(
        "harness: Secure Boot, the loader's hash enrolled, {}: {}; {} pages exact on the screen",
        adapter.name(),
        qemu.ready,
        builtin::ALL.len()
    );
    Ok(())
}

#[test]
fn with_the_loaders_hash_enrolled_std_boots_and_every_page_is_exact_on_the_screen() -> Result<()> {
    enrolled_hash_boots_and_every_page_is_exact(Adapter::Std)
}

#[test]
fn with_the_loaders_hash_enrolled_cirrus_boots_and_every_page_is_exact_on_the_screen() -> Result<()> {
    enrolled_hash_boots_and_every_page_is_exact(Adapter::Cirrus)
}

#[test]
fn with_nothing_enrolled_shim_refuses_the_loader() -> Result<()> {
    let (image, dir) = (build_image()?, scratch()?);
    let said = refused(&image, &[], (SHIM_REFUSES, ""), dir.path())?;
    eprintln!("harness: Secure Boot, nothing enrolled: shim says `{said}`");
    Ok(())
}

/// The loader re-stamped for another kernel (one byte of the kernel's
/// SHA-256 in it changed), the hash of the loader as built enrolled: the
/// hash covers the digests, so shim refuses it before it runs.
#[test]
fn a_loader_changed_after_its_hash_was_enrolled_is_refused_by_shim() -> Result<()> {
    let (image, dir) = (build_image()?, scratch()?);
    let hash = loader_hash(&image)?;
    let mut fat = FatImage::open(&image)?;
    let mut loader = fat.read(LOADER_PATH)?;
    let marker = loader.windows(DIGESTS_MARKER.len()).position(|window| window == DIGESTS_MARKER);
    let Some(marker) = marker else { anyhow::bail!("the loader on the stick has no digests") };
    loader[marker + DIGESTS_MARKER.len()] ^= 1;
    fat.replace(LOADER_PATH, &loader)?;
    let copy = dir.path().join("restamped-loader.img");
    fat.write(&copy)?;
    ensure!(loader_hash(&copy)? != hash, "the changed loader has the enrolled hash");
    let said = refused(&copy, &[MokEntry::Hash(&hash)], (SHIM_REFUSES, ""), dir.path())?;
    eprintln!("harness: Secure Boot, the loader changed after its hash was enrolled: shim says `{said}`");
    Ok(())
}

/// The first boot of a new stick on a PC with Secure Boot on, as
/// docs/secure-boot.md#the-first-boot tells it: shim refuses the loader, MokManager comes up,
/// and the keys a user presses enroll the hash of the loader's copy at the
/// stick's root; after the reboot the show plays. Each screen waits for
/// its words on COM1 before its key is pressed, and is saved as a PNG in
/// target/secure-boot-screens/hash.
#[test]
fn the_first_boot_enrolls_the_loaders_hash_with_mokmanager_and_boots_after_the_reboot() -> Result<()> {
    let image = build_image()?;
    let screens: [Screen; 10] = [
        (SHIM_REFUSES, "1-shim-refuses", &["ret"]),
        ("Press any key to perform MOK management", "2-press-any-key", &["ret"]),
        ("Enroll hash from disk", "3-mok-management", &["down", "down", "ret"]),
        ("Select Binary", "4-select-volume", &["ret"]),
        (HASH_ENROLL_PATH, "5-select-loader", &["ret"]),
        ("View key 0", "6-enroll-mok", &["ret"]),
        // The hash MokManager is about to enroll, to compare with the
        // one the build printed.
        ("SHA256 hash", "7-the-hash", &["ret"]),
        ("View key 0", "8-enroll-mok", &["down", "ret"]),
        ("Enroll the key(s)?", "9-enroll-the-keys", &["down", "ret"]),
        ("Reboot", "10-reboot", &["ret"]),
    ];
    let ready = first_boot(&image, &screens, "hash")?;
    eprintln!("harness: Secure Boot, the first boot: the loader's hash enrolled with MokManager, then {ready}");
    Ok(())
}
