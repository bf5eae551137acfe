//! The image build is done once per change of its inputs: built twice in
//! a row, the second build of the kernel and of the image writer (which
//! carries the patched boot stages) compiles nothing. Before the stages'
//! build folder moved out of the folders bootloader's build script watches
//! (and the folders it watches existed), every image build compiled
//! bootloader and boot again, rebuilding the stages (about 30 s on a
//! quiet machine, docs/boot.md).

use anyhow::{ensure, Context, Result};
use boot_image::process::command_line;
use boot_image::stage_builds;

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
    build_once()?;
    for stderr in build_once()? {
        let compiled: Vec<&str> = stderr.lines().filter(|line| line.trim_start().starts_with("Compiling ")).collect();
        ensure!(compiled.is_empty(), "the second build compiled again:\n{}", compiled.join("\n"));
        ensure!(stderr.contains("Finished"), "cargo did not say the build finished: {stderr}");
    }
    Ok(())
}
