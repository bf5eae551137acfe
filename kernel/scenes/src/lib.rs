//! `scenes`: what the lab draws, as data. The seeds' sample programs as
//! built-in scenes ([`builtin`]), the plain-text scene files users write
//! ([`file`](mod@file)), the VGA default palette ([`palette`]), and the demo's show
//! ([`show`]: every frame of every entry, the book pages, animations with
//! shading, textures and depth through one attribute interpolator, and the
//! race of every method), drawn the same way in the kernel and on the host
//! and labelled with an 8x8 font (`font8x8`).
//!
//! Scan conversion is the `raster` crate's; this crate only says what to
//! fill, in which colour, with which method.
#![no_std]
#![forbid(unsafe_code)]

extern crate alloc;

// Every item has one path: the scene itself (`scene`) is private and
// re-exported here, at the top; the other modules are namespaces whose
// items are called by their module's name (`builtin::ALL`, `file::parse`,
// `packed::pack`, `palette::VGA_DEFAULT`, `show::Stage`).
pub mod builtin;
pub mod file;
pub mod packed;
pub mod palette;
mod scene;
pub mod show;

pub use scene::{DrawReport, Op, PaletteEntry, Scene, FILE_METHOD};
