//! Where things are in the workspace.

pub use boot_image::workspace::{nightly_target_dir, root, target_dir};
