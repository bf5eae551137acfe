//! What the Secure Boot tests need besides QEMU: UEFI variable stores
//! with a MOK list written in (Microsoft's keys, Secure Boot on, and the
//! hashes or certificates a test enrolls), copies of the image with a file
//! of its FAT partition replaced or added (a loader without its
//! signature, another kernel, a ramdisk), and the boots the tests share:
//! READY in mode 13h, a refusal with no READY, MokManager driven by keys.

use std::io::{Cursor, Read, Write};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Duration;

use anyhow::{ensure, Context, Result};
use protocol::{Firmware, Video};

use crate::checks::{dump_matches_host_render, screen_matches_dump};
use crate::{Adapter, Qemu, QemuOptions};
use install::ensure_virt_fw_vars;
use install::output_of;
use install::{ensure_secure_boot_ovmf, ovmf_microsoft_vars};

/// The GUID shim's variables (`MokList` among them) live under.
pub const SHIM_LOCK_GUID: &str = "605dab50-e046-4300-abb6-3dd810dd8b23";

/// Longest wait for the first words of shim, MokManager or the loader:
/// OVMF's Secure Boot build under TCG, with SMM, on a loaded machine.
pub const FIRMWARE_TIMEOUT: Duration = Duration::from_secs(180);
/// Longest wait for the next screen once a key is pressed.
pub const SCREEN_TIMEOUT: Duration = Duration::from_secs(60);
/// How long a refused boot is watched for a READY that must not come.
pub const NO_READY_WATCH: Duration = Duration::from_secs(10);

/// shim's words when the loader is not trusted (its hash not enrolled,
/// no signature, or one by a key not in the MOK list).
pub const SHIM_REFUSES: &str = "Verification failed: (0x1A) Security Violation";
/// The loader's words, start and end, when it refuses what is on the stick.
pub const LOADER_REFUSES: (&str, &str) = ("polylab: refusing to boot.", "switch it off.");

/// One entry of shim's MOK list.
#[derive(Clone, Copy, Debug)]
pub enum MokEntry<'a> {
    /// A certificate file, PEM or DER ("Enroll key from disk").
    Certificate(&'a Path),
    /// An image's Authenticode SHA-256 ("Enroll hash from disk").
    Hash(&'a [u8; 32]),
}

/// Writes `out`: OVMF's variable store with Microsoft's keys and Secure
/// Boot on, with `entries` in shim's MOK list, as if they had been
/// enrolled with MokManager; with none, the store as a new PC has it.
pub fn variables_with_mok_list(entries: &[MokEntry], out: &Path) -> Result<()> {
    ensure_secure_boot_ovmf()?;
    let microsoft_vars = ovmf_microsoft_vars();
    if entries.is_empty() {
        std::fs::copy(&microsoft_vars, out)
            .with_context(|| format!("failed to copy {} to {}", microsoft_vars.display(), out.display()))?;
        return Ok(());
    }
    let mut command = Command::new(ensure_virt_fw_vars()?);
    command.arg("-i").arg(&microsoft_vars).arg("-o").arg(out);
    for entry in entries {
        match entry {
            MokEntry::Certificate(certificate) => command.args(["--add-mok", SHIM_LOCK_GUID]).arg(certificate),
            MokEntry::Hash(hash) => command.args(["--add-mok-hash", SHIM_LOCK_GUID, &boot_image::hex(*hash)]),
        };
    }
    output_of(&mut command).map(drop).context("failed to write the MOK list into a UEFI variable store")
}

/// A folder of the test's own, removed when it ends.
pub fn scratch() -> Result<tempfile::TempDir> {
    tempfile::Builder::new().prefix("polylab-secure-boot-").tempdir().context("failed to create a temporary folder")
}

/// Starts `image` under Secure Boot on `adapter`, the MOK list holding
/// `entries`; the variable store is written in `dir`.
pub fn boot(image: &Path, entries: &[MokEntry], adapter: Adapter, allow_reboot: bool, dir: &Path) -> Result<Qemu> {
    let variables = dir.join("OVMF_VARS_4M.ms.fd");
    variables_with_mok_list(entries, &variables)?;
    let options =
        QemuOptions { firmware: Firmware::Uefi, secure_boot: true, adapter, allow_reboot, ..QemuOptions::default() };
    Qemu::spawn_with_variables(image, options, &variables)
}

/// Waits for READY and checks it: UEFI, the card, mode 13h with every
/// register read back as written.
pub fn ready_in_mode_13h(qemu: &mut Qemu, adapter: Adapter) -> Result<()> {
    let ready = qemu.console.wait_ready()?;
    ensure!(ready.firmware == Firmware::Uefi, "READY names the firmware {:?}", ready.firmware);
    ensure!(ready.display == adapter.pci_id(), "READY names the display {:?}", ready.display);
    ensure!(ready.video == Video::Vga13h { mismatches: 0 }, "READY says {:?}", ready.video);
    qemu.ready = ready;
    Ok(())
}

/// Waits for READY in mode 13h on the std card, then has page 1 drawn:
/// the dump as the host renders it, the screen exact (saved under `name`
/// if not).
pub fn ready_and_page_1_exact(qemu: &mut Qemu, name: &str) -> Result<()> {
    ready_in_mode_13h(qemu, Adapter::Std)?;
    let page_1 = scenes::builtin::ABRASH38_1;
    let dump = dump_matches_host_render(&mut qemu.console, page_1.name, page_1.method)?;
    screen_matches_dump(name, &dump, &qemu.screendump()?, &qemu.ready.video)
}

/// Boots `image` with `entries` enrolled and expects `reason` on COM1,
/// then `until` (the end of what is said, if not empty), with no READY
/// before it, nor for a while after; returns what was said.
pub fn refused(image: &Path, entries: &[MokEntry], (reason, until): (&str, &str), dir: &Path) -> Result<String> {
    let mut qemu = boot(image, entries, Adapter::Std, false, dir)?;
    let (which, _) = qemu.console.wait_for_first_text(&[reason, "@READY"], FIRMWARE_TIMEOUT)?;
    ensure!(which == 0, "the kernel said READY, and nothing said `{reason}`");
    let rest = if until.is_empty() { String::new() } else { qemu.console.wait_for_text(until, SCREEN_TIMEOUT)? };
    let after = qemu.console.wait_for_text("@READY", NO_READY_WATCH);
    ensure!(after.is_err(), "the kernel said READY after `{reason}`");
    Ok(format!("{reason}{rest}"))
}

/// One screen of a first boot: the words that show it is up, the
/// picture's name, the keys (QEMU's names) that answer it.
pub type Screen<'a> = (&'a str, &'a str, &'a [&'a str]);

/// The first boot of `image` with nothing enrolled, as a user lives it:
/// `screens` (shim's refusal, then MokManager's) answered in turn, then
/// after the reboot READY and page 1 exact; the screens are saved as PNGs
/// in target/secure-boot-screens/`name`. Returns READY's line.
pub fn first_boot(image: &Path, screens: &[Screen], name: &str) -> Result<String> {
    let dir = scratch()?;
    let mut qemu = boot(image, &[], Adapter::Std, true, dir.path())?;
    answer_screens(&mut qemu, screens, &crate::workspace::target_dir().join("secure-boot-screens").join(name))?;
    ready_and_page_1_exact(&mut qemu, &format!("secure-boot.{name}.first-boot.abrash38-1"))?;
    Ok(qemu.ready.to_string())
}

/// Answers `screens` in turn, each once its words are on COM1 (no READY
/// before them), saving each as a PNG in `pictures`.
fn answer_screens(qemu: &mut Qemu, screens: &[Screen], pictures: &Path) -> Result<()> {
    std::fs::create_dir_all(pictures).with_context(|| format!("failed to create {}", pictures.display()))?;
    for (i, (words, picture, keys)) in screens.iter().enumerate() {
        let timeout = if i == 0 { FIRMWARE_TIMEOUT } else { SCREEN_TIMEOUT };
        let (which, _) = qemu.console.wait_for_first_text(&[words, "@READY"], timeout)?;
        ensure!(which == 0, "the kernel said READY before `{words}`");
        // Let the screen finish drawing before it is saved and answered.
        std::thread::sleep(Duration::from_secs(1));
        qemu.screendump()?.write_png(&pictures.join(format!("{picture}.png")))?;
        for key in *keys {
            qemu.send_key(key)?;
            std::thread::sleep(Duration::from_millis(300));
        }
    }
    Ok(())
}

/// The Authenticode SHA-256 of the loader on `image`, as MokManager's
/// "Enroll hash from disk" enrolls it.
pub fn loader_hash(image: &Path) -> Result<[u8; 32]> {
    let loader = FatImage::open(image)?.read(boot_image::secure_boot::LOADER_PATH)?;
    boot_image::secure_boot::loader::authenticode_sha256(&loader)
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

    /// Adds a file at `fat_path` (in the root folder) with `contents`.
    pub fn add(&mut self, fat_path: &str, contents: &[u8]) -> Result<()> {
        let file_system = self.file_system()?;
        let mut file =
            file_system.root_dir().create_file(fat_path).with_context(|| format!("failed to create {fat_path}"))?;
        file.write_all(contents).with_context(|| format!("failed to write {fat_path}"))?;
        file.flush().with_context(|| format!("failed to write {fat_path}"))?;
        drop(file);
        file_system.unmount().with_context(|| format!("failed to write {}'s FAT", self.path.display()))
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
        fat.add("ramdisk", b"a ramdisk").unwrap();
        let copy = dir.path().join("copy");
        fat.write(&copy).unwrap();
        assert_eq!(FatImage::open(&copy).unwrap().read("kernel-x86_64").unwrap(), b"another, longer kernel");
        assert_eq!(FatImage::open(&copy).unwrap().read("ramdisk").unwrap(), b"a ramdisk");
        assert_eq!(FatImage::open(&image).unwrap().read("kernel-x86_64").unwrap(), b"the kernel");
        assert!(fat.read("boot.json").unwrap_err().to_string().contains("no boot.json on the FAT"));
    }
}
