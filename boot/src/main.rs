//! Writes the bootable image from the kernel ELF: `boot KERNEL_ELF
//! OUT_IMAGE`. Run by the image build (boot/image) with the pinned nightly:
//! bootloader's build script compiles its boot stages with -Zbuild-std.
//!
//! One raw file boots both ways. It is bootloader's BIOS disk image (an MBR
//! whose partition 1 is stage 2 and partition 2 a FAT holding the kernel,
//! `boot.json` and stages 3 and 4) with bootloader's UEFI loader added to
//! that FAT as `efi/boot/bootx64.efi`, the path a UEFI firmware starts from
//! removable media. A BIOS (or a CSM) runs the MBR's boot code, which never
//! looks at the loader; a UEFI firmware runs the loader, which finds the
//! kernel and `boot.json` on the partition it was loaded from.

use std::path::PathBuf;

use anyhow::{bail, Context, Result};
use bootloader::{BootConfig, DiskImageBuilder, UefiBoot};

/// Where a UEFI firmware looks for the loader of removable media (FAT
/// names are case-insensitive).
const UEFI_LOADER_PATH: &str = "efi/boot/bootx64.efi";
/// The name `UefiBoot`'s network-boot folder gives the UEFI loader.
const PXE_LOADER_NAME: &str = "bootloader";

fn main() -> Result<()> {
    let args: Vec<PathBuf> = std::env::args_os().skip(1).map(PathBuf::from).collect();
    let [kernel, image] = args.as_slice() else {
        bail!("usage: boot KERNEL_ELF OUT_IMAGE");
    };
    // The bootloader logs to COM1 and the framebuffer by default; COM1 is
    // our protocol channel, and log text on the screen would only slow the
    // boot (and under UEFI stay on the firmware's framebuffer, which the
    // kernel may present its frame in), so both stay quiet.
    let mut config = BootConfig::default();
    config.serial_logging = false;
    config.frame_buffer_logging = false;
    let uefi_loader = uefi_loader(kernel, &config)?;
    DiskImageBuilder::new(kernel.clone())
        .set_boot_config(&config)
        .set_file_contents(UEFI_LOADER_PATH.to_string(), uefi_loader)
        .create_bios_image(image)
        .with_context(|| format!("failed to create the disk image {} from {}", image.display(), kernel.display()))?;
    Ok(())
}

/// The bytes of bootloader's UEFI loader. The crate hands them out only
/// inside an image or in its network-boot (PXE/TFTP) folder; the folder is
/// a plain file, where an image would need its GPT taken apart.
fn uefi_loader(kernel: &std::path::Path, config: &BootConfig) -> Result<Vec<u8>> {
    let folder = tempfile::tempdir().context("failed to create a temporary folder for the UEFI loader")?;
    UefiBoot::new(kernel)
        .set_boot_config(config)
        .create_pxe_tftp_folder(folder.path())
        .context("failed to write bootloader's UEFI network-boot folder")?;
    let loader = folder.path().join(PXE_LOADER_NAME);
    std::fs::read(&loader).with_context(|| format!("failed to read the UEFI loader {}", loader.display()))
}
