//! `lamothe` and `lamothe_fixed`: André LaMothe's triangle filler from
//! "Solid Filled Polygons" (*Tricks of the Windows Game Programming Gurus*,
//! ch. 8; `docs/methods.md#lamothe`). `Draw_Triangle_2D` sorts the
//! vertices by y and splits the triangle along its long edge into a
//! flat-bottom half (`Draw_Bottom_Tri`) and a flat-top half
//! (`Draw_Top_Tri`); each half traces its two edges one scan line at a time
//! and `memset`s the span between them.
//!
//! The seed prints the float functions and only names their fixed-point
//! twins (`Draw_TriangleFP_2D`, `Draw_Top_TriFP`, `Draw_Bottom_TriFP`) and
//! the quad splitter `Draw_QuadFP_2D` ("also in the library file"). The
//! fixed-point code followed in `fixed.rs` is that of the book's demo and
//! library sources (DEMO8_8.CPP, T3DLIB1.CPP), whose float functions are the
//! seed's text word for word.
//!
//! What both variants share exists once, in `halves.rs`: the
//! polygon-to-triangle decomposition, `Draw_Triangle_2D` (degenerate test,
//! sort, trivial rejection, split point), and the scan loop of the two flat
//! halves (y clip, the no-x-clip and x-clip paths, the per-line x clip).
//! `float.rs` ([`Lamothe`]) and `fixed.rs` ([`LamotheFixed`]) supply only the
//! edge arithmetic.
//!
//! - Convention (both): integer rows, every row from a half's top vertex to
//!   its bottom vertex drawn, and both ends of every span. Triangles sharing
//!   an edge therefore overlap on it, and the two halves of a split triangle
//!   both draw the middle vertex's row ("the single scanline that is common
//!   to both will be rasterized twice"). Where the three vertices lie inside
//!   the clip rectangle a half takes his no-x-clip path, whose `memset`
//!   count is computed differently from the x-clip path's ends: the same
//!   triangle can lose or gain a pixel per line as it crosses the screen
//!   edge. Both paths are kept.
//! - Clip rectangle: the sink, `min_clip_x = 0`, `max_clip_x = width - 1`,
//!   likewise for y (his globals set to `SCREEN_WIDTH - 1` etc.).
//! - Classes: triangles. Four vertices are split as `Draw_QuadFP_2D` does,
//!   into (0, 1, 3) and (1, 2, 3). More vertices are triangulated as the
//!   seed's n-gon algorithm says ("take the first three vertices ... and
//!   recursively process ... the remaining (n-1) vertices"), a fan from
//!   vertex 0, with its final three vertices drawn as the last triangle.
//!   A fan is right for convex polygons, not for every polygon monotone in
//!   y, hence `handles: Class::Triangle`. (`Draw_Filled_Polygon2D`, his fill
//!   without triangulation, is not in the seed: "I would show you the
//!   listing of the function, but it's rather large".)
//! - Integers: the original takes `int`s; vertices are rounded with
//!   [`Point::round_to_pixel`](crate::Point::round_to_pixel) and so lie
//!   within ±2^23, where all of his `int` arithmetic on them (differences up
//!   to 2^24, the split point) is exact in `i32`. Only the 16.16 values of
//!   `lamothe_fixed` overflow, and wrap there as on the 32-bit x86 he wrote for.
//!
//! Safety changes: a `memset` count below zero, which the original's
//! `(unsigned int)` turns into a run over the whole buffer (reachable where
//! rounding crosses the two edges near an apex, or after a 16.16 wrap),
//! draws nothing; and spans are cut at the sink's width, where the no-x-clip
//! path can run one pixel past `max_clip_x` (onto the next line of his
//! linear buffer). Every loop is bounded by the clip rectangle: his y clip
//! jumps past the lines above it in one multiplication, so a half costs at
//! most `height` lines and a rejected triangle nothing.

mod fixed;
mod float;
mod halves;

pub use fixed::LamotheFixed;
pub use float::Lamothe;
