//! The Rust toolchains and tools the commands build with: the cargo that
//! runs us (stable, for the host crates), the pinned nightly the kernel
//! and the boot stages build with, the wasm32 target the explorer's engine
//! is built for, the thumbv7em target `raster` is checked on, and
//! cargo-fuzz; each installed with rustup or cargo when
//! missing. Machines here set `RUSTUP_AUTO_INSTALL=0`, so nothing installs
//! itself.

use std::process::Command;
use std::sync::OnceLock;

use anyhow::{Context, Result};

use crate::once::{once_per_process, Failure};
use crate::packages::ensure_debian_packages;
use crate::process::{find_in_path, output_of, run_streaming};
use crate::workspace;

/// The nightly that builds the kernel and `bootloader`'s BIOS stages
/// (`docs/development.md#the-toolchain`: `x86_64` 0.15.5 needs >= 2026-07-10).
pub const PINNED_TOOLCHAIN: &str = "nightly-2026-10-01";
/// The kernel's target triple.
pub const KERNEL_TARGET: &str = "x86_64-unknown-none";

/// Components of the pinned nightly: `bootloader`'s build script compiles
/// its BIOS stages with `-Zbuild-std` (rust-src) and links them with LLVM's
/// tools (llvm-tools-preview). Each with the prefix rustup lists it under
/// once installed.
const COMPONENTS: [(&str, &str); 2] = [("rust-src", "rust-src"), ("llvm-tools-preview", "llvm-tools")];

/// Variables that a parent cargo (`cargo xtask`, `cargo test`) or rustup
/// proxy sets: `RUSTC`, `RUSTDOC`, `CARGO` and the wrappers name the stable
/// tools and would beat `+toolchain`, the flags are the host build's, and
/// `RUSTUP_TOOLCHAIN` would pick stable for any tool the nightly cargo
/// starts through a proxy.
const PARENT_TOOLCHAIN_VARS: &[&str] = &[
    "RUSTUP_TOOLCHAIN",
    "RUSTUP_TOOLCHAIN_SOURCE",
    "RUSTC",
    "RUSTDOC",
    "CARGO",
    "RUSTFLAGS",
    "CARGO_ENCODED_RUSTFLAGS",
    "RUSTDOCFLAGS",
    "CARGO_ENCODED_RUSTDOCFLAGS",
    "RUSTC_WRAPPER",
    "RUSTC_WORKSPACE_WRAPPER",
    "CARGO_BUILD_TARGET",
];

/// `program` (a rustup proxy: `cargo` or `rustup`) with the pinned toolchain
/// selected by `+toolchain`, the parent's toolchain variables removed, run
/// from the workspace root.
pub fn pinned(program: &str) -> Command {
    let mut command = Command::new(program);
    command.arg(format!("+{PINNED_TOOLCHAIN}")).current_dir(workspace::root());
    for var in PARENT_TOOLCHAIN_VARS {
        command.env_remove(var);
    }
    command
}

/// The cargo that runs the xtask (the stable toolchain, for the host
/// crates), run from the workspace root.
pub fn host() -> Command {
    let mut command = Command::new(std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into()));
    command.current_dir(workspace::root());
    command
}

/// Makes sure the pinned nightly, its components and the kernel target are
/// installed, installing what is missing (and saying so). Costs two quick
/// rustup look-ups when everything is there.
pub fn ensure_toolchain() -> Result<()> {
    static DONE: OnceLock<Result<(), Failure>> = OnceLock::new();
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
            "install: what the kernel build needs: Rust toolchain {PINNED_TOOLCHAIN} (profile minimal) with {} \
             and target {KERNEL_TARGET}",
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

/// The target the explorer's engine is built for.
pub const WASM_TARGET: &str = "wasm32-unknown-unknown";
/// The microcontroller target `raster` and `raster-eg` are built for with
/// no allocator (`cargo xtask lint`), so that they stay `no_std`.
pub const THUMB_TARGET: &str = "thumbv7em-none-eabihf";

/// Makes sure the toolchain that runs us (the one `cargo xtask` or `cargo
/// test` was started with, the one [`host`] builds with) has the
/// `wasm32-unknown-unknown` target, adding it with rustup when missing.
pub fn ensure_wasm_target() -> Result<()> {
    static DONE: OnceLock<Result<(), Failure>> = OnceLock::new();
    once_per_process(&DONE, || ensure_host_target(WASM_TARGET, "the explorer page"))
}

/// [`ensure_wasm_target`] for [`THUMB_TARGET`].
pub fn ensure_thumb_target() -> Result<()> {
    static DONE: OnceLock<Result<(), Failure>> = OnceLock::new();
    once_per_process(&DONE, || ensure_host_target(THUMB_TARGET, "raster's no_std build"))
}

/// Adds `target` to the toolchain that runs us when it is missing, saying
/// it is for `purpose`.
fn ensure_host_target(target: &str, purpose: &str) -> Result<()> {
    let toolchain = host_toolchain()?;
    let installed =
        output_of(Command::new("rustup").args(["target", "list", "--installed", "--toolchain"]).arg(&toolchain))
            .with_context(|| format!("rustup is needed to add the {target} target (see https://rustup.rs)"))?;
    if installed.lines().any(|line| line.trim() == target) {
        return Ok(());
    }
    eprintln!("install: adding target {target} to Rust toolchain {toolchain} for {purpose}");
    run_streaming(&mut target_command(&toolchain, target)).with_context(|| format!("failed to add the {target} target"))
}

/// The rustup toolchain that runs us: rustup's proxies name it in
/// `RUSTUP_TOOLCHAIN` to every process they start; failing that, the one
/// rustup picks here.
fn host_toolchain() -> Result<String> {
    if let Some(toolchain) = std::env::var_os("RUSTUP_TOOLCHAIN") {
        return Ok(toolchain.to_string_lossy().into_owned());
    }
    let active = output_of(Command::new("rustup").args(["show", "active-toolchain"]))
        .context("rustup is needed to add a target (see https://rustup.rs)")?;
    active.split_whitespace().next().map(str::to_string).context("rustup named no active toolchain")
}

fn target_command(toolchain: &str, target: &str) -> Command {
    let mut add = Command::new("rustup");
    add.args(["target", "add", "--toolchain", toolchain, target]);
    add
}

/// The cargo-fuzz release `cargo xtask fuzz` installs when none is there.
pub const CARGO_FUZZ_VERSION: &str = "0.13.2";

/// Makes sure a C++ compiler is there for libFuzzer, which the fuzz
/// targets' `libfuzzer-sys` compiles: installs Debian's `g++`
/// ([`ensure_debian_packages`]).
pub fn ensure_cxx() -> Result<()> {
    static DONE: OnceLock<Result<(), Failure>> = OnceLock::new();
    once_per_process(&DONE, || {
        ensure_debian_packages("a C++ compiler (for libFuzzer)", &["g++"], || find_in_path("c++").is_some())
    })
}

/// Makes sure `cargo fuzz` (cargo-fuzz, which builds the fuzz targets with
/// libFuzzer) is installed, installing it from crates.io with `cargo
/// install --locked` when missing, and a C++ compiler ([`ensure_cxx`]).
pub fn ensure_cargo_fuzz() -> Result<()> {
    static DONE: OnceLock<Result<(), Failure>> = OnceLock::new();
    once_per_process(&DONE, || {
        ensure_cxx()?;
        if find_in_path("cargo-fuzz").is_some() {
            return Ok(());
        }
        eprintln!(
            "install: cargo-fuzz {CARGO_FUZZ_VERSION} from crates.io (cargo install), which builds and runs the \
             fuzz targets"
        );
        run_streaming(&mut cargo_fuzz_install_command()).context("failed to install cargo-fuzz")
    })
}

fn cargo_fuzz_install_command() -> Command {
    let mut install = host();
    install.args(["install", "cargo-fuzz", "--locked", "--version", CARGO_FUZZ_VERSION]);
    install
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::process::command_line;
    use std::ffi::OsStr;

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
    fn the_toolchain_is_recognised_with_or_without_its_host_suffix() {
        assert!(has_toolchain(
            "stable-x86_64-unknown-linux-gnu (default)\nnightly-2026-10-01-x86_64-unknown-linux-gnu\n"
        ));
        assert!(has_toolchain("nightly-2026-10-01\n"));
        assert!(!has_toolchain("nightly-2026-10-011-x86_64-unknown-linux-gnu\nnightly-x86_64-unknown-linux-gnu\n"));
    }

    #[test]
    fn parent_toolchain_variables_are_removed() {
        let command = pinned("rustup");
        let removed: Vec<&OsStr> =
            command.get_envs().filter(|(_, value)| value.is_none()).map(|(key, _)| key).collect();
        for var in ["RUSTUP_TOOLCHAIN", "RUSTC", "CARGO", "RUSTFLAGS"] {
            assert!(removed.contains(&OsStr::new(var)), "{var} is not removed");
        }
    }

    #[test]
    fn a_target_is_added_to_the_named_toolchain() {
        assert_eq!(
            command_line(&target_command("stable-x86_64-unknown-linux-gnu", WASM_TARGET)),
            "rustup target add --toolchain stable-x86_64-unknown-linux-gnu wasm32-unknown-unknown"
        );
    }

    #[test]
    fn cargo_fuzz_is_installed_at_its_pinned_version_from_the_lock_file() {
        assert!(command_line(&cargo_fuzz_install_command()).ends_with(" install cargo-fuzz --locked --version 0.13.2"));
    }
}
