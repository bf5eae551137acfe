//! The image writer, run by the image build (boot/image) with the pinned
//! nightly: bootloader's build script compiles its boot stages with
//! -Zbuild-std, so this program carries them.
//!
//! ```text
//! boot loader OUT_DIR
//!     writes bootloader's UEFI loader (OUT_DIR/loader.efi) and the
//!     boot.json every image carries (OUT_DIR/boot.json)
//! boot image KERNEL_ELF BOOT_JSON OUT_IMAGE [FAT_PATH=FILE]...
//!     writes the image: bootloader's BIOS disk image with the kernel,
//!     BOOT_JSON and each FILE at its FAT_PATH on the FAT partition
//! ```
//!
//! The image build signs the loader between the two steps (it writes the
//! kernel's and boot.json's SHA-256 into it first), so that the one raw
//! file boots three ways: bootloader's BIOS disk image (an MBR whose
//! partition 1 is stage 2 and partition 2 a FAT holding the kernel,
//! `boot.json` and stages 3 and 4) with shim, the signed loader and
//! MokManager added to that FAT under `efi/boot/`. A BIOS (or a CSM) runs
//! the MBR's boot code, which never looks at `efi/`; a UEFI firmware runs
//! shim, which runs the loader, which finds the kernel and `boot.json` on
//! the partition it was loaded from.

use std::path::{Path, PathBuf};

use anyhow::{bail, Context, Result};
use bootloader::{BootConfig, DiskImageBuilder};

/// The name bootloader's network-boot folder gives the UEFI loader.
const PXE_LOADER_NAME: &str = "bootloader";
/// The name bootloader's stages and loader read the configuration from.
const CONFIG_NAME: &str = "boot.json";

fn main() -> Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match args.iter().map(String::as_str).collect::<Vec<_>>()[..] {
        ["loader", out_dir] => write_loader(Path::new(out_dir)),
        ["image", kernel, boot_json, image, ref files @ ..] => {
            let files = files.iter().map(|file| fat_file(file)).collect::<Result<Vec<_>>>()?;
            write_image(Path::new(kernel), Path::new(boot_json), Path::new(image), &files)
        }
        _ => bail!("usage: boot loader OUT_DIR | boot image KERNEL_ELF BOOT_JSON OUT_IMAGE [FAT_PATH=FILE]..."),
    }
}

/// The configuration every image carries. The bootloader logs to COM1 and
/// the framebuffer by default; COM1 is our protocol channel, and log text
/// on the screen would only slow the boot (and under UEFI stay on the
/// firmware's framebuffer, which the kernel may present its frame in), so
/// both stay quiet. Under UEFI the loader sets the smallest graphics mode
/// of at least 640x400 (its patched mode choice,
/// boot/image/src/bootloader.rs): the kernel's 320x200 frame at scale 2
/// at least, and no more pixels to write a frame than that needs.
fn boot_config() -> BootConfig {
    let mut config = BootConfig::default();
    config.serial_logging = false;
    config.frame_buffer_logging = false;
    config.frame_buffer.minimum_framebuffer_width = Some(MINIMUM_FRAMEBUFFER.0);
    config.frame_buffer.minimum_framebuffer_height = Some(MINIMUM_FRAMEBUFFER.1);
    config
}

/// The smallest framebuffer the loader picks under UEFI: twice the
/// kernel's 320x200 frame each way.
const MINIMUM_FRAMEBUFFER: (u64, u64) = (640, 400);

/// Writes `loader.efi` and `boot.json` into `out_dir`. The crate hands its
/// UEFI loader out only inside an image or in its network-boot (PXE/TFTP)
/// folder; the folder is plain files, where an image would need its GPT
/// taken apart.
fn write_loader(out_dir: &Path) -> Result<()> {
    let folder = tempfile::tempdir().context("failed to create a temporary folder for the UEFI loader")?;
    DiskImageBuilder::empty()
        .set_boot_config(&boot_config())
        .create_uefi_tftp_folder(folder.path())
        .context("failed to write bootloader's UEFI network-boot folder")?;
    for (from, to) in [(PXE_LOADER_NAME, "loader.efi"), (CONFIG_NAME, CONFIG_NAME)] {
        let (from, to) = (folder.path().join(from), out_dir.join(to));
        std::fs::copy(&from, &to).with_context(|| format!("failed to copy {} to {}", from.display(), to.display()))?;
    }
    Ok(())
}

/// `FAT_PATH=FILE`, split.
fn fat_file(arg: &str) -> Result<(String, PathBuf)> {
    let (fat_path, file) = arg.split_once('=').with_context(|| format!("`{arg}` is not FAT_PATH=FILE"))?;
    Ok((fat_path.to_string(), PathBuf::from(file)))
}

/// Writes the image. `boot_json` goes in as it is (not as `BootConfig`
/// serialized here again), so the loader's digest of it is of these very
/// bytes. bootloader's `DiskImageBuilder` lays out the MBR and stage 2 as
/// for any BIOS image and sizes the FAT for every file (formatted with the
/// `fatfs` crate, which picks FAT16 at this size).
fn write_image(kernel: &Path, boot_json: &Path, image: &Path, files: &[(String, PathBuf)]) -> Result<()> {
    let mut builder = DiskImageBuilder::new(kernel.to_path_buf());
    builder.set_file(CONFIG_NAME.to_string(), boot_json.to_path_buf());
    for (fat_path, file) in files {
        builder.set_file(fat_path.clone(), file.clone());
    }
    builder
        .create_bios_image(image)
        .with_context(|| format!("failed to create the disk image {} from {}", image.display(), kernel.display()))
}
