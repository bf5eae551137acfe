//! Installing what the runs need when it is missing: QEMU (and its window
//! and OVMF, the UEFI firmware, when a run needs them), Chromium and
//! chromedriver, the wasm32 target, the Cairo headers the lab's Cairo peer
//! builds against, the C libraries of its Allegro, SDL2_gfx and GD peers,
//! and cargo-fuzz with a C++ compiler for libFuzzer (the
//! pinned nightly the image builds with is `boot_image::toolchain`'s). Machines here set `RUSTUP_AUTO_INSTALL=0`,
//! so nothing installs itself. Debian packages come with their
//! dependencies but without their recommendations: exactly the packages
//! named here, each for the reason its constant says (`packages` installs
//! them, on Debian, Ubuntu and their derivatives).
//!
//! Each is ensured where it is used (QEMU when a QEMU starts, Chromium
//! when a browser does), so a run installs only what its tests need. The
//! firmware files and the browser are where Debian puts them unless an
//! environment variable names others (`POLYLAB_OVMF_CODE`, ...: see each
//! constant); a file so named must exist, and nothing is installed for it.

use std::ffi::OsString;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

use anyhow::{ensure, Context, Result};

use boot_image::once::once_per_process;
pub use boot_image::process::find_in_path;
use boot_image::process::{output_of, run_streaming};

pub use crate::packages::ensure_debian_packages;

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

/// The Debian packages the lab's Cairo peer (`cairo-rs` over the system
/// libcairo) builds with: the headers and `.pc` file, and pkg-config, which
/// finds them.
const CAIRO_PACKAGES: [&str; 2] = ["libcairo2-dev", "pkg-config"];

/// The Debian packages the lab's C peers build and link with: Allegro 4
/// (`polygon()`), SDL2 with its gfx add-on (`filledPolygonRGBA`), GD
/// (`gdImageFilledPolygon`), each with its headers and `.pc` file, and
/// pkg-config, which finds them.
const PEER_PACKAGES: [&str; 5] = ["liballegro4-dev", "libsdl2-dev", "libsdl2-gfx-dev", "libgd-dev", "pkg-config"];
/// Their pkg-config names, all of which must be found.
const PEER_PKG_CONFIG: [&str; 4] = ["allegro", "sdl2", "SDL2_gfx", "gdlib"];

/// Makes sure `qemu-system-x86_64` is on the `PATH`: installs Debian's
/// `qemu-system-x86` with apt-get when running as root, otherwise fails
/// with the exact command to run.
pub fn ensure_qemu() -> Result<()> {
    static DONE: OnceLock<Result<(), String>> = OnceLock::new();
    once_per_process(&DONE, || ensure_debian_packages(QEMU, &[QEMU_PACKAGE], || on_path(&[QEMU])))
}

/// QEMU's QXL card, and the package Debian's QEMU 8 and later keeps it
/// in (a module of its own, `hw-display-qxl`; QEMU 7.2's package has it
/// built in).
const QXL_DEVICE: &str = "qxl-vga";
const QXL_PACKAGE: &str = "qemu-system-modules-spice";

/// Makes sure QEMU has its QXL card (`-device help` lists it), installing
/// `qemu-system-modules-spice` as [`ensure_qemu`] installs QEMU (from the
/// same suite as QEMU, where that is backports).
pub fn ensure_qemu_qxl() -> Result<()> {
    static DONE: OnceLock<Result<(), String>> = OnceLock::new();
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
/// [`ensure_qemu`] installs QEMU.
pub fn ensure_qemu_window() -> Result<()> {
    static DONE: OnceLock<Result<(), String>> = OnceLock::new();
    once_per_process(&DONE, || {
        ensure_qemu()?;
        let has_window = || {
            output_of(Command::new(QEMU).args(["-display", "help"])).is_ok_and(|help| help.lines().any(|l| l == "gtk"))
        };
        ensure_debian_packages("QEMU's window (its GTK display)", &[QEMU_WINDOW_PACKAGE], has_window)
    })
}

/// Makes sure Bochs, its BIOS and its Cirrus VGA BIOS are there,
/// installing them as [`ensure_qemu`] installs QEMU.
pub fn ensure_bochs() -> Result<()> {
    static DONE: OnceLock<Result<(), String>> = OnceLock::new();
    once_per_process(&DONE, || {
        let files = [(BOCHS_BIOS_ENV, BOCHS_BIOS), (BOCHS_CIRRUS_VGA_BIOS_ENV, BOCHS_CIRRUS_VGA_BIOS)];
        ensure_system_files("Bochs (with its BIOS and VGA BIOS)", &BOCHS_PACKAGES, &[BOCHS], &files)
    })
}

/// Makes sure OVMF's code and variable store are there, installing
/// Debian's `ovmf` as [`ensure_qemu`] installs QEMU.
pub fn ensure_ovmf() -> Result<()> {
    static DONE: OnceLock<Result<(), String>> = OnceLock::new();
    once_per_process(&DONE, || {
        let files = [(OVMF_CODE_ENV, OVMF_CODE), (OVMF_VARS_ENV, OVMF_VARS)];
        ensure_system_files("OVMF (the UEFI firmware for QEMU)", &[OVMF_PACKAGE], &[], &files)
    })
}

/// The file the environment variable `env` names, or else `default`
/// (where a Debian package puts it).
pub fn system_file(env: &str, default: &str) -> PathBuf {
    chosen(std::env::var_os(env), default)
}

fn chosen(named: Option<OsString>, default: &str) -> PathBuf {
    named.filter(|named| !named.is_empty()).map_or_else(|| PathBuf::from(default), PathBuf::from)
}

/// Makes sure `programs` are on the `PATH` and `files` (each an
/// environment variable and Debian's path, [`system_file`]) exist,
/// installing `packages` as [`ensure_qemu`] installs QEMU; a file a
/// variable names must exist already.
fn ensure_system_files(what: &str, packages: &[&str], programs: &[&str], files: &[(&str, &str)]) -> Result<()> {
    ensure_named_files_exist(files)?;
    let present = || on_path(programs) && files.iter().all(|(env, path)| system_file(env, path).is_file());
    ensure_debian_packages(what, packages, present)
}

/// Fails unless every file an environment variable of `files` names
/// exists: a file the user names is never installed over.
fn ensure_named_files_exist(files: &[(&str, &str)]) -> Result<()> {
    for (env, default) in files {
        let path = system_file(env, default);
        ensure!(path == Path::new(default) || path.is_file(), "{env} names {}, which is not a file", path.display());
    }
    Ok(())
}

/// OVMF's code and variable store for the runs ([`OVMF_CODE_ENV`] and
/// [`OVMF_VARS_ENV`] name others than Debian's).
pub fn ovmf_code() -> PathBuf {
    system_file(OVMF_CODE_ENV, OVMF_CODE)
}

pub fn ovmf_vars() -> PathBuf {
    system_file(OVMF_VARS_ENV, OVMF_VARS)
}

/// The browser the explorer's tests drive, its WebDriver server, and the
/// Debian packages that have them; the variables name others (a path, or
/// a program on the PATH), such as Google Chrome and its chromedriver.
pub const CHROMIUM: &str = "chromium";
pub const CHROMEDRIVER: &str = "chromedriver";
pub const CHROMIUM_ENV: &str = "POLYLAB_CHROMIUM";
pub const CHROMEDRIVER_ENV: &str = "POLYLAB_CHROMEDRIVER";
const CHROMIUM_PACKAGES: [&str; 2] = ["chromium", "chromium-driver"];

/// Where the browser ([`CHROMIUM_ENV`], else `chromium` on the PATH) and
/// its driver ([`CHROMEDRIVER_ENV`], else `chromedriver`) are.
pub fn chromium() -> Option<PathBuf> {
    program(CHROMIUM_ENV, CHROMIUM)
}

pub fn chromedriver() -> Option<PathBuf> {
    program(CHROMEDRIVER_ENV, CHROMEDRIVER)
}

/// The program `env` names (a path, or a name on the PATH), or else
/// `default` on the PATH.
fn program(env: &str, default: &str) -> Option<PathBuf> {
    let named = chosen(std::env::var_os(env), default);
    if named.components().count() > 1 {
        return named.is_file().then_some(named);
    }
    find_in_path(named.to_str()?)
}

/// Makes sure the browser and its driver are there, installing Debian's
/// `chromium` and `chromium-driver` as [`ensure_qemu`] installs QEMU
/// unless the variables name others, which must then exist.
pub fn ensure_chromium() -> Result<()> {
    static DONE: OnceLock<Result<(), String>> = OnceLock::new();
    once_per_process(&DONE, || {
        for (env, found) in [(CHROMIUM_ENV, chromium()), (CHROMEDRIVER_ENV, chromedriver())] {
            if let Some(named) = std::env::var_os(env).filter(|named| !named.is_empty()) {
                ensure!(found.is_some(), "{env} names {}, which is not a program", named.to_string_lossy());
            }
        }
        ensure_debian_packages("Chromium (chromium and chromedriver)", &CHROMIUM_PACKAGES, || {
            chromium().is_some() && chromedriver().is_some()
        })
    })
}

/// Makes sure libcairo's headers are there for `pkg-config --exists cairo`,
/// as the lab's Cairo peer needs to build: installs Debian's
/// `libcairo2-dev` (and `pkg-config`) with apt-get when running as root,
/// otherwise fails with the exact command to run.
pub fn ensure_cairo() -> Result<()> {
    static DONE: OnceLock<Result<(), String>> = OnceLock::new();
    once_per_process(&DONE, || {
        let found = || Command::new("pkg-config").args(["--exists", "cairo"]).status().is_ok_and(|s| s.success());
        ensure_debian_packages("libcairo (for the lab's Cairo peer)", &CAIRO_PACKAGES, found)
    })
}

/// Makes sure the C libraries of the lab's Allegro, SDL2_gfx and GD peers
/// are there for `pkg-config --exists`, as the lab needs to build:
/// installs their Debian `-dev` packages as [`ensure_cairo`] installs
/// Cairo's.
pub fn ensure_peer_libraries() -> Result<()> {
    static DONE: OnceLock<Result<(), String>> = OnceLock::new();
    once_per_process(&DONE, || {
        let found =
            || Command::new("pkg-config").arg("--exists").args(PEER_PKG_CONFIG).status().is_ok_and(|s| s.success());
        ensure_debian_packages("Allegro 4, SDL2_gfx and GD (for the lab's C peers)", &PEER_PACKAGES, found)
    })
}

/// The cargo-fuzz release `cargo xtask fuzz` installs when none is there.
pub const CARGO_FUZZ_VERSION: &str = "0.13.2";

/// Makes sure a C++ compiler is there for libFuzzer, which the fuzz
/// targets' `libfuzzer-sys` compiles: installs Debian's `g++` as
/// [`ensure_qemu`] installs QEMU.
pub fn ensure_cxx() -> Result<()> {
    static DONE: OnceLock<Result<(), String>> = OnceLock::new();
    once_per_process(&DONE, || ensure_debian_packages("a C++ compiler (for libFuzzer)", &["g++"], || on_path(&["c++"])))
}

/// Makes sure `cargo fuzz` (cargo-fuzz, which builds the fuzz targets with
/// libFuzzer) is installed, installing it from crates.io with `cargo
/// install --locked` when missing, and a C++ compiler ([`ensure_cxx`]).
pub fn ensure_cargo_fuzz() -> Result<()> {
    static DONE: OnceLock<Result<(), String>> = OnceLock::new();
    once_per_process(&DONE, || {
        ensure_cxx()?;
        if find_in_path("cargo-fuzz").is_some() {
            return Ok(());
        }
        eprintln!(
            "harness: installing cargo-fuzz {CARGO_FUZZ_VERSION} from crates.io (cargo install), \
             which builds and runs the fuzz targets"
        );
        run_streaming(&mut cargo_fuzz_install_command()).context("failed to install cargo-fuzz")
    })
}

fn cargo_fuzz_install_command() -> Command {
    let mut install = boot_image::cargo::host();
    install.args(["install", "cargo-fuzz", "--locked", "--version", CARGO_FUZZ_VERSION]);
    install
}

/// Whether every one of `programs` is on the `PATH`.
fn on_path(programs: &[&str]) -> bool {
    programs.iter().all(|program| find_in_path(program).is_some())
}

/// The target the explorer's engine is built for.
pub const WASM_TARGET: &str = "wasm32-unknown-unknown";

/// Makes sure the toolchain that runs us (the one `cargo xtask` or `cargo
/// test` was started with, the one [`boot_image::cargo::host`] builds with) has
/// the `wasm32-unknown-unknown` target, adding it with rustup when missing.
pub fn ensure_wasm_target() -> Result<()> {
    static DONE: OnceLock<Result<(), String>> = OnceLock::new();
    once_per_process(&DONE, || {
        let toolchain = host_toolchain()?;
        let installed =
            output_of(Command::new("rustup").args(["target", "list", "--installed", "--toolchain"]).arg(&toolchain))
                .context("rustup is needed to add the wasm32 target (see https://rustup.rs)")?;
        if installed.lines().any(|line| line.trim() == WASM_TARGET) {
            return Ok(());
        }
        eprintln!("harness: adding target {WASM_TARGET} to Rust toolchain {toolchain} for the explorer page");
        run_streaming(&mut wasm_target_command(&toolchain)).context("failed to add the wasm32 target")
    })
}

/// The rustup toolchain that runs us: rustup's proxies name it in
/// `RUSTUP_TOOLCHAIN` to every process they start; failing that, the one
/// rustup picks here.
fn host_toolchain() -> Result<String> {
    if let Some(toolchain) = std::env::var_os("RUSTUP_TOOLCHAIN") {
        return Ok(toolchain.to_string_lossy().into_owned());
    }
    let active = output_of(Command::new("rustup").args(["show", "active-toolchain"]))
        .context("rustup is needed to add the wasm32 target (see https://rustup.rs)")?;
    active.split_whitespace().next().map(str::to_string).context("rustup named no active toolchain")
}

fn wasm_target_command(toolchain: &str) -> Command {
    let mut add = Command::new("rustup");
    add.args(["target", "add", "--toolchain", toolchain, WASM_TARGET]);
    add
}

/// OVMF's Secure Boot build (it needs SMM, so QEMU's q35 machine) and a
/// variable store with Microsoft's keys enrolled and Secure Boot on, both
/// in Debian's `ovmf` with [`OVMF_CODE`]; the variables name others.
pub const OVMF_SECURE_BOOT_CODE: &str = "/usr/share/OVMF/OVMF_CODE_4M.secboot.fd";
pub const OVMF_MICROSOFT_VARS: &str = "/usr/share/OVMF/OVMF_VARS_4M.ms.fd";
pub const OVMF_SECURE_BOOT_CODE_ENV: &str = "POLYLAB_OVMF_SECURE_BOOT_CODE";
pub const OVMF_MICROSOFT_VARS_ENV: &str = "POLYLAB_OVMF_MICROSOFT_VARS";

/// Makes sure OVMF's Secure Boot build and its variable store with
/// Microsoft's keys are there, installing Debian's `ovmf` as
/// [`ensure_qemu`] installs QEMU.
pub fn ensure_secure_boot_ovmf() -> Result<()> {
    static DONE: OnceLock<Result<(), String>> = OnceLock::new();
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

/// The release of virt-firmware (PyPI) whose `virt-fw-vars` writes the
/// Secure Boot tests' MOK lists into OVMF variable stores: the one Debian
/// 13 packages, which needs only `cryptography`, `pefile` and
/// `setuptools`; later releases also need `crypt_r` on Python 3.13 (its
/// cloud-init helper hashes passwords), a C extension that does not build
/// there without Python's headers.
pub const VIRT_FIRMWARE_VERSION: &str = "24.11";
/// The setuptools it imports `pkg_resources` from: the last release that
/// has it (82.0 removed it). Python 3.11's venv brings an older setuptools,
/// Python 3.12's and later none, and pip would then take the newest.
pub const SETUPTOOLS_VERSION: &str = "81.0.0";

/// Makes sure `virt-fw-vars` is there and returns its path: virt-firmware
/// [`VIRT_FIRMWARE_VERSION`] installed from PyPI with pip into a Python
/// virtual environment under `target/` (Python's `venv` module, Debian's
/// `python3-venv`, installed as [`ensure_qemu`] installs QEMU).
pub fn ensure_virt_fw_vars() -> Result<PathBuf> {
    static DONE: OnceLock<Result<PathBuf, String>> = OnceLock::new();
    once_per_process(&DONE, || {
        let venv = crate::workspace::target_dir().join("virt-firmware");
        let program = venv.join("bin").join("virt-fw-vars");
        let installed = venv.join(format!("virt-firmware-{VIRT_FIRMWARE_VERSION}-setuptools-{SETUPTOOLS_VERSION}"));
        if program.is_file() && installed.is_file() {
            return Ok(program);
        }
        // Debian's python3 has the `venv` module but not `ensurepip`, which
        // `venv` needs to put pip into the environment: python3-venv adds
        // it. (`python3 -m venv --help` succeeds without it.)
        let has_venv = || {
            Command::new("python3").args(["-c", "import ensurepip, venv"]).output().is_ok_and(|o| o.status.success())
        };
        ensure_debian_packages("Python's venv module (for virt-firmware)", &["python3-venv"], has_venv)?;
        eprintln!(
            "harness: installing virt-firmware {VIRT_FIRMWARE_VERSION} from PyPI into {} (its virt-fw-vars \
             writes the Secure Boot tests' MOK lists)",
            venv.display()
        );
        run_streaming(Command::new("python3").args(["-m", "venv"]).arg(&venv))?;
        run_streaming(&mut virt_firmware_install_command(&venv))?;
        std::fs::write(&installed, "").with_context(|| format!("failed to write {}", installed.display()))?;
        Ok(program)
    })
}

fn virt_firmware_install_command(venv: &Path) -> Command {
    let mut install = Command::new(venv.join("bin").join("pip"));
    install.args(["install", "--quiet", &format!("virt-firmware=={VIRT_FIRMWARE_VERSION}")]);
    install.arg(format!("setuptools=={SETUPTOOLS_VERSION}"));
    install
}

#[cfg(test)]
mod tests {
    use super::*;
    use boot_image::process::command_line;

    #[test]
    fn a_named_file_or_program_replaces_debians() {
        assert_eq!(chosen(None, OVMF_CODE), Path::new(OVMF_CODE));
        assert_eq!(chosen(Some("".into()), OVMF_CODE), Path::new(OVMF_CODE));
        assert_eq!(chosen(Some("/opt/edk2/code.fd".into()), OVMF_CODE), Path::new("/opt/edk2/code.fd"));
    }

    #[test]
    fn the_wasm_target_is_added_to_the_named_toolchain() {
        assert_eq!(
            command_line(&wasm_target_command("stable-x86_64-unknown-linux-gnu")),
            "rustup target add --toolchain stable-x86_64-unknown-linux-gnu wasm32-unknown-unknown"
        );
    }

    #[test]
    fn virt_firmware_is_installed_at_its_pinned_version_into_the_venv() {
        assert_eq!(
            command_line(&virt_firmware_install_command(Path::new("/t/virt-firmware"))),
            "/t/virt-firmware/bin/pip install --quiet virt-firmware==24.11 setuptools==81.0.0"
        );
    }

    #[test]
    fn cargo_fuzz_is_installed_at_its_pinned_version_from_the_lock_file() {
        assert!(command_line(&cargo_fuzz_install_command()).ends_with(" install cargo-fuzz --locked --version 0.13.2"));
    }
}
