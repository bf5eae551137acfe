//! The bootable image's build, for the xtask (`cargo xtask image`) and the
//! test harness alike: the kernel built with the pinned nightly, and
//! `boot` (the image writer, `boot/src/main.rs`) built against the copy of
//! `bootloader` whose BIOS stage 2 leaves the card in text mode
//! ([`bootloader`]), then run to write one raw image that boots under a
//! BIOS (or a UEFI firmware's CSM) and under UEFI.
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
pub mod once;
pub mod process;
pub mod toolchain;
pub mod workspace;

use std::path::PathBuf;
use std::process::Command;
use std::sync::OnceLock;

use anyhow::{ensure, Context, Result};

use crate::cargo::NightlyBuild;
use crate::once::once_per_process;
use crate::process::run_streaming;
use crate::toolchain::ensure_toolchain;

/// Names a prebuilt image to use instead of building one (`cargo xtask
/// test` builds once and hands it to every test binary this way). A
/// relative path is taken from the workspace root, since test binaries run
/// in their package's directory.
pub const IMAGE_ENV: &str = "POLYLAB_IMAGE";

/// The raw image, built once per process (or taken from [`IMAGE_ENV`]).
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
        ensure_toolchain()?;
        let patched = bootloader::prepare()?;
        eprintln!("image: building the kernel and the image writer (the first build takes minutes)");
        let kernel = NightlyBuild::KERNEL;
        run_streaming(&mut kernel.command()).with_context(|| format!("failed to build `{}`", kernel.package))?;
        let writer = NightlyBuild::IMAGE_WRITER;
        run_streaming(writer.command().args(patched.cargo_args()?))
            .with_context(|| format!("failed to build `{}` against {}", writer.package, patched.dir.display()))?;
        patched.ensure_used()?;
        let image = image_path();
        let mut write_image = Command::new(NightlyBuild::IMAGE_WRITER.artifact());
        write_image.arg(NightlyBuild::KERNEL.artifact()).arg(&image);
        run_streaming(&mut write_image).context("failed to write the disk image")?;
        eprintln!("image: built {}", image.display());
        Ok(image)
    })
}

/// Where [`build_image`] writes the image.
fn image_path() -> PathBuf {
    workspace::nightly_target_dir().join("polylab.img")
}
