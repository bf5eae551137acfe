//! Typed `cargo +<pinned nightly>` invocations for the kernel and the image
//! writer (`boot`).

use std::path::PathBuf;
use std::process::Command;

use crate::workspace;

/// The nightly that builds the kernel and `bootloader`'s BIOS stages
/// (`docs/development.md#the-toolchain`: `x86_64` 0.15.5 needs >= 2026-07-10).
pub const PINNED_TOOLCHAIN: &str = "nightly-2026-10-01";
/// The kernel's target triple.
pub const KERNEL_TARGET: &str = "x86_64-unknown-none";
/// Workspace members that only build with the pinned nightly (`boot`'s
/// bootloader build script uses `-Zbuild-std`; the kernel is bare metal):
/// host-wide commands (`cargo test`, `cargo clippy`) exclude them, and the
/// image is how they are tested.
pub const NIGHTLY_ONLY: [&str; 2] = ["kernel", "boot"];

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

/// One release build of a workspace package with the pinned nightly.
#[derive(Clone, Copy, Debug)]
pub struct NightlyBuild<'a> {
    pub package: &'a str,
    /// Cross target; `None` builds for the host (the image writer).
    pub target: Option<&'a str>,
}

impl NightlyBuild<'_> {
    /// The kernel, for bare metal.
    pub const KERNEL: NightlyBuild<'static> = NightlyBuild { package: "kernel", target: Some(KERNEL_TARGET) };
    /// The image writer (`boot/`), a host program.
    pub const IMAGE_WRITER: NightlyBuild<'static> = NightlyBuild { package: "boot", target: None };

    pub fn command(&self) -> Command {
        let mut command = pinned("cargo");
        command.args(["build", "--package", self.package, "--release"]);
        if let Some(target) = self.target {
            command.args(["--target", target]);
            // The bootloader's stage 2 reads the whole ELF through BIOS disk
            // calls: the workspace's `debug = 1` makes the kernel 16 times
            // larger and doubles the boot time under TCG. Symbols stay.
            command.args(["--config", "profile.release.strip=\"debuginfo\""]);
            // The kernel's panic locations name its sources: cargo's
            // trim-paths (a nightly feature) writes the toolchain's, the
            // registry's and ours without the builder's home folder.
            command.args(["-Ztrim-paths", "--config", "profile.release.trim-paths=\"all\""]);
        }
        command.arg("--target-dir").arg(workspace::nightly_target_dir());
        command
    }

    /// The binary the build leaves (named after its package).
    pub fn artifact(&self) -> PathBuf {
        let mut path = workspace::nightly_target_dir();
        if let Some(target) = self.target {
            path.push(target);
        }
        path.join("release").join(self.package)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::process::command_line;
    use std::ffi::OsStr;

    #[test]
    fn kernel_build_uses_the_pinned_nightly_and_its_own_target_dir() {
        let command = NightlyBuild::KERNEL.command();
        let nightly = workspace::nightly_target_dir();
        assert_eq!(
            command_line(&command),
            format!(
                "cargo +nightly-2026-10-01 build --package kernel --release --target x86_64-unknown-none \
                 --config 'profile.release.strip=\"debuginfo\"' -Ztrim-paths \
                 --config 'profile.release.trim-paths=\"all\"' --target-dir {}",
                nightly.display()
            )
        );
        assert_eq!(command.get_current_dir(), Some(workspace::root()));
        assert_eq!(NightlyBuild::KERNEL.artifact(), nightly.join("x86_64-unknown-none/release/kernel"));
    }

    #[test]
    fn image_builder_builds_for_the_host() {
        let command = NightlyBuild::IMAGE_WRITER.command();
        assert!(!command.get_args().any(|a| a == "--target"));
        assert_eq!(NightlyBuild::IMAGE_WRITER.artifact(), workspace::nightly_target_dir().join("release/boot"));
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
}
