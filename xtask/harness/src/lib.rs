//! The headless QEMU harness, shared by the integration tests in `tests/`
//! and by the xtask: build the image, boot it, speak the serial protocol,
//! take QEMU's screendumps, and compare pictures.
//!
//! ```no_run
//! use harness::{compare_images, render, sources, Qemu, QemuOptions};
//! # fn main() -> anyhow::Result<()> {
//! let mut qemu = Qemu::boot(QemuOptions::default())?;
//! qemu.console.draw("abrash38-1", None)?;
//! let dump = qemu.console.dump()?;
//! let scene = sources::builtin_scene("abrash38-1")?;
//! let expected = render::render(&scene, scene.method);
//! compare_images("abrash38-1", &expected, &dump.image())?;
//! # Ok(())
//! # }
//! ```

pub mod bochs;
pub mod browser;
pub mod cable;
pub mod checks;
pub mod client;
pub mod large_scenes;
pub mod picture;
pub mod qemu;
pub mod secure_boot;
pub mod serial_check;
pub mod soak;
pub mod sources;
pub mod supervisor;
pub mod workspace;

pub use client::{Console, Dump, Reply};
pub use picture::compare::compare_images;
pub use picture::{render, Image};
pub use qemu::{
    Adapter, Board, Cpu, Display, DisplayAhead, ExitDevice, Medium, Qemu, QemuOptions, SerialLine, TimeBase,
};
