//! `cargo xtask lab`: runs the lab crate's binary in release, since the
//! xtask itself is built unoptimised and the lab measures speed, after
//! installing the C libraries its peers build against (libcairo, Allegro
//! 4, SDL2 with SDL2_gfx, GD).
//!
//! The lab is built for the machine it runs on (`-C target-cpu=native`),
//! our code and the Rust peers alike, so that every contender may use the
//! widest stores the CPU has (the framebuffer's span store takes 64-byte
//! blocks where there is AVX2; the host's baseline, SSE2, has 16-byte
//! ones); in a target directory of its own (`target/native`), so that the
//! other builds keep theirs. Cairo is the system's library, built by
//! Debian for the baseline, which picks its SIMD at run time.
//!
//! On x86-64 it is also built with no jump straddling or ending on a
//! 32-byte boundary (LLVM's `-x86-branches-within-32B-boundaries`, the
//! padding Intel advises against the jump-conditional-code erratum of its
//! Skylake-derived cores, whose microcode fix makes such a jump miss the
//! decoded-instruction cache). Without it, where the loops of a fill
//! happen to fall moves their time by 10-20% from one build to the next
//! on those cores with no change to their code, our code's and the Rust
//! peers' alike; with it every build lays its jumps out the same way.
//! Other x86-64 cores get the same padding; the lab has been timed with
//! and without it on Cascade Lake only.

use std::path::absolute;

use anyhow::{Context, Result};
use install::libraries::ensure_lab_libraries;
use install::process::run_streaming;

use crate::opt::LabOpt;

/// What the lab is built with: code for this machine's CPU, its jumps
/// kept within 32-byte blocks on x86-64.
const NATIVE_RUSTFLAGS: &str = if cfg!(target_arch = "x86_64") {
    "-C target-cpu=native -C llvm-args=-x86-branches-within-32B-boundaries"
} else {
    "-C target-cpu=native"
};
/// Where, apart from the other builds (whose flags differ).
const NATIVE_TARGET_DIR: &str = "target/native";

pub fn lab(opt: &LabOpt) -> Result<()> {
    // The Cairo peer builds against the system libcairo; the Allegro,
    // SDL2_gfx and GD peers against theirs.
    ensure_lab_libraries()?;
    let out = absolute(&opt.out).with_context(|| format!("bad output directory {}", opt.out.display()))?;
    let mut command = install::toolchain::host();
    command.env("RUSTFLAGS", NATIVE_RUSTFLAGS);
    command.args(["run", "--quiet", "--release", "--package", "lab", "--target-dir", NATIVE_TARGET_DIR, "--"]);
    if opt.quick {
        command.arg("--quick");
    }
    command.arg("--runs").arg(opt.runs.to_string());
    command.arg("--out").arg(out);
    run_streaming(&mut command)
}
