//! What the loader refuses on the stick, under UEFI Secure Boot with its
//! hash enrolled (so shim starts it): a kernel or `boot.json` changed
//! after the image was built, a `ramdisk` (which nothing checks and
//! bootloader's loader would map for the kernel), and an empty kernel,
//! `boot.json` or ramdisk (which would stop bootloader's loader in a panic
//! that names nothing). Each refusal names polylab on COM1 (and on the
//! screen: the firmware's console, which OVMF copies to COM1 too), and
//! the kernel never says READY.

use anyhow::{ensure, Result};
use boot_image::build_image;
use harness::secure_boot::{loader_hash, refused, scratch, FatImage, MokEntry, LOADER_REFUSES};

/// What changes on the stick.
enum Change {
    /// The file one byte longer (a kernel ELF still loads with a byte
    /// after its end; JSON parses with a space after it).
    Append(u8),
    /// The file emptied.
    Empty,
    /// A new file at the root.
    Add(&'static [u8]),
}

/// The image with `fat_path` changed, the loader's hash enrolled: the
/// loader refuses it with `words`.
fn refused_by_the_loader(fat_path: &str, change: Change, words: &str) -> Result<()> {
    let (image, dir) = (build_image()?, scratch()?);
    let hash = loader_hash(&image)?;
    let mut fat = FatImage::open(&image)?;
    match change {
        Change::Append(byte) => {
            let mut changed = fat.read(fat_path)?;
            changed.push(byte);
            fat.replace(fat_path, &changed)?;
        }
        Change::Empty => fat.replace(fat_path, &[])?,
        Change::Add(contents) => fat.add(fat_path, contents)?,
    }
    let copy = dir.path().join("changed.img");
    fat.write(&copy)?;
    let said = refused(&copy, &[MokEntry::Hash(&hash)], LOADER_REFUSES, dir.path())?;
    ensure!(said.contains(words), "the loader did not say `{words}`: {said}");
    eprintln!("harness: Secure Boot, {fat_path} changed: the loader says `{}`", said.replace("\r\n", " "));
    Ok(())
}

#[test]
fn a_kernel_swapped_after_the_build_is_refused_by_the_loader() -> Result<()> {
    refused_by_the_loader("kernel-x86_64", Change::Append(0), "kernel-x86_64 is not the kernel this loader")
}

#[test]
fn a_boot_json_changed_after_the_build_is_refused_by_the_loader() -> Result<()> {
    refused_by_the_loader("boot.json", Change::Append(b' '), "boot.json is not the boot.json this loader")
}

#[test]
fn a_ramdisk_on_the_stick_is_refused_by_the_loader() -> Result<()> {
    refused_by_the_loader("ramdisk", Change::Add(&[0x5A; 4096]), "a ramdisk is on the volume")
}

#[test]
fn an_empty_kernel_is_refused_by_the_loader() -> Result<()> {
    refused_by_the_loader("kernel-x86_64", Change::Empty, "kernel-x86_64 is an empty file")
}

#[test]
fn an_empty_boot_json_is_refused_by_the_loader() -> Result<()> {
    refused_by_the_loader("boot.json", Change::Empty, "boot.json is an empty file")
}

#[test]
fn an_empty_ramdisk_is_refused_by_the_loader() -> Result<()> {
    refused_by_the_loader("ramdisk", Change::Add(&[]), "ramdisk is an empty file")
}
