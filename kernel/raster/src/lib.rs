//! `raster`: exact polygon scan conversion, `no_std`, with no dependencies
//! and no `unsafe`, for a bare-metal kernel or any tool with a byte-per-pixel
//! target: the code that fills polylab's mode-13h screen at 0xA0000, run the
//! same on the host. Beside our `exact` method it holds the classic methods
//! of the books (Abrash, Pendleton, LaMothe, the WGT tutorial), each a
//! faithful port, and a brute-force reference to judge them by.
//!
//! # Filling a polygon
//!
//! A polygon is one or more closed contours of [`Point`]s in 1/256 pixel,
//! one colour and a [`FillRule`]. [`fill_auto`] fills it exactly into any
//! [`SpanSink`]; a [`Framebuffer`] is a byte vector, one byte a pixel:
//!
//! ```
//! use raster::{fill_auto, Framebuffer, Polygon, Size};
//!
//! let mut screen = Framebuffer::new(Size { width: 8, height: 4 });
//! let triangle = Polygon::from_pixels(&[(0, 0), (8, 0), (0, 4)], (0, 0), 7);
//! fill_auto(&triangle, &mut screen).expect("exact declines nothing but a failed allocation");
//! assert_eq!(
//!     screen.pixels(),
//!     &[7, 7, 7, 7, 7, 7, 7, 0, //
//!       7, 7, 7, 7, 7, 0, 0, 0, //
//!       7, 7, 7, 0, 0, 0, 0, 0, //
//!       7, 0, 0, 0, 0, 0, 0, 0]
//! );
//! ```
//!
//! # What `exact` guarantees
//!
//! - **Exact**: a pixel is in when its centre (x + 0.5, y + 0.5) is inside
//!   the polygon by its fill rule, decided in integers: the very
//!   pixels of [`reference::fill`], which tests every centre against every
//!   edge (`docs/conventions.md` says it in full).
//! - **Top-left rule**: a centre exactly on an edge belongs to the polygon
//!   only on a left or top edge, so polygons that share an edge draw every
//!   pixel once and only once, and nothing is drawn twice within a fill.
//! - **Both fill rules**, even-odd and non-zero, over any number of
//!   contours: holes, self-intersections, touching edges.
//! - **Any `i32` vertex**, on any target size: nothing is declined for its
//!   range, and the rows outside the target are never visited.
//! - **Never out of bounds**: every span it emits is inside the sink's
//!   [`Size`], non-empty, and never a pixel twice.
//! - **No allocation** for polygons of up to 256 edges (64 when they may
//!   be 512 px or longer); beyond that its tables come from a
//!   [`Scratch`], which a caller may keep from fill to fill
//!   ([`fill_auto_with`]).
//!
//! The classic methods keep their originals' conventions and arithmetic
//! (each states them in its [`MethodInfo`]); none of them panics, loops
//! without bound or writes outside its target on any input, but each may
//! decline a polygon ([`Refusal`]) or draw it as its original would.
//!
//! # Spans and sinks
//!
//! Scan conversion never touches memory: every method emits horizontal
//! spans into a [`SpanSink`] (Abrash's split between `FillConvexPolygon`
//! and `DrawHorizontalLineList`). polylab's kernel writes them to video
//! memory, the host's [`Framebuffer`] to a vector, the tests count them
//! ([`CoverageSink`]). Every method is generic over its sink, so a span
//! into a sink of a known type costs no call.
//!
//! # Choosing a method
//!
//! Every method is named by a [`MethodId`]: a name from the outside (a
//! command line, a serial line, a file) is parsed into one once, and an
//! unknown name is an error that lists the known ones; [`Method`] is the
//! interface over all of them, and [`classify()`] tells a polygon's class,
//! the most general one a method must handle to fill it.
//!
//! `examples/png.rs` fills a few polygons and writes them as a PNG
//! (`cargo run -p raster --example png -- OUT.png`).
//!
//! # Without an allocator
//!
//! The `alloc` feature, on by default, brings [`Polygon`], the classic
//! methods, the reference, [`Framebuffer`] and the heap [`Scratch`].
//! Without it `exact` alone is here: it fills a [`PolygonRef`], whose
//! contours are any slices of points, with its tables on the stack, or
//! for a polygon of more edges in a [`FixedScratch`] the caller lends; a
//! polygon of more edges than that holds is refused
//! ([`Refusal::TooManyVertices`]), never drawn in part:
//!
//! ```
//! use raster::{fill_auto_with, FillRule, FixedScratch, Point, PolygonRef, Size, SpanSink};
//!
//! struct Rows([i32; 16]);
//! impl SpanSink for Rows {
//!     fn size(&self) -> Size {
//!         Size { width: 16, height: 16 }
//!     }
//!     fn span(&mut self, y: i32, x_start: i32, x_end: i32, _color: u8) {
//!         self.0[y as usize] += x_end - x_start;
//!     }
//! }
//!
//! let square = [(2, 2), (14, 2), (14, 14), (2, 14)].map(|(x, y)| Point::from_pixels(x, y));
//! let hole = [(6, 6), (6, 10), (10, 10), (10, 6)].map(|(x, y)| Point::from_pixels(x, y));
//! let framed = PolygonRef { contours: &[square, hole], color: 1, rule: FillRule::NonZero };
//! let (mut rows, mut scratch) = (Rows([0; 16]), FixedScratch::<512>::new());
//! fill_auto_with(framed, &mut rows, &mut scratch).unwrap();
//! assert_eq!(rows.0[..8], [0, 0, 12, 12, 12, 12, 8, 8]);
//! ```
#![no_std]
#![forbid(unsafe_code)]

#[cfg(feature = "alloc")]
extern crate alloc;

// Every item has one path: the modules are private, and what a caller
// uses is re-exported here, at the top, except three namespaces whose
// items are called by their module's name: `methods` (each method's
// type, `methods::Exact`), `reference` (`reference::fill`, the judge) and `stores`
// (`stores::clear`, `stores::set_bytes`: what a sink may store spans
// with; the sink interface, `SpanSink`, is the target's, in target.rs).
mod classify;
#[cfg(feature = "alloc")]
mod coverage;
#[cfg(feature = "alloc")]
mod framebuffer;
mod geometry;
pub mod methods;
#[cfg(feature = "alloc")]
pub mod reference;
pub mod stores;
mod target;
#[cfg(test)]
mod test_rng;

#[cfg(feature = "alloc")]
pub use classify::{classify, Class};
#[cfg(feature = "alloc")]
pub use coverage::{CoverageReport, CoverageSink};
#[cfg(feature = "alloc")]
pub use framebuffer::Framebuffer;
#[cfg(feature = "alloc")]
pub use geometry::Polygon;
pub use geometry::{FillRule, PixelPoint, Point, PolygonRef, SUBPIXEL_BITS, SUBPIXEL_ONE};
#[cfg(feature = "alloc")]
pub use methods::exact::Scratch;
pub use methods::exact::{fill_auto, fill_auto_with, ExactPath, FixedScratch, ScratchMut};
pub use methods::info::Refusal;
#[cfg(feature = "alloc")]
pub use methods::info::{Heap, MethodInfo};
#[cfg(feature = "alloc")]
pub use methods::interface::Method;
#[cfg(feature = "alloc")]
pub use methods::method_id::{MethodId, UnknownMethod};
pub use target::{Size, SpanSink, SCREEN};
