//! What the Secure Boot tests need besides QEMU: UEFI variable stores
//! with a MOK list written in (Microsoft's keys, Secure Boot on, and the
//! certificates a test enrolls), and copies of the image with a file of
//! its FAT partition replaced (a loader without its signature, another
//! kernel).

use std::io::{Cursor, Read, Write};
use std::path::{Path, PathBuf};
use std::process::Command;

use anyhow::{ensure, Context, Result};

use crate::prerequisites::{ensure_secure_boot_ovmf, ensure_virt_fw_vars, ovmf_microsoft_vars};
use crate::process::output_of;

/// The GUID shim's variables (`MokList` among them) live under.
pub const SHIM_LOCK_GUID: &str = "605dab50-e046-4300-abb6-3dd810dd8b23";

/// Writes `out`: OVMF's variable store with Microsoft's keys and Secure
/// Boot on, with `certificates` (PEM or DER files) in shim's MOK list, as
/// if they had been enrolled with MokManager; with none, the store as a
/// new PC has it.
pub fn variables_with_mok_list(certificates: &[&Path], out: &Path) -> Result<()> {
    ensure_secure_boot_ovmf()?;
    let microsoft_vars = ovmf_microsoft_vars();
    if certificates.is_empty() {
        std::fs::copy(&microsoft_vars, out)
            .with_context(|| format!("failed to copy {} to {}", microsoft_vars.display(), out.display()))?;
        return Ok(());
    }
    let mut command = Command::new(ensure_virt_fw_vars()?);
    command.arg("-i").arg(&microsoft_vars).arg("-o").arg(out);
    for certificate in certificates {
        command.args(["--add-mok", SHIM_LOCK_GUID]).arg(certificate);
    }
    output_of(&mut command).map(drop).context("failed to write the MOK list into a UEFI variable store")
}

/// A raw image's FAT partition (partition 2 of its MBR), read into memory.
pub struct FatImage {
    path: PathBuf,
    bytes: Vec<u8>,
    partition: std::ops::Range<usize>,
}

impl FatImage {
    /// The image at `path`, its partition table read.
    pub fn open(path: &Path) -> Result<Self> {
        let bytes = std::fs::read(path).with_context(|| format!("failed to read {}", path.display()))?;
        ensure!(bytes.len() >= 512 && bytes[510..512] == [0x55, 0xAA], "{} has no MBR", path.display());
        // Partition 2's entry: LBA of its first sector and its sector count.
        let entry = &bytes[446 + 16..446 + 32];
        let start = u32::from_le_bytes(entry[8..12].try_into().expect("4 bytes")) as usize * 512;
        let len = u32::from_le_bytes(entry[12..16].try_into().expect("4 bytes")) as usize * 512;
        ensure!(start > 0 && start + len <= bytes.len(), "{}'s partition 2 is not in the file", path.display());
        Ok(Self { path: path.to_path_buf(), bytes, partition: start..start + len })
    }

    fn file_system(&mut self) -> Result<fatfs::FileSystem<Cursor<&mut [u8]>>> {
        let partition = Cursor::new(&mut self.bytes[self.partition.clone()]);
        fatfs::FileSystem::new(partition, fatfs::FsOptions::new())
            .with_context(|| format!("{}'s partition 2 is not a FAT volume", self.path.display()))
    }

    /// The file at `fat_path` (`/`-separated, from the root).
    pub fn read(&mut self, fat_path: &str) -> Result<Vec<u8>> {
        let file_system = self.file_system()?;
        let mut file =
            file_system.root_dir().open_file(fat_path).with_context(|| format!("no {fat_path} on the FAT"))?;
        let mut bytes = Vec::new();
        file.read_to_end(&mut bytes).with_context(|| format!("failed to read {fat_path} from the FAT"))?;
        Ok(bytes)
    }

    /// Replaces the file at `fat_path` with `contents`.
    pub fn replace(&mut self, fat_path: &str, contents: &[u8]) -> Result<()> {
        let file_system = self.file_system()?;
        let mut file =
            file_system.root_dir().open_file(fat_path).with_context(|| format!("no {fat_path} on the FAT"))?;
        file.truncate().with_context(|| format!("failed to empty {fat_path}"))?;
        file.write_all(contents).with_context(|| format!("failed to write {fat_path}"))?;
        file.flush().with_context(|| format!("failed to write {fat_path}"))?;
        drop(file);
        file_system.unmount().with_context(|| format!("failed to write {}'s FAT", self.path.display()))
    }

    /// Writes the image, with any replaced file, to `path`.
    pub fn write(&self, path: &Path) -> Result<()> {
        std::fs::write(path, &self.bytes).with_context(|| format!("failed to write {}", path.display()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 1 MB "image": an MBR whose partition 2 (from LBA 8) holds a fresh
    /// FAT volume with one file.
    fn image_with(file: &str, contents: &[u8], dir: &Path) -> PathBuf {
        let mut bytes = vec![0u8; 1 << 20];
        let (start, sectors) = (8u32, (1u32 << 20) / 512 - 8);
        bytes[446 + 16 + 8..446 + 16 + 12].copy_from_slice(&start.to_le_bytes());
        bytes[446 + 16 + 12..446 + 16 + 16].copy_from_slice(&sectors.to_le_bytes());
        bytes[510..512].copy_from_slice(&[0x55, 0xAA]);
        let mut partition = Cursor::new(&mut bytes[start as usize * 512..]);
        fatfs::format_volume(&mut partition, fatfs::FormatVolumeOptions::new()).unwrap();
        let file_system = fatfs::FileSystem::new(partition, fatfs::FsOptions::new()).unwrap();
        file_system.root_dir().create_file(file).unwrap().write_all(contents).unwrap();
        file_system.unmount().unwrap();
        let path = dir.join("image");
        std::fs::write(&path, bytes).unwrap();
        path
    }

    #[test]
    fn a_replaced_file_reads_back_in_the_written_copy_and_the_original_is_untouched() {
        let dir = tempfile::tempdir().unwrap();
        let image = image_with("kernel-x86_64", b"the kernel", dir.path());
        let mut fat = FatImage::open(&image).unwrap();
        assert_eq!(fat.read("kernel-x86_64").unwrap(), b"the kernel");
        fat.replace("kernel-x86_64", b"another, longer kernel").unwrap();
        let copy = dir.path().join("copy");
        fat.write(&copy).unwrap();
        assert_eq!(FatImage::open(&copy).unwrap().read("kernel-x86_64").unwrap(), b"another, longer kernel");
        assert_eq!(FatImage::open(&image).unwrap().read("kernel-x86_64").unwrap(), b"the kernel");
        assert!(fat.read("boot.json").unwrap_err().to_string().contains("no boot.json on the FAT"));
    }
}
