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
//! Every method is named by a [`MethodId`]: names from the outside (the
//! command line, the serial line, scene files) are parsed into one once, and
//! an unknown name is an error that lists the known ones.
//!
//! The crate has no dependencies and no `unsafe`: the very code that fills
//! video memory on bare metal runs on the host and in the lab. What is drawn
//! (the book pages, scene files, the show) lives in the `scenes` crate.
#![no_std]
#![forbid(unsafe_code)]

extern crate alloc;

pub mod classify;
pub mod coverage;
pub mod geometry;
pub mod method;
pub mod methods;
pub mod reference;
pub mod sink;

pub use classify::classify;
pub use coverage::{CoverageReport, CoverageSink};
pub use geometry::{FillRule, PixelPoint, Point, Polygon, SUBPIXEL_BITS, SUBPIXEL_ONE};
pub use method::{Class, Convention, Heap, MethodInfo, Refusal};
pub use methods::exact::fill_auto;
pub use methods::{Method, MethodId, UnknownMethod};
pub use sink::{Framebuffer, Size, SpanSink, SCREEN};
