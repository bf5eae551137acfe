//! `cargo xtask test`: everything, the QEMU harness included.

use std::process::Command;

use anyhow::Result;
use boot_image::cargo::NIGHTLY_ONLY;
use boot_image::process::run_streaming;
use boot_image::toolchain::ensure_toolchain;
use boot_image::{build_image, IMAGE_ENV};
use harness::prerequisites::{
    ensure_bochs, ensure_cairo, ensure_chromium, ensure_ovmf, ensure_peer_libraries, ensure_qemu, ensure_wasm_target,
};

use crate::opt::TestOpt;

pub fn test(opt: &TestOpt) -> Result<()> {
    ensure_toolchain()?;
    ensure_qemu()?;
    // The adapter matrix boots OVMF too, and one test boots Bochs.
    ensure_ovmf()?;
    ensure_bochs()?;
    // The explorer page's tests: its engine is built for wasm32 and run in
    // headless Chromium.
    ensure_wasm_target()?;
    ensure_chromium()?;
    // The lab, a workspace member, builds its peers against libcairo,
    // Allegro 4, SDL2 with SDL2_gfx, and GD.
    ensure_cairo()?;
    ensure_peer_libraries()?;
    let image = build_image()?;
    run_streaming(test_command(&opt.cargo_args).env(IMAGE_ENV, image))
}

/// `cargo test` over every host crate of the workspace, run by the cargo
/// (the stable toolchain) that runs the xtask.
fn test_command(cargo_args: &[String]) -> Command {
    let mut command = boot_image::cargo::host();
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
    use boot_image::process::command_line;

    #[test]
    fn extra_arguments_go_to_cargo_test() {
        let command = test_command(&["--test".into(), "pages".into(), "--".into(), "--nocapture".into()]);
        assert!(
            command_line(&command)
                .ends_with(" test --workspace --exclude kernel --exclude boot --test pages -- --nocapture"),
            "{}",
            command_line(&command)
        );
        assert_eq!(command.get_current_dir(), Some(boot_image::workspace::root()));
    }
}
