//! Installing what the runs need when it is missing: QEMU (and its window
//! and OVMF, the UEFI firmware, when a run needs them), Chromium and
//! chromedriver, the wasm32 target, the Cairo headers the lab's Cairo peer
//! builds against, the C libraries of its Allegro, SDL2_gfx and GD peers,
//! and cargo-fuzz with a C++ compiler for libFuzzer (the
//! pinned nightly the image builds with is `boot_image::toolchain`'s). Machines here set `RUSTUP_AUTO_INSTALL=0`,
//! so nothing installs itself. Debian packages come with their
//! dependencies but without their recommendations: exactly the packages
//! named here, each for the reason its constant says.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

use anyhow::{bail, Context, Result};

use boot_image::once::once_per_process;
use boot_image::process::{output_of, run_streaming};

/// The QEMU binary the harness runs, and the Debian package that has it
/// (with SeaBIOS and the VGA BIOSes, its dependencies).
pub const QEMU: &str = "qemu-system-x86_64";
const QEMU_PACKAGE: &str = "qemu-system-x86";
/// QEMU's GTK window, a module of its own package: only `cargo xtask run`
/// with a display opens one.
const QEMU_WINDOW_PACKAGE: &str = "qemu-system-gui";

/// OVMF, the UEFI firmware QEMU boots UEFI runs with: its code, mapped
/// read-only, and its empty variable store, which each run copies.
pub const OVMF_CODE: &str = "/usr/share/OVMF/OVMF_CODE_4M.fd";
pub const OVMF_VARS: &str = "/usr/share/OVMF/OVMF_VARS_4M.fd";
const OVMF_PACKAGE: &str = "ovmf";

/// Bochs 2.7, the second emulator (`bochs.rs`), and the Debian packages
/// it needs: the emulator; its terminal display, the smallest package
/// that meets its need for a display library (else apt picks the
/// wxWidgets one); its own BIOS and VGA BIOSes, which it would otherwise
/// take from SeaBIOS.
pub const BOCHS: &str = "bochs";
pub const BOCHS_BIOS: &str = "/usr/share/bochs/BIOS-bochs-latest";
pub const BOCHS_CIRRUS_VGA_BIOS: &str = "/usr/share/vgabios/vgabios-cirrus.bin";
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
        let present =
            || on_path(&[BOCHS]) && [BOCHS_BIOS, BOCHS_CIRRUS_VGA_BIOS].iter().all(|f| Path::new(f).is_file());
        ensure_debian_packages("Bochs (with its BIOS and VGA BIOS)", &BOCHS_PACKAGES, present)
    })
}

/// Makes sure OVMF's code and variable store are there, installing
/// Debian's `ovmf` as [`ensure_qemu`] installs QEMU.
pub fn ensure_ovmf() -> Result<()> {
    static DONE: OnceLock<Result<(), String>> = OnceLock::new();
    once_per_process(&DONE, || {
        let present = || [OVMF_CODE, OVMF_VARS].iter().all(|file| Path::new(file).is_file());
        ensure_debian_packages("OVMF (the UEFI firmware for QEMU)", &[OVMF_PACKAGE], present)
    })
}

/// The browser the explorer's tests drive, its WebDriver server, and the
/// Debian packages that have them.
pub const CHROMIUM: &str = "chromium";
pub const CHROMEDRIVER: &str = "chromedriver";
const CHROMIUM_PACKAGES: [&str; 2] = ["chromium", "chromium-driver"];

/// Makes sure `chromium` and `chromedriver` are on the `PATH`, installing
/// Debian's `chromium` and `chromium-driver` as [`ensure_qemu`] installs QEMU.
pub fn ensure_chromium() -> Result<()> {
    static DONE: OnceLock<Result<(), String>> = OnceLock::new();
    once_per_process(&DONE, || {
        ensure_debian_packages("Chromium (chromium and chromedriver)", &CHROMIUM_PACKAGES, || {
            on_path(&[CHROMIUM, CHROMEDRIVER])
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
    let mut install = crate::cargo::host();
    install.args(["install", "cargo-fuzz", "--locked", "--version", CARGO_FUZZ_VERSION]);
    install
}

/// Installs `packages` with apt-get unless `present` says `what` is there
/// already; without root (or apt-get) fails with the command to run.
fn ensure_debian_packages(what: &str, packages: &[&str], present: impl Fn() -> bool) -> Result<()> {
    if present() {
        return Ok(());
    }
    let packages = packages.join(" ");
    let as_root = output_of(Command::new("id").arg("-u")).is_ok_and(|uid| uid.trim() == "0");
    if !as_root || find_in_path("apt-get").is_none() {
        bail!(
            "{what} is not installed; install it with:\n    sudo apt-get update && sudo apt-get install -y \
             --no-install-recommends {packages}"
        );
    }
    eprintln!("harness: {what} is missing; installing the Debian packages {packages} with apt-get");
    run_streaming(Command::new("apt-get").arg("update"))?;
    run_streaming(&mut apt_install(packages.split(' ')))?;
    if !present() {
        bail!("{packages} installed, but {what} is still not found");
    }
    Ok(())
}

/// `apt-get install` of `packages` and their dependencies, without the
/// packages they merely recommend (for QEMU: its GUI, OVMF, its disk
/// tools and block backends, and what they pull in), which a run needs
/// only as named above.
fn apt_install<'a>(packages: impl IntoIterator<Item = &'a str>) -> Command {
    let mut install = Command::new("apt-get");
    install.args(["install", "-y", "--no-install-recommends"]).args(packages).env("DEBIAN_FRONTEND", "noninteractive");
    install
}

/// Whether every one of `programs` is on the `PATH`.
fn on_path(programs: &[&str]) -> bool {
    programs.iter().all(|program| find_in_path(program).is_some())
}

/// The target the explorer's engine is built for.
pub const WASM_TARGET: &str = "wasm32-unknown-unknown";

/// Makes sure the toolchain that runs us (the one `cargo xtask` or `cargo
/// test` was started with, the one [`crate::cargo::host`] builds with) has
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

/// The first `program` on the `PATH`.
pub fn find_in_path(program: &str) -> Option<PathBuf> {
    let path = std::env::var_os("PATH")?;
    std::env::split_paths(&path).map(|dir| dir.join(program)).find(|candidate| candidate.is_file())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::process::command_line;

    #[test]
    fn debian_packages_come_without_their_recommendations() {
        assert_eq!(
            command_line(&apt_install(["qemu-system-x86", "ovmf"])),
            "apt-get install -y --no-install-recommends qemu-system-x86 ovmf"
        );
    }

    #[test]
    fn the_wasm_target_is_added_to_the_named_toolchain() {
        assert_eq!(
            command_line(&wasm_target_command("stable-x86_64-unknown-linux-gnu")),
            "rustup target add --toolchain stable-x86_64-unknown-linux-gnu wasm32-unknown-unknown"
        );
    }

    #[test]
    fn cargo_fuzz_is_installed_at_its_pinned_version_from_the_lock_file() {
        assert!(command_line(&cargo_fuzz_install_command()).ends_with(" install cargo-fuzz --locked --version 0.13.2"));
    }
}
