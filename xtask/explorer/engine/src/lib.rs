//! `explorer`: the engine of the explorer page (`cargo xtask explore`), where
//! one polygon is looked at under every method. It is the `raster` and
//! `scenes` code itself, built for `wasm32-unknown-unknown` and driven by the
//! page's hand-written script through a few `extern "C"` functions
//! ([`exports`]); everything else here is plain Rust, unit-tested on the
//! host.
//!
//! - [`model`]: the scene being explored (a built-in page or a scene file),
//!   the selected polygon, vertex edits, and the limits that keep the page
//!   responsive on hostile input.
//! - [`judge`]: what a method is judged against (`exact`, or the reference
//!   at the method's own sample point) and the counts of how it differs.
//! - [`view`]: a method's picture of the scene, and the difference view of
//!   the selected polygon against its judge, with counts.
//! - [`family`]: which family of the lab's corpus a polygon is nearest to,
//!   for reading its speed and error figures out of `results.json`.

#![deny(unsafe_code)]

pub mod exports;
pub mod family;
pub mod judge;
pub mod model;
pub mod view;
