//! `cargo xtask lab`: runs the lab crate's binary in release, since the
//! xtask itself is built unoptimised and the lab measures speed, after
//! installing the libcairo headers its Cairo peer builds against.

use std::path::absolute;

use anyhow::{Context, Result};
use harness::prerequisites::ensure_cairo;
use harness::process::run_streaming;

use crate::opt::LabOpt;

pub fn lab(opt: &LabOpt) -> Result<()> {
    // The Cairo peer builds against the system libcairo.
    ensure_cairo()?;
    let out = absolute(&opt.out).with_context(|| format!("bad output directory {}", opt.out.display()))?;
    let mut command = harness::cargo::host();
    command.args(["run", "--quiet", "--release", "--package", "lab", "--"]);
    if opt.quick {
        command.arg("--quick");
    }
    command.arg("--out").arg(out);
    run_streaming(&mut command)
}
