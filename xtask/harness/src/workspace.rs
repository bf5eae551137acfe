//! Where things are in the workspace.

pub use install::workspace::{nightly_target_dir, root, target_dir};
