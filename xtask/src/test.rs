//! `cargo xtask test`: everything, the QEMU harness included.

use std::process::Command;

use anyhow::Result;
use harness::build_image;
use harness::image::IMAGE_ENV;
use harness::prerequisites::{ensure_cairo, ensure_qemu, ensure_toolchain};
use harness::process::run_streaming;

use crate::opt::TestOpt;

pub fn test(opt: &TestOpt) -> Result<()> {
    ensure_toolchain()?;
    ensure_qemu()?;
    // The lab, a workspace member, builds its Cairo peer against libcairo.
    ensure_cairo()?;
    let image = build_image()?;
    run_streaming(test_command(&opt.cargo_args).env(IMAGE_ENV, image))
}

/// Workspace members that only build with the pinned nightly (`boot`'s
/// bootloader build script uses `-Zbuild-std`; the kernel is bare metal):
/// the image built above is how they are tested.
const NIGHTLY_ONLY: [&str; 2] = ["kernel", "boot"];

/// `cargo test` over every host crate of the workspace, run by the cargo
/// (the stable toolchain) that runs the xtask.
fn test_command(cargo_args: &[String]) -> Command {
    let mut command = harness::cargo::host();
    command.args(["test", "--workspace"]);
    for package in NIGHTLY_ONLY {
        command.args(["--exclude", package]);
    }
    command.args(cargo_args);
    command
}

#[cfg(test)]
mod tests {
    use super::*;
    use harness::process::command_line;

    #[test]
    fn extra_arguments_go_to_cargo_test() {
        let command = test_command(&["--test".into(), "pages".into(), "--".into(), "--nocapture".into()]);
        assert!(
            command_line(&command)
                .ends_with(" test --workspace --exclude kernel --exclude boot --test pages -- --nocapture"),
            "{}",
            command_line(&command)
        );
        assert_eq!(command.get_current_dir(), Some(harness::workspace::root()));
    }
}
