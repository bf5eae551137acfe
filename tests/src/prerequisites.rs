//! Installing what the build and the runs need when it is missing: the
//! pinned nightly with its components and target, QEMU, the Cairo headers
//! the lab's Cairo peer builds against, and cargo-fuzz. Machines here set
//! `RUSTUP_AUTO_INSTALL=0`, so nothing installs itself.

use std::path::PathBuf;
use std::process::Command;
use std::sync::OnceLock;

use anyhow::{bail, Context, Result};

use crate::cargo::{pinned, KERNEL_TARGET, PINNED_TOOLCHAIN};
use crate::once::once_per_process;
use crate::process::{output_of, run_streaming};

/// Components of the pinned nightly: `bootloader`'s build script compiles
/// its BIOS stages with `-Zbuild-std` (rust-src) and links them with LLVM's
/// tools (llvm-tools-preview). Each with the prefix rustup lists it under
/// once installed.
const COMPONENTS: [(&str, &str); 2] = [("rust-src", "rust-src"), ("llvm-tools-preview", "llvm-tools")];

/// The QEMU binary the harness runs, and the Debian package that has it.
pub const QEMU: &str = "qemu-system-x86_64";
const QEMU_PACKAGE: &str = "qemu-system-x86";

/// The Debian packages the lab's Cairo peer (`cairo-rs` over the system
/// libcairo) builds with: the headers and `.pc` file, and pkg-config, which
/// finds them.
const CAIRO_PACKAGES: [&str; 2] = ["libcairo2-dev", "pkg-config"];

/// Makes sure the pinned nightly, its components and the kernel target are
/// installed, installing what is missing (and saying so). Costs two quick
/// rustup look-ups when everything is there.
pub fn ensure_toolchain() -> Result<()> {
    static DONE: OnceLock<Result<(), String>> = OnceLock::new();
    once_per_process(&DONE, || {
        let toolchains = output_of(Command::new("rustup").args(["toolchain", "list"]))
            .context("rustup is needed to install the pinned nightly (see https://rustup.rs)")?;
        let installed = if has_toolchain(&toolchains) {
            Some(output_of(pinned("rustup").args(["component", "list", "--installed"]))?)
        } else {
            None
        };
        let commands = install_commands(installed.as_deref());
        if commands.is_empty() {
            return Ok(());
        }
        eprintln!(
            "harness: installing what the kernel build needs: Rust toolchain {PINNED_TOOLCHAIN} \
             (profile minimal) with {} and target {KERNEL_TARGET}",
            COMPONENTS.map(|(name, _)| name).join(", ")
        );
        for mut command in commands {
            run_streaming(&mut command).context("failed to install the pinned nightly")?;
        }
        Ok(())
    })
}

fn has_toolchain(rustup_toolchain_list: &str) -> bool {
    rustup_toolchain_list
        .lines()
        .any(|line| line.starts_with(&format!("{PINNED_TOOLCHAIN}-")) || line == PINNED_TOOLCHAIN)
}

/// The rustup commands that complete the install, given the pinned nightly's
/// `component list --installed` output (`None`: not installed at all).
fn install_commands(installed: Option<&str>) -> Vec<Command> {
    let Some(installed) = installed else {
        let mut install = Command::new("rustup");
        install.args(["toolchain", "install", PINNED_TOOLCHAIN, "--profile", "minimal", "--component"]);
        install.arg(COMPONENTS.map(|(name, _)| name).join(","));
        install.args(["--target", KERNEL_TARGET]);
        return vec![install];
    };
    let has = |prefix: &str| installed.lines().any(|line| line.trim().starts_with(prefix));
    let mut commands = Vec::new();
    let missing: Vec<&str> = COMPONENTS.iter().filter(|(_, prefix)| !has(prefix)).map(|(name, _)| *name).collect();
    if !missing.is_empty() {
        let mut add = Command::new("rustup");
        add.args(["component", "add", "--toolchain", PINNED_TOOLCHAIN]).args(missing);
        commands.push(add);
    }
    if !has(&format!("rust-std-{KERNEL_TARGET}")) {
        let mut add = Command::new("rustup");
        add.args(["target", "add", "--toolchain", PINNED_TOOLCHAIN, KERNEL_TARGET]);
        commands.push(add);
    }
    commands
}

/// Makes sure `qemu-system-x86_64` is on the `PATH`: installs Debian's
/// `qemu-system-x86` with apt-get when running as root, otherwise fails
/// with the exact command to run.
pub fn ensure_qemu() -> Result<()> {
    static DONE: OnceLock<Result<(), String>> = OnceLock::new();
    once_per_process(&DONE, || ensure_debian_packages(QEMU, &[QEMU_PACKAGE], || on_path(&[QEMU])))
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
            "{what} is not installed; install it with:\n    sudo apt-get update && sudo apt-get install -y {packages}"
        );
    }
    eprintln!("harness: {what} is missing; installing the Debian packages {packages} with apt-get");
    run_streaming(Command::new("apt-get").arg("update"))?;
    run_streaming(
        Command::new("apt-get")
            .args(["install", "-y"])
            .args(packages.split(' '))
            .env("DEBIAN_FRONTEND", "noninteractive"),
    )?;
    if !present() {
        bail!("{packages} installed, but {what} is still not found");
    }
    Ok(())
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

    fn lines(commands: &[Command]) -> Vec<String> {
        commands.iter().map(command_line).collect()
    }

    #[test]
    fn a_missing_toolchain_is_installed_whole() {
        assert_eq!(
            lines(&install_commands(None)),
            ["rustup toolchain install nightly-2026-10-01 --profile minimal --component rust-src,llvm-tools-preview --target x86_64-unknown-none"]
        );
    }

    #[test]
    fn a_complete_toolchain_needs_nothing() {
        let installed = "cargo-x86_64-unknown-linux-gnu\nllvm-tools-x86_64-unknown-linux-gnu\nrust-src\n\
                         rust-std-x86_64-unknown-linux-gnu\nrust-std-x86_64-unknown-none\nrustc-x86_64-unknown-linux-gnu\n";
        assert!(install_commands(Some(installed)).is_empty());
    }

    #[test]
    fn missing_components_and_target_are_added() {
        let installed = "cargo-x86_64-unknown-linux-gnu\nrust-src\nrustc-x86_64-unknown-linux-gnu\n";
        assert_eq!(
            lines(&install_commands(Some(installed))),
            [
                "rustup component add --toolchain nightly-2026-10-01 llvm-tools-preview",
                "rustup target add --toolchain nightly-2026-10-01 x86_64-unknown-none",
            ]
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

    #[test]
    fn the_toolchain_is_recognised_with_or_without_its_host_suffix() {
        assert!(has_toolchain(
            "stable-x86_64-unknown-linux-gnu (default)\nnightly-2026-10-01-x86_64-unknown-linux-gnu\n"
        ));
        assert!(has_toolchain("nightly-2026-10-01\n"));
        assert!(!has_toolchain("nightly-2026-10-011-x86_64-unknown-linux-gnu\nnightly-x86_64-unknown-linux-gnu\n"));
    }
}
