//! The stick with Debian 12's shim 15.8 (`shim-signed
//! 1.44~1+deb12u1+15.8-1~deb12u1`, what a machine whose package lists
//! were never refreshed downloads). shim 15.8 halts at ExitBootServices
//! ("Bootloader has not verified loaded image.") a second stage it
//! verified by a certificate, unless that stage had shim verify what it
//! boots; it lets one through that it verified by a MOK list hash. So:
//!
//! - the image whose loader is enrolled by its hash (the default) boots
//!   with shim 15.8 and draws;
//! - the build refuses to sign the loader with a key around shim 15.8,
//!   saying why and what to do.
//!
//! The two packages are fetched from Debian's pool (apt's own downloader,
//! `apt-helper`) and pinned by SHA-256. When the pool drops them, these
//! tests fail saying so: they cannot prove anything about shim 15.8 then,
//! and must not pass as if they had.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

use anyhow::{ensure, Context, Result};
use boot_image::secure_boot::debian::{PinnedDeb, Unpacked};
use boot_image::secure_boot::key::SigningKey;
use boot_image::secure_boot::{shim, Enrollment, SHIM_PATH};
use harness::secure_boot::{boot, loader_hash, ready_and_page_1_exact, scratch, FatImage, MokEntry};
use harness::Adapter;
use install::output_of;
use install::{once_per_process, Failure};

/// Debian's pool, where every package version lives until it is dropped.
const POOL: &str = "http://deb.debian.org/debian/pool/main/s";

/// (package, path in the pool, the .deb's SHA-256), read when the test
/// was written (2026-11-27).
const PACKAGES: [(&str, &str, &str); 2] = [
    (
        "shim-signed",
        "shim-signed/shim-signed_1.44~1+deb12u1+15.8-1~deb12u1_amd64.deb",
        "4525b3450756562543c2d4a92545a64f3ae379add26d86617b0bd28683856a42",
    ),
    (
        "shim-helpers-amd64-signed",
        "shim-helpers-amd64-signed/shim-helpers-amd64-signed_1+15.8+1~deb12u1_amd64.deb",
        "640b409cd0e50a470002fc700bdde0c9bfa9bac81d11a2694be53fad9c79b596",
    ),
];

/// Where the packages are kept and unpacked, and the image built.
fn shim_15_dir() -> PathBuf {
    harness::workspace::target_dir().join("shim-15.8")
}

/// shim 15.8 and its MokManager, fetched once (the pool's files kept in
/// target/shim-15.8), each checked against its pin and unpacked afresh
/// where an unpacked file differs from its package's
/// ([`Unpacked::get`]): a folder unpacked by an earlier run is never
/// trusted as found.
fn shim_15_packages() -> Result<Unpacked> {
    static DEBS: OnceLock<Result<Vec<PinnedDeb>, Failure>> = OnceLock::new();
    let debs = once_per_process(&DEBS, fetch)?;
    Ok(Unpacked::pinned(shim_15_dir().join("unpacked"), debs))
}

/// [`shim_15_packages`]'s downloads, where they are not there yet.
fn fetch() -> Result<Vec<PinnedDeb>> {
    let dir = shim_15_dir();
    PACKAGES
        .iter()
        .map(|(package, pool_path, sha256)| {
            let deb = dir.join(pool_path.rsplit('/').next().expect("a file name"));
            if !deb.is_file() {
                download(&format!("{POOL}/{pool_path}"), &deb)?;
            }
            Ok(PinnedDeb { package, deb, sha256 })
        })
        .collect()
}

/// Downloads `url` to `to` with apt's downloader, failing with what it
/// means when the pool no longer has the file.
fn download(url: &str, to: &Path) -> Result<()> {
    std::fs::create_dir_all(to.parent().expect("a folder")).context("failed to create the packages' folder")?;
    let partial = to.with_extension("partial");
    let mut download = Command::new("/usr/lib/apt/apt-helper");
    download.arg("download-file").arg(url).arg(&partial);
    output_of(&mut download).with_context(|| {
        format!(
            "could not fetch {url}: if Debian's pool has dropped shim 15.8, these tests can no longer prove \
             that a stick with shim 15.8 boots (or that its build is refused); they fail rather than pass \
             untested. Put the .deb at {} by hand (its SHA-256 is pinned in tests/tests/shim_15.rs), or \
             retire these tests with a note in docs/secure-boot.md",
            to.display()
        )
    })?;
    std::fs::rename(&partial, to).with_context(|| format!("failed to move {} to {}", partial.display(), to.display()))
}

/// The image with shim 15.8, its loader to be enrolled by its hash.
fn shim_15_image() -> Result<PathBuf> {
    static IMAGE: OnceLock<Result<PathBuf, Failure>> = OnceLock::new();
    once_per_process(&IMAGE, || {
        let image = shim_15_dir().join("polylab-shim-15.8.img");
        boot_image::build_image_with(&Enrollment::Hash, &shim_15_packages()?, &image)
    })
}

#[test]
fn with_shim_15_8_the_loader_enrolled_by_its_hash_boots_and_draws() -> Result<()> {
    let (image, dir) = (shim_15_image()?, scratch()?);
    let on_the_stick = shim::version(&FatImage::open(&image)?.read(SHIM_PATH)?)?;
    ensure!(on_the_stick == (15, 8), "the stick carries shim {on_the_stick:?}, not 15.8");
    let hash = loader_hash(&image)?;
    let mut qemu = boot(&image, &[MokEntry::Hash(&hash)], Adapter::Std, false, dir.path())?;
    ready_and_page_1_exact(&mut qemu, "secure-boot.shim-15.8.abrash38-1")?;
    eprintln!("harness: Secure Boot with shim 15.8, the loader's hash enrolled: {}", qemu.ready);
    Ok(())
}

#[test]
fn with_shim_15_8_the_build_refuses_to_sign_the_loader_with_a_key() -> Result<()> {
    let dir = scratch()?;
    let key = SigningKey::in_folder(&dir.path().join("key"), Some("polylab Secure Boot tests".into()))?;
    let image = dir.path().join("never.img");
    let error = match boot_image::build_image_with(&Enrollment::Key(key), &shim_15_packages()?, &image) {
        Ok(_) => anyhow::bail!("the build signed the loader with a key around shim 15.8"),
        Err(error) => format!("{error:#}"),
    };
    ensure!(error.contains("around shim 15.8"), "{error}");
    ensure!(error.contains("Bootloader has not verified loaded image"), "{error}");
    ensure!(error.contains("--enroll hash"), "{error}");
    ensure!(!image.exists(), "the refused build left an image");
    eprintln!("harness: shim 15.8 and --enroll key: {error}");
    Ok(())
}
