//! `cargo xtask test`: everything, the QEMU harness included.

use std::process::Command;

use anyhow::Result;
use harness::build_image;
use harness::cargo::NIGHTLY_ONLY;
use harness::image::IMAGE_ENV;
use harness::prerequisites::{ensure_cairo, ensure_chromium, ensure_qemu, ensure_toolchain, ensure_wasm_target};
use harness::process::run_streaming;

use crate::opt::TestOpt;

pub fn test(opt: &TestOpt) -> Result<()> {
    ensure_toolchain()?;
    ensure_qemu()?;
    // The explorer page's tests: its engine is built for wasm32 and run in
    // headless Chromium.
    ensure_wasm_target()?;
    ensure_chromium()?;
    // The lab, a workspace member, builds its Cairo peer against libcairo.
    ensure_cairo()?;
    let image = build_image()?;
    run_streaming(test_command(&opt.cargo_args).env(IMAGE_ENV, image))
}

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
