//! The image build is done once per change of its inputs: built twice in
//! a row, the second build of the kernel and of the image writer (which
//! carries the patched boot stages) compiles nothing. Before the stages'
//! build folder moved out of the folders bootloader's build script watches
//! (and the folders it watches existed), every image build compiled
//! bootloader and boot again, rebuilding the stages (about 30 s on a
//! quiet machine, docs/boot.md). And what the build compiles the loader
//! from is checked against its sources every time.

use std::path::Path;

use anyhow::{ensure, Context, Result};
use boot_image::patched_copy::{fingerprint, PatchedBootloader, COPY_BUILD_FOLDER};
use boot_image::{image_build_turn, stage_builds, stage_builds_with};
use install::command_line;

/// Runs every stage build, failing on a failed one; returns what cargo
/// printed on its standard error, build by build.
fn build_once() -> Result<Vec<String>> {
    let mut printed = Vec::new();
    for mut build in stage_builds()? {
        let line = command_line(&build);
        let output = build.output().with_context(|| format!("failed to start `{line}`"))?;
        let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
        ensure!(output.status.success(), "`{line}` failed: {stderr}");
        printed.push(stderr);
    }
    Ok(printed)
}

#[test]
fn a_second_image_build_compiles_nothing() -> Result<()> {
    let _turn = image_build_turn()?;
    build_once()?;
    for stderr in build_once()? {
        let compiled: Vec<&str> = stderr.lines().filter(|line| line.trim_start().starts_with("Compiling ")).collect();
        ensure!(compiled.is_empty(), "the second build compiled again:\n{}", compiled.join("\n"));
        ensure!(stderr.contains("Finished"), "cargo did not say the build finished: {stderr}");
    }
    Ok(())
}

/// Copies the folder `from` to `to`, without its top-level `skip`.
fn copy_tree(from: &Path, to: &Path, skip: &str) -> Result<()> {
    std::fs::create_dir_all(to).with_context(|| format!("failed to create {}", to.display()))?;
    for entry in std::fs::read_dir(from).with_context(|| format!("failed to list {}", from.display()))? {
        let entry = entry?;
        if entry.file_name() == skip {
            continue;
        }
        let target = to.join(entry.file_name());
        if entry.file_type()?.is_dir() {
            copy_tree(&entry.path(), &target, "")?;
        } else {
            std::fs::copy(entry.path(), &target).with_context(|| format!("failed to copy {}", target.display()))?;
        }
    }
    Ok(())
}

/// The image build itself (the function `cargo xtask image` calls to
/// build the kernel and the writer) over a patched bootloader edited by
/// hand after the build made it: with the loader's call of
/// `check_kernel` deleted (the edit that once let a signed loader boot
/// any kernel), or a build script added, the build refuses, naming the
/// file, before anything is compiled; the copy as the build made it
/// passes. The copy lives in a target folder of the test's own, its stamp
/// saying it is current, as the build's own is after a build.
#[test]
fn the_image_build_refuses_a_hand_edited_patched_bootloader_naming_the_file() -> Result<()> {
    let _turn = image_build_turn()?;
    stage_builds()?;
    let made = PatchedBootloader::in_target_dir();
    let target = tempfile::tempdir()?;
    let copy = PatchedBootloader::under(target.path());
    copy_tree(&made.dir, &copy.dir, COPY_BUILD_FOLDER)?;
    std::fs::write(copy.stamp(), fingerprint())?;
    let main = copy.dir.join("uefi/src/main.rs");
    let text = std::fs::read_to_string(&main)?;
    let call = "    polylab_verify::check_kernel(kernel_slice);\n";
    ensure!(text.contains(call), "the loader never calls check_kernel: {}", main.display());
    std::fs::write(&main, text.replace(call, ""))?;
    let refused = |why: &str| -> Result<String> {
        let error = stage_builds_with(&copy).err().with_context(|| format!("a copy {why} was built"))?;
        Ok(format!("{error:#}"))
    };
    let error = refused("without check_kernel")?;
    ensure!(error.contains("(changed uefi/src/main.rs)"), "{error}");
    std::fs::write(&main, text)?;
    std::fs::write(copy.dir.join("uefi/build.rs"), "fn main() {}\n")?;
    let error = refused("with a build script added")?;
    ensure!(error.contains("(added uefi/build.rs)"), "{error}");
    eprintln!("harness: {error}");
    std::fs::remove_file(copy.dir.join("uefi/build.rs"))?;
    stage_builds_with(&copy).context("the copy as the build made it was refused")?;
    Ok(())
}

/// The words of the builder's home folder as paths in the image would
/// hold them: `$HOME/`, and cargo's and rustup's folders wherever they
/// are (`~/.cargo/registry/src/...` in a panic location, say).
fn builders_folders() -> Vec<String> {
    ["HOME", "CARGO_HOME", "RUSTUP_HOME"]
        .iter()
        .filter_map(|var| std::env::var(var).ok())
        .map(|folder| format!("{}/", folder.trim_end_matches('/')))
        .filter(|folder| folder.len() > 1)
        .collect()
}

#[test]
fn the_image_holds_no_path_of_the_builders_home_folder() -> Result<()> {
    let image = boot_image::build_image()?;
    let bytes = std::fs::read(&image).with_context(|| format!("failed to read {}", image.display()))?;
    let folders = builders_folders();
    ensure!(!folders.is_empty(), "neither HOME nor CARGO_HOME nor RUSTUP_HOME is set: nothing to look for");
    for folder in folders {
        let found = bytes.windows(folder.len()).filter(|window| *window == folder.as_bytes()).count();
        ensure!(
            found == 0,
            "{} holds {found} paths under {folder} (the boot stages, the loader and the kernel are built with \
             cargo's trim-paths; `strings {} | grep {folder}` shows them)",
            image.display(),
            image.display()
        );
    }
    Ok(())
}
