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
//! This module holds what both variants share, so it exists once: the
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

pub use fixed::LamotheFixed;
pub use float::Lamothe;

use crate::geometry::{PixelPoint, Polygon};
use crate::method::Refusal;
use crate::sink::{Size, SpanSink};

/// His clipping globals `min_clip_x` .. `max_clip_y`, inclusive.
#[derive(Clone, Copy, Debug)]
struct ClipRect {
    min_x: i32,
    max_x: i32,
    min_y: i32,
    max_y: i32,
}

impl ClipRect {
    /// The whole sink, or `None` when it has no pixels.
    fn of(size: Size) -> Option<Self> {
        (size.width > 0 && size.height > 0).then(|| Self {
            min_x: 0,
            max_x: size.width - 1,
            min_y: 0,
            max_y: size.height - 1,
        })
    }

    fn contains_x(&self, x: i32) -> bool {
        (self.min_x..=self.max_x).contains(&x)
    }
}

/// The left (`xs`) and right (`xe`) edge positions of one flat half and
/// their steps per line (`dx_left`, `dx_right`), in a variant's arithmetic.
trait EdgePair {
    /// `xs += dx_left * lines; xe += dx_right * lines`: the y clip's jump
    /// over the lines above the clip rectangle.
    fn skip_lines(&mut self, lines: i32);
    /// The next line: `xs += dx_left; xe += dx_right`.
    fn step(&mut self);
    /// First pixel and pixel count of the no-x-clip path's `memset`.
    fn memset_span(&self) -> (i64, i64);
    /// `left` and `right` (both drawn) of the x-clip path.
    fn ends(&self) -> (i32, i32);
}

/// A variant's setup of `Draw_Top_Tri` and `Draw_Bottom_Tri`: the swap of
/// the two x values on the flat side, the slopes and starting points.
/// Arguments are in his parameter order; `None` is his degenerate test.
trait FlatHalves {
    type Edges: EdgePair;
    /// Flat top: `p1` and `p2` on the top line, `p3` below.
    fn top(&self, p1: PixelPoint, p2: PixelPoint, p3: PixelPoint) -> Option<Self::Edges>;
    /// Flat bottom: `p1` on top, `p2` and `p3` on the bottom line.
    fn bottom(&self, p1: PixelPoint, p2: PixelPoint, p3: PixelPoint) -> Option<Self::Edges>;
}

/// `Method::fill` for both variants: one contour, rounded to pixels, cut
/// into triangles (module doc), each drawn by `Draw_Triangle_2D`.
fn fill_polygon<S: SpanSink + ?Sized>(
    variant: &impl FlatHalves,
    polygon: &Polygon,
    sink: &mut S,
) -> Result<(), Refusal> {
    let contour = polygon.single_contour().ok_or(Refusal::MultipleContours)?;
    let Some(clip) = ClipRect::of(sink.size()) else {
        return Ok(());
    };
    // Rounded where used, so no vertex list is allocated.
    let v = |i: usize| contour[i].round_to_pixel();
    let mut draw = |triangle| draw_triangle_2d(variant, triangle, clip, polygon.color, sink);
    if contour.len() == 4 {
        draw([v(0), v(1), v(3)]);
        draw([v(1), v(2), v(3)]);
    } else {
        for i in 2..contour.len() {
            draw([v(0), v(i - 1), v(i)]);
        }
    }
    Ok(())
}

/// `Draw_Triangle_2D` / `Draw_TriangleFP_2D` (the two differ only in the
/// halves they call).
fn draw_triangle_2d<S: SpanSink + ?Sized>(
    variant: &impl FlatHalves,
    [p1, p2, p3]: [PixelPoint; 3],
    clip: ClipRect,
    color: u8,
    sink: &mut S,
) {
    // "test for h lines and v lines"
    if (p1.x == p2.x && p2.x == p3.x) || (p1.y == p2.y && p2.y == p3.y) {
        return;
    }
    // His three compare-and-swaps, strict `<`, so ties keep their order.
    let (mut p1, mut p2, mut p3) = (p1, p2, p3);
    if p2.y < p1.y {
        core::mem::swap(&mut p1, &mut p2);
    }
    if p3.y < p1.y {
        core::mem::swap(&mut p1, &mut p3);
    }
    if p3.y < p2.y {
        core::mem::swap(&mut p2, &mut p3);
    }
    let xs = [p1.x, p2.x, p3.x];
    let rejected = p3.y < clip.min_y
        || p1.y > clip.max_y
        || xs.iter().all(|&x| x < clip.min_x)
        || xs.iter().all(|&x| x > clip.max_x);
    if rejected {
        return;
    }
    let mut half = |edges: Option<_>, a: PixelPoint, b: PixelPoint, c: PixelPoint| {
        if let Some(edges) = edges {
            scan_half(edges, [a.x, b.x, c.x], a.y, c.y, clip, color, sink);
        }
    };
    if p1.y == p2.y {
        half(variant.top(p1, p2, p3), p1, p2, p3);
    } else if p2.y == p3.y {
        half(variant.bottom(p1, p2, p3), p1, p2, p3);
    } else {
        let split = PixelPoint { x: p1.x + long_edge_offset(p1, p2, p3), y: p2.y };
        half(variant.bottom(p1, split, p2), p1, split, p2);
        half(variant.top(p2, split, p3), p2, split, p3);
    }
}

/// `(int)(0.5+(float)(y2-y1)*(float)(x3-x1)/(float)(y3-y1))`: the long
/// edge's x offset at the middle vertex's row, products and quotient in
/// `float`, the `0.5` a `double` literal, then truncated toward zero (so
/// negative offsets round up, his bias). Only called with `y1 < y2 < y3`.
fn long_edge_offset(p1: PixelPoint, p2: PixelPoint, p3: PixelPoint) -> i32 {
    let quotient = (p2.y - p1.y) as f32 * (p3.x - p1.x) as f32 / (p3.y - p1.y) as f32;
    (0.5 + f64::from(quotient)) as i32
}

/// The body shared by `Draw_Top_Tri`, `Draw_Bottom_Tri` and their FP twins
/// after the setup: y clip, then lines `y1..=y3` by the no-x-clip path when
/// all three x lie inside the clip rectangle, else by the x-clip path.
fn scan_half<S: SpanSink + ?Sized>(
    mut edges: impl EdgePair,
    xs: [i32; 3],
    mut y1: i32,
    mut y3: i32,
    clip: ClipRect,
    color: u8,
    sink: &mut S,
) {
    if y1 < clip.min_y {
        edges.skip_lines(clip.min_y - y1);
        y1 = clip.min_y;
    }
    if y3 > clip.max_y {
        y3 = clip.max_y;
    }
    let needs_x_clip = !xs.iter().all(|&x| clip.contains_x(x));
    for y in y1..=y3 {
        if !needs_x_clip {
            let (start, count) = edges.memset_span();
            edges.step();
            memset(sink, y, start, count, color);
            continue;
        }
        let (mut left, mut right) = edges.ends();
        edges.step();
        if left < clip.min_x {
            left = clip.min_x;
            if right < clip.min_x {
                continue;
            }
        }
        if right > clip.max_x {
            right = clip.max_x;
            if left > clip.max_x {
                continue;
            }
        }
        memset(sink, y, i64::from(left), i64::from(right) - i64::from(left) + 1, color);
    }
}

/// `memset(dest_addr + start, color, count)` on line `y`, cut to the sink
/// (module doc: a negative count draws nothing).
fn memset<S: SpanSink + ?Sized>(sink: &mut S, y: i32, start: i64, count: i64, color: u8) {
    let width = i64::from(sink.size().width);
    let (x0, x1) = (start.max(0), start.saturating_add(count).min(width));
    if x0 < x1 {
        sink.span(y, x0 as i32, x1 as i32, color);
    }
}
