//! Typed `cargo +<pinned nightly>` invocations for the kernel and the image
//! writer (`boot`); the toolchain itself is `install::toolchain`'s.

use std::path::PathBuf;
use std::process::Command;

use install::workspace;
use install::{pinned, KERNEL_TARGET};

/// Workspace members that only build with the pinned nightly (`boot`'s
/// bootloader build script uses `-Zbuild-std`; the kernel is bare metal):
/// host-wide commands (`cargo test`, `cargo clippy`) exclude them, and the
/// image is how they are tested.
pub const NIGHTLY_ONLY: [&str; 2] = ["kernel", "boot"];

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
    use install::command_line;

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
}
