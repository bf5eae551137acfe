//! The headless QEMU harness, shared by the integration tests in `tests/`
//! and by the xtask: build the image, boot it, speak the serial protocol,
//! take QEMU's screendumps, and compare pictures.
//!
//! ```no_run
//! use harness::{compare_images, render, Qemu, QemuOptions};
//! # fn main() -> anyhow::Result<()> {
//! let mut qemu = Qemu::boot(QemuOptions::default())?;
//! qemu.console.draw("abrash38-1", None)?;
//! let dump = qemu.console.dump()?;
//! let scene = render::builtin_scene("abrash38-1")?;
//! let expected = render::render(&scene, scene.method.method());
//! compare_images("abrash38-1", &expected, &dump.image())?;
//! # Ok(())
//! # }
//! ```

pub mod bootloader;
pub mod browser;
pub mod cargo;
pub mod checks;
pub mod image;
mod once;
pub mod picture;
pub mod prerequisites;
pub mod process;
pub mod qemu;
pub mod workspace;

pub use image::build_image;
pub use picture::compare::compare_images;
pub use picture::{render, Image};
pub use qemu::console::{BenchRow, Console, Dump, Listing, Reply};
pub use qemu::{Adapter, Clock, Display, Medium, Qemu, QemuOptions};
