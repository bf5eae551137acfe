//! Where things are in the workspace.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

use anyhow::{Context, Result};

/// The workspace root: the harness crate lives in its `tests/` folder.
pub fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR")).parent().expect("the harness crate is inside the workspace")
}

/// The host target directory: `CARGO_TARGET_DIR` when set, as cargo does,
/// else `target/` in the workspace.
pub fn target_dir() -> PathBuf {
    match std::env::var_os("CARGO_TARGET_DIR") {
        Some(dir) => root().join(dir),
        None => root().join("target"),
    }
}

/// Where the pinned nightly builds the kernel and the image builder: a
/// directory of its own, so the stable host builds and the nightly builds
/// never invalidate each other's artifacts.
pub fn nightly_target_dir() -> PathBuf {
    target_dir().join("nightly")
}

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
