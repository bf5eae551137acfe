//! The bootable BIOS disk image: the kernel built with the pinned nightly,
//! wrapped by the `boot` image builder, which is built against the
//! bootloader copy whose stage 2 leaves the card in text mode
//! (`bootloader.rs`).

use std::path::PathBuf;
use std::process::Command;
use std::sync::OnceLock;

use anyhow::{ensure, Context, Result};

use crate::bootloader;
use crate::cargo::NightlyBuild;
use crate::once::once_per_process;
use crate::prerequisites::ensure_toolchain;
use crate::process::run_streaming;
use crate::workspace;

/// Names a prebuilt image to use instead of building one (`cargo xtask
/// test` builds once and hands it to every test binary this way). A
/// relative path is taken from the workspace root, since test binaries run
/// in their package's directory.
pub const IMAGE_ENV: &str = "POLYLAB_IMAGE";

/// The raw BIOS image, built once per process (or taken from
/// [`IMAGE_ENV`]). Installs the pinned nightly first when it is missing.
pub fn build_image() -> Result<PathBuf> {
    static IMAGE: OnceLock<Result<PathBuf, String>> = OnceLock::new();
    once_per_process(&IMAGE, || {
        if let Some(image) = std::env::var_os(IMAGE_ENV) {
            let image = workspace::root().join(image);
            ensure!(image.is_file(), "{IMAGE_ENV} names {}, which is not a file", image.display());
            eprintln!("harness: using the image {} from {IMAGE_ENV}", image.display());
            return Ok(image);
        }
        ensure_toolchain()?;
        let patched = bootloader::prepare()?;
        eprintln!("harness: building the kernel and the BIOS image builder (the first build takes minutes)");
        let kernel = NightlyBuild::KERNEL;
        run_streaming(&mut kernel.command()).with_context(|| format!("failed to build `{}`", kernel.package))?;
        let builder = NightlyBuild::IMAGE_BUILDER;
        run_streaming(builder.command().args(patched.cargo_args()?))
            .with_context(|| format!("failed to build `{}` against {}", builder.package, patched.dir.display()))?;
        patched.ensure_used()?;
        let image = image_path();
        let mut make_image = Command::new(NightlyBuild::IMAGE_BUILDER.artifact());
        make_image.arg(NightlyBuild::KERNEL.artifact()).arg(&image);
        run_streaming(&mut make_image).context("failed to make the BIOS disk image")?;
        eprintln!("harness: built {}", image.display());
        Ok(image)
    })
}

/// Where [`build_image`] writes the image.
fn image_path() -> PathBuf {
    workspace::nightly_target_dir().join("polylab-bios.img")
}
