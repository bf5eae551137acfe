//! Where the installs and the builds read and write in the workspace.

use std::path::{Path, PathBuf};

/// The workspace root: this crate lives in its `boot/install/` folder.
pub fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .and_then(Path::parent)
        .expect("the install crate is two folders inside the workspace")
}

/// The host target directory: `CARGO_TARGET_DIR` when set, as cargo does,
/// else `target/` in the workspace.
pub fn target_dir() -> PathBuf {
    match std::env::var_os("CARGO_TARGET_DIR") {
        Some(dir) => root().join(dir),
        None => root().join("target"),
    }
}

/// Where the pinned nightly builds the kernel and the image writer: a
/// directory of its own, so the stable host builds and the nightly builds
/// never invalidate each other's artifacts.
pub fn nightly_target_dir() -> PathBuf {
    target_dir().join("nightly")
}
