//! `cargo xtask lint`: formatting and clippy, as CI runs them. Clippy runs
//! with the pinned nightly, over the host crates and the kernel (for bare
//! metal), so its lints are the same on every machine: the default stable
//! toolchain moves on, and each release's clippy brings lints of its own.
//! Formatting is checked with the host toolchain's rustfmt, whose output
//! does not change between releases. Warnings are errors. Installs rustfmt,
//! the pinned nightly and its clippy where missing (the minimal rustup
//! profile has neither tool), the C libraries the lab's peers build
//! against (libcairo, Allegro 4, SDL2 with SDL2_gfx, GD), and a C++ compiler for the fuzz targets' libFuzzer.
//! The fuzz targets (xtask/fuzz/targets, a workspace of their own) are
//! formatted and linted apart.

use std::process::Command;

use anyhow::{Context, Result};
use boot_image::cargo::{NightlyBuild, NIGHTLY_ONLY};
use install::ensure_all;
use install::ensure_cxx;
use install::ensure_lab_libraries;
use install::ensure_toolchain;
use install::run_streaming;
use install::workspace;
use install::{ensure_thumb_target, host, pinned, KERNEL_TARGET, THUMB_TARGET};

pub fn lint() -> Result<()> {
    // Under `cargo xtask`, rustup names the running toolchain in
    // RUSTUP_TOOLCHAIN, so this adds the components to that one.
    run_streaming(Command::new("rustup").args(["component", "add", "rustfmt"])).context("failed to install rustfmt")?;
    run_streaming(&mut fmt_check())?;
    run_streaming(&mut fuzz_targets_fmt_check())?;
    ensure_toolchain()?;
    run_streaming(pinned("rustup").args(["component", "add", "clippy"]))
        .context("failed to install clippy for the pinned nightly")?;
    // Clippy builds the lab, whose peers link the system libcairo, Allegro
    // 4, SDL2 with SDL2_gfx, and GD; the fuzz targets build libFuzzer,
    // which is C++.
    ensure_all(&[ensure_lab_libraries, ensure_cxx])?;
    for mut command in [host_clippy(), kernel_clippy(), fuzz_targets_clippy()] {
        run_streaming(&mut command)?;
    }
    ensure_thumb_target()?;
    run_streaming(&mut no_alloc_build())?;
    eprintln!(
        "xtask: formatted, clippy finds nothing in the host crates or the kernel, and raster builds for {THUMB_TARGET} \
         with no allocator"
    );
    Ok(())
}

/// `cargo fmt --check` over the whole workspace, kernel included (rustfmt
/// does not compile, so the host toolchain's will do).
fn fmt_check() -> Command {
    let mut command = host();
    command.args(["fmt", "--all", "--check"]);
    command
}

/// `cargo fmt --check` over the fuzz targets' own workspace.
fn fuzz_targets_fmt_check() -> Command {
    let mut command = host();
    command.args(["fmt", "--all", "--check", "--manifest-path"]).arg(fuzz_targets_manifest());
    command
}

/// Clippy on the fuzz targets with the pinned nightly, in the target
/// directory `cargo xtask fuzz` builds them in.
fn fuzz_targets_clippy() -> Command {
    let mut command = pinned("cargo");
    command.args(["clippy", "--all-targets", "--manifest-path"]).arg(fuzz_targets_manifest());
    command.arg("--target-dir").arg(workspace::target_dir().join("fuzz"));
    command.args(["--", "-D", "warnings"]);
    command
}

/// `raster` (without its `alloc` feature) and `raster-eg` for a
/// microcontroller with no allocator, on the host toolchain, in a target
/// directory of their own, warnings denied.
fn no_alloc_build() -> Command {
    let mut command = host();
    command.args(["build", "--package", "raster", "--package", "raster-eg", "--no-default-features"]);
    command.args(["--target", THUMB_TARGET]).arg("--target-dir").arg(workspace::target_dir().join("thumb"));
    command.env("RUSTFLAGS", "-D warnings");
    command
}

fn fuzz_targets_manifest() -> std::path::PathBuf {
    workspace::root().join(crate::fuzz::FUZZ_DIR).join("Cargo.toml")
}

/// Clippy on every host crate with the pinned nightly, in the nightly's
/// own target directory.
fn host_clippy() -> Command {
    let mut command = pinned("cargo");
    command.args(["clippy", "--workspace"]);
    for package in NIGHTLY_ONLY {
        command.args(["--exclude", package]);
    }
    command.arg("--all-targets").arg("--target-dir").arg(workspace::nightly_target_dir());
    command.args(["--", "-D", "warnings"]);
    command
}

/// Clippy on the kernel with the pinned nightly, for its bare-metal target,
/// in the nightly's own target directory (as its build).
fn kernel_clippy() -> Command {
    let mut command = pinned("cargo");
    command.args(["clippy", "--package", NightlyBuild::KERNEL.package, "--release", "--target", KERNEL_TARGET]);
    command.arg("--target-dir").arg(workspace::nightly_target_dir());
    command.args(["--", "-D", "warnings"]);
    command
}

#[cfg(test)]
mod tests {
    use super::*;
    use install::command_line;

    #[test]
    fn host_clippy_covers_every_host_crate_with_the_pinned_nightly_and_denies_warnings() {
        let line = command_line(&host_clippy());
        assert!(
            line.starts_with(
                "cargo +nightly-2026-10-01 clippy --workspace --exclude kernel --exclude boot --all-targets"
            ),
            "{line}"
        );
        assert!(line.ends_with(" -- -D warnings"), "{line}");
    }

    #[test]
    fn the_fuzz_targets_are_formatted_and_linted_in_their_own_workspace() {
        let fmt = command_line(&fuzz_targets_fmt_check());
        assert!(fmt.contains(" fmt --all --check --manifest-path "), "{fmt}");
        assert!(fmt.ends_with("xtask/fuzz/targets/Cargo.toml"), "{fmt}");
        let clippy = command_line(&fuzz_targets_clippy());
        assert!(clippy.starts_with("cargo +nightly-2026-10-01 clippy --all-targets --manifest-path "), "{clippy}");
        assert!(clippy.contains("xtask/fuzz/targets/Cargo.toml --target-dir "), "{clippy}");
        assert!(clippy.ends_with(" -- -D warnings"), "{clippy}");
    }

    #[test]
    fn raster_is_built_for_a_microcontroller_with_no_allocator() {
        let line = command_line(&no_alloc_build());
        assert!(line.contains(" build --package raster --package raster-eg --no-default-features"), "{line}");
        assert!(line.contains("--target thumbv7em-none-eabihf --target-dir "), "{line}");
    }

    #[test]
    fn the_kernel_is_linted_with_the_pinned_nightly_for_bare_metal() {
        let line = command_line(&kernel_clippy());
        assert!(line.starts_with("cargo +nightly-2026-10-01 clippy --package kernel --release"), "{line}");
        assert!(line.contains("--target x86_64-unknown-none"), "{line}");
        assert!(line.ends_with(" -- -D warnings"), "{line}");
    }
}
