//! The pinned nightly the kernel and the boot stages build with, installed
//! when missing. Machines here set `RUSTUP_AUTO_INSTALL=0`, so nothing
//! installs itself.

use std::process::Command;
use std::sync::OnceLock;

use anyhow::{Context, Result};

use crate::cargo::{pinned, KERNEL_TARGET, PINNED_TOOLCHAIN};
use crate::once::once_per_process;
use crate::process::{output_of, run_streaming};

/// Components of the pinned nightly: `bootloader`'s build script compiles
/// its BIOS stages with `-Zbuild-std` (rust-src) and links them with LLVM's
/// tools (llvm-tools-preview). Each with the prefix rustup lists it under
/// once installed.
const COMPONENTS: [(&str, &str); 2] = [("rust-src", "rust-src"), ("llvm-tools-preview", "llvm-tools")];

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
            "image: installing what the kernel build needs: Rust toolchain {PINNED_TOOLCHAIN} \
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
    fn the_toolchain_is_recognised_with_or_without_its_host_suffix() {
        assert!(has_toolchain(
            "stable-x86_64-unknown-linux-gnu (default)\nnightly-2026-10-01-x86_64-unknown-linux-gnu\n"
        ));
        assert!(has_toolchain("nightly-2026-10-01\n"));
        assert!(!has_toolchain("nightly-2026-10-011-x86_64-unknown-linux-gnu\nnightly-x86_64-unknown-linux-gnu\n"));
    }
}
