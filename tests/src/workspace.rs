//! Where things are in the workspace, and the harness's scratch folders.

use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};

use anyhow::{Context, Result};

pub use boot_image::workspace::{nightly_target_dir, root, target_dir};

/// A new, empty folder for one run of a child process (QEMU, a browser):
/// `polylab-<kind>-<pid>-<n>` in the system's temporary folder. The caller
/// removes it when the run ends.
pub fn fresh_run_dir(kind: &str) -> Result<PathBuf> {
    static RUNS: AtomicUsize = AtomicUsize::new(0);
    let dir = std::env::temp_dir().join(format!(
        "polylab-{kind}-{}-{}",
        std::process::id(),
        RUNS.fetch_add(1, Ordering::Relaxed)
    ));
    std::fs::create_dir_all(&dir).with_context(|| format!("failed to create {}", dir.display()))?;
    Ok(dir)
}
