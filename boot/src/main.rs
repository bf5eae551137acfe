//! Builds the raw BIOS disk image from the kernel ELF:
//! `boot KERNEL_ELF OUT_IMAGE`. Run by the xtask with the pinned nightly
//! (bootloader's build script compiles its boot stages with -Zbuild-std).

use std::path::PathBuf;

use anyhow::{bail, Context, Result};
use bootloader::{BiosBoot, BootConfig};

fn main() -> Result<()> {
    let args: Vec<PathBuf> = std::env::args_os().skip(1).map(PathBuf::from).collect();
    let [kernel, image] = args.as_slice() else {
        bail!("usage: boot KERNEL_ELF OUT_IMAGE");
    };
    // The bootloader logs to COM1 and the framebuffer by default; COM1 is
    // our protocol channel, and the framebuffer its patched stage 2 hands
    // on is the mode-13h window (tests/src/bootloader.rs), where log text
    // would only slow the boot, so both stay quiet.
    let mut config = BootConfig::default();
    config.serial_logging = false;
    config.frame_buffer_logging = false;
    BiosBoot::new(kernel)
        .set_boot_config(&config)
        .create_disk_image(image)
        .with_context(|| format!("failed to create BIOS disk image {} from {}", image.display(), kernel.display()))?;
    Ok(())
}
