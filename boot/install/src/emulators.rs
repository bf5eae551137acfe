//! The emulators the runs boot the image in, and their firmware: QEMU
//! (with its window and its QXL card where a run needs them), OVMF (the
//! UEFI firmware, with its Secure Boot build), and Bochs with its BIOSes.
//! Each is ensured where it is used (QEMU when a QEMU starts), so a run
//! installs only what its tests need. The firmware files are where
//! Debian puts them unless an environment variable names others
//! (`POLYLAB_OVMF_CODE`, ...: see each constant).

use std::path::PathBuf;
use std::process::Command;
use std::sync::OnceLock;

use anyhow::Result;

use crate::files::{ensure_system_files, on_path, system_file};
use crate::missing::ensure_all;
use crate::once::{once_per_process, Failure};
use crate::packages::ensure_debian_packages;
use crate::process::output_of;

/// The QEMU binary the harness runs, and the Debian package that has it
/// (with SeaBIOS and the VGA BIOSes, its dependencies).
pub const QEMU: &str = "qemu-system-x86_64";
const QEMU_PACKAGE: &str = "qemu-system-x86";
/// QEMU's GTK window, a module of its own package: only `cargo xtask run`
/// with a display opens one.
const QEMU_WINDOW_PACKAGE: &str = "qemu-system-gui";

/// OVMF, the UEFI firmware QEMU boots UEFI runs with: its code, mapped
/// read-only, and its empty variable store, which each run copies; where
/// Debian's `ovmf` puts them, and the variables that name others.
pub const OVMF_CODE: &str = "/usr/share/OVMF/OVMF_CODE_4M.fd";
pub const OVMF_VARS: &str = "/usr/share/OVMF/OVMF_VARS_4M.fd";
pub const OVMF_CODE_ENV: &str = "POLYLAB_OVMF_CODE";
pub const OVMF_VARS_ENV: &str = "POLYLAB_OVMF_VARS";
const OVMF_PACKAGE: &str = "ovmf";

/// OVMF's Secure Boot build (it needs SMM, so QEMU's q35 machine) and a
/// variable store with Microsoft's keys enrolled and Secure Boot on, both
/// in Debian's `ovmf` with [`OVMF_CODE`]; the variables name others.
pub const OVMF_SECURE_BOOT_CODE: &str = "/usr/share/OVMF/OVMF_CODE_4M.secboot.fd";
pub const OVMF_MICROSOFT_VARS: &str = "/usr/share/OVMF/OVMF_VARS_4M.ms.fd";
pub const OVMF_SECURE_BOOT_CODE_ENV: &str = "POLYLAB_OVMF_SECURE_BOOT_CODE";
pub const OVMF_MICROSOFT_VARS_ENV: &str = "POLYLAB_OVMF_MICROSOFT_VARS";

/// Bochs 2.7, the second emulator (`bochs.rs`), and the Debian packages
/// it needs: the emulator; its terminal display, which the runs use (it
/// also meets the package's need for a display library, else apt picks
/// the wxWidgets one); its own BIOS and VGA BIOSes, which it would
/// otherwise take from SeaBIOS. The BIOSes are where Debian puts them
/// unless the variables name others.
pub const BOCHS: &str = "bochs";
pub const BOCHS_BIOS: &str = "/usr/share/bochs/BIOS-bochs-latest";
pub const BOCHS_CIRRUS_VGA_BIOS: &str = "/usr/share/vgabios/vgabios-cirrus.bin";
pub const BOCHS_BIOS_ENV: &str = "POLYLAB_BOCHS_BIOS";
pub const BOCHS_CIRRUS_VGA_BIOS_ENV: &str = "POLYLAB_BOCHS_VGA_BIOS";
const BOCHS_PACKAGES: [&str; 4] = ["bochs", "bochs-term", "bochsbios", "vgabios"];

/// Makes sure `qemu-system-x86_64` is on the `PATH`: installs Debian's
/// `qemu-system-x86` ([`ensure_debian_packages`]: with apt-get as root,
/// else failing with the exact commands to run).
pub fn ensure_qemu() -> Result<()> {
    static DONE: OnceLock<Result<(), Failure>> = OnceLock::new();
    once_per_process(&DONE, || ensure_debian_packages(QEMU, &[QEMU_PACKAGE], || on_path(&[QEMU])))
}

/// QEMU's QXL card, and the package Debian's QEMU 8 and later keeps it
/// in (a module of its own, `hw-display-qxl`; QEMU 7.2's package has it
/// built in).
const QXL_DEVICE: &str = "qxl-vga";
const QXL_PACKAGE: &str = "qemu-system-modules-spice";

/// Makes sure QEMU has its QXL card (`-device help` lists it), installing
/// `qemu-system-modules-spice` as [`ensure_qemu`] installs QEMU (from the
/// same suite as QEMU, where that is backports). Where QEMU is missing,
/// the error names QEMU alone: whether the card needs a package of its
/// own depends on the QEMU installed (Debian 12's QEMU 7.2 has it built
/// in, and Debian 12 has no such package).
pub fn ensure_qemu_qxl() -> Result<()> {
    static DONE: OnceLock<Result<(), Failure>> = OnceLock::new();
    once_per_process(&DONE, || {
        ensure_qemu()?;
        let listed = || {
            let name = format!("name \"{QXL_DEVICE}\"");
            output_of(Command::new(QEMU).args(["-device", "help"])).is_ok_and(|help| help.contains(&name))
        };
        ensure_debian_packages("QEMU's QXL card (its SPICE module)", &[QXL_PACKAGE], listed)
    })
}

/// Makes sure QEMU can open a window (its GTK display module is there, as
/// `-display help` lists it), installing `qemu-system-gui` as
/// [`ensure_qemu`] installs QEMU. Where QEMU is missing too, a user who
/// is not root is told both at once ([`ensure_all`]): a QEMU installed
/// without its recommendations has no window.
pub fn ensure_qemu_window() -> Result<()> {
    static DONE: OnceLock<Result<(), Failure>> = OnceLock::new();
    once_per_process(&DONE, || ensure_all(&[ensure_qemu, ensure_gtk_display]))
}

/// Installs QEMU's GTK display module unless `-display help` lists it:
/// also where QEMU is missing, which lists nothing.
fn ensure_gtk_display() -> Result<()> {
    let has_window =
        || output_of(Command::new(QEMU).args(["-display", "help"])).is_ok_and(|help| help.lines().any(|l| l == "gtk"));
    ensure_debian_packages("QEMU's window (its GTK display)", &[QEMU_WINDOW_PACKAGE], has_window)
}

/// Makes sure Bochs, its BIOS and its Cirrus VGA BIOS are there,
/// installing them as [`ensure_qemu`] installs QEMU.
pub fn ensure_bochs() -> Result<()> {
    static DONE: OnceLock<Result<(), Failure>> = OnceLock::new();
    once_per_process(&DONE, || {
        let files = [(BOCHS_BIOS_ENV, BOCHS_BIOS), (BOCHS_CIRRUS_VGA_BIOS_ENV, BOCHS_CIRRUS_VGA_BIOS)];
        ensure_system_files("Bochs (with its BIOS and VGA BIOS)", &BOCHS_PACKAGES, &[BOCHS], &files)
    })
}

/// Makes sure OVMF's code and variable store are there, installing
/// Debian's `ovmf` as [`ensure_qemu`] installs QEMU.
pub fn ensure_ovmf() -> Result<()> {
    static DONE: OnceLock<Result<(), Failure>> = OnceLock::new();
    once_per_process(&DONE, || {
        let files = [(OVMF_CODE_ENV, OVMF_CODE), (OVMF_VARS_ENV, OVMF_VARS)];
        ensure_system_files("OVMF (the UEFI firmware for QEMU)", &[OVMF_PACKAGE], &[], &files)
    })
}

/// OVMF's code and variable store for the runs ([`OVMF_CODE_ENV`] and
/// [`OVMF_VARS_ENV`] name others than Debian's).
pub fn ovmf_code() -> PathBuf {
    system_file(OVMF_CODE_ENV, OVMF_CODE)
}

pub fn ovmf_vars() -> PathBuf {
    system_file(OVMF_VARS_ENV, OVMF_VARS)
}

/// Makes sure OVMF's Secure Boot build and its variable store with
/// Microsoft's keys are there, installing Debian's `ovmf` as
/// [`ensure_qemu`] installs QEMU.
pub fn ensure_secure_boot_ovmf() -> Result<()> {
    static DONE: OnceLock<Result<(), Failure>> = OnceLock::new();
    once_per_process(&DONE, || {
        let files =
            [(OVMF_SECURE_BOOT_CODE_ENV, OVMF_SECURE_BOOT_CODE), (OVMF_MICROSOFT_VARS_ENV, OVMF_MICROSOFT_VARS)];
        ensure_system_files("OVMF's Secure Boot build (with Microsoft's keys)", &[OVMF_PACKAGE], &[], &files)
    })
}

/// OVMF's Secure Boot build and its store with Microsoft's keys for the
/// runs ([`OVMF_SECURE_BOOT_CODE_ENV`] and [`OVMF_MICROSOFT_VARS_ENV`] name
/// others than Debian's).
pub fn ovmf_secure_boot_code() -> PathBuf {
    system_file(OVMF_SECURE_BOOT_CODE_ENV, OVMF_SECURE_BOOT_CODE)
}

pub fn ovmf_microsoft_vars() -> PathBuf {
    system_file(OVMF_MICROSOFT_VARS_ENV, OVMF_MICROSOFT_VARS)
}
