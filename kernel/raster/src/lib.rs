//! `raster`: polygon scan conversion for a 320x200 mode-13h screen and for
//! the host, with the same code on both sides.
//!
//! Scan conversion never touches memory: every method emits horizontal spans
//! into a [`SpanSink`] (Abrash's split between `FillConvexPolygon` and
//! `DrawHorizontalLineList`). The kernel's sink writes video memory, the
//! host's sink ([`Framebuffer`]) writes a byte vector, and the two are compared
//! byte for byte by the test harness.
//!
//! Coordinates are fixed point with [`SUBPIXEL_BITS`] fractional bits (see
//! [`Point`]); the classic ports round them to whole pixels first, as their
//! originals only took integers.
//!
//! [`show`] is the kernel's demo as data: every frame of every entry (the
//! seeds' pages, animations with shading, textures and depth through one
//! attribute interpolator, the method race), drawn the same way on both
//! sides and labelled with an 8x8 font (`font8x8`, the crate's one
//! dependency).
#![no_std]
#![forbid(unsafe_code)]

extern crate alloc;

pub mod classify;
pub mod coverage;
pub mod geometry;
pub mod method;
pub mod methods;
pub mod palette;
pub mod reference;
pub mod scene;
pub mod scene_file;
pub mod scenes;
pub mod show;
pub mod sink;

pub use classify::{classify, fill_auto};
pub use coverage::{CoverageReport, CoverageSink};
pub use geometry::{FillRule, PixelPoint, Point, Polygon, SUBPIXEL_BITS, SUBPIXEL_ONE};
pub use method::{Class, Convention, Heap, Method, MethodInfo, Refusal};
pub use scene::{Op, Scene};
pub use sink::{Framebuffer, Size, SpanSink, SCREEN};
