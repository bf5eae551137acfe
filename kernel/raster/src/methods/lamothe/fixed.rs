//! `lamothe_fixed`: the fixed-point twin of `lamothe`, named in LaMothe's
//! article (`docs/methods.md#lamothe`: "I've also created fixed-point versions of
//! the functions that run a bit faster") and followed from the book's
//! library (`Draw_TriangleFP_2D`, `Draw_Top_TriFP`, `Draw_Bottom_TriFP`);
//! decomposition and clipping in the parent module.
//!
//! - Convention: integer rows, both span ends drawn; x rounded to nearest,
//!   halves up (`(xs+FIXP16_ROUND_UP)>>FIXP16_SHIFT`). Unlike the float
//!   version both edges start on whole pixels (no `+0.5`). The no-x-clip
//!   path draws `((xe-xs+FIXP16_ROUND_UP)>>16)+1` pixels, a rounded
//!   *difference*, so it can draw one pixel more than the x-clip path.
//! - Arithmetic: 16.16 in a 32-bit `int` (`FIXP16_SHIFT` 16,
//!   `FIXP16_ROUND_UP` 0x8000), slopes `((x3-x1)<<16)/height` truncated
//!   toward zero, arithmetic `>>`. The split point of a general triangle is
//!   still computed in `float`, as in `Draw_TriangleFP_2D`.
//! - Overflow: `x<<16` needs |x| < 32768 and the y clip's `dx *
//!   (min_clip_y - y1)` a small product; beyond that his `int`s overflow.
//!   They wrap here as they did on the 32-bit x86 he wrote for (Rust's `<<`
//!   drops the high bits like `shl`; adds and multiplies are `wrapping_*`),
//!   so far-away or wide triangles draw the original's garbage, inside the
//!   target. Divisions are by a height of at least one line (his degenerate
//!   tests plus the y sort), so they cannot fail.
//! - Classes: triangles; quads and convex polygons through the parent
//!   module's split and fan.

use crate::classify::Class;
use crate::geometry::{FillRule, PixelPoint, Polygon};
use crate::methods::info::{Heap, MethodInfo, Refusal};
use crate::methods::interface::Builtin;
use crate::reference::Convention;
use crate::target::SpanSink;

use super::halves::{fill_polygon, EdgePair, FlatHalves};

/// LaMothe's fixed-point `Draw_TriangleFP_2D`, with his quad split and fan.
pub struct LamotheFixed;

/// `FIXP16_SHIFT`: 16 fractional bits.
const FIXP16_SHIFT: u32 = 16;
/// `FIXP16_ROUND_UP`: one half, added before shifting down.
const FIXP16_ROUND_UP: i32 = 0x8000;

static INFO: MethodInfo = MethodInfo {
    name: "lamothe_fixed",
    source: "LaMothe, \"Solid Filled Polygons\": Draw_TriangleFP_2D",
    convention: Convention {
        sample_x: 0,
        sample_y: 0,
        summary: "integer rows; flat halves draw their top and bottom rows and both span ends (overlaps); x rounded",
    },
    numeric:
        "integer vertices; 16.16 fixed point in i32 (wrapping), +0x8000 >> 16 rounding; split point (int)(0.5 + f32)",
    handles: Class::Triangle,
    rules: &[FillRule::EvenOdd, FillRule::NonZero],
    heap: Heap::Never,
};

impl Builtin for LamotheFixed {
    const INFO: &'static MethodInfo = &INFO;

    fn fill_into<S: SpanSink + ?Sized>(&self, polygon: &Polygon, sink: &mut S) -> Result<(), Refusal> {
        fill_polygon(self, polygon, sink)
    }
}

/// `xs`, `xe`, `dx_left`, `dx_right` of `Draw_Top_TriFP` /
/// `Draw_Bottom_TriFP`, 16.16.
pub(super) struct FixedEdges {
    xs: i32,
    xe: i32,
    dx_left: i32,
    dx_right: i32,
}

/// `((to - from)<<FIXP16_SHIFT)/height`, wrapping (module doc).
fn slope(from: i32, to: i32, height: i32) -> i32 {
    ((to - from) << FIXP16_SHIFT).wrapping_div(height)
}

impl FlatHalves for LamotheFixed {
    type Edges = FixedEdges;

    /// `Draw_Top_TriFP`.
    fn top(&self, p1: PixelPoint, p2: PixelPoint, p3: PixelPoint) -> Option<FixedEdges> {
        // "test for degenerate"
        if p1.y == p3.y || p2.y == p3.y {
            return None;
        }
        let (x1, x2) = if p2.x < p1.x { (p2.x, p1.x) } else { (p1.x, p2.x) };
        let height = p3.y - p1.y;
        Some(FixedEdges {
            xs: x1 << FIXP16_SHIFT,
            xe: x2 << FIXP16_SHIFT,
            dx_left: slope(x1, p3.x, height),
            dx_right: slope(x2, p3.x, height),
        })
    }

    /// `Draw_Bottom_TriFP`.
    fn bottom(&self, p1: PixelPoint, p2: PixelPoint, p3: PixelPoint) -> Option<FixedEdges> {
        if p1.y == p2.y || p1.y == p3.y {
            return None;
        }
        let (x2, x3) = if p3.x < p2.x { (p3.x, p2.x) } else { (p2.x, p3.x) };
        let height = p3.y - p1.y;
        Some(FixedEdges {
            xs: p1.x << FIXP16_SHIFT,
            xe: p1.x << FIXP16_SHIFT,
            dx_left: slope(p1.x, x2, height),
            dx_right: slope(p1.x, x3, height),
        })
    }
}

impl EdgePair for FixedEdges {
    fn skip_lines(&mut self, lines: i32) {
        self.xs = self.xs.wrapping_add(self.dx_left.wrapping_mul(lines));
        self.xe = self.xe.wrapping_add(self.dx_right.wrapping_mul(lines));
    }

    fn step(&mut self) {
        self.xs = self.xs.wrapping_add(self.dx_left);
        self.xe = self.xe.wrapping_add(self.dx_right);
    }

    fn memset_span(&self) -> (i64, i64) {
        let start = self.xs.wrapping_add(FIXP16_ROUND_UP) >> FIXP16_SHIFT;
        let count = (self.xe.wrapping_sub(self.xs).wrapping_add(FIXP16_ROUND_UP) >> FIXP16_SHIFT) + 1;
        (i64::from(start), i64::from(count))
    }

    fn ends(&self) -> (i32, i32) {
        let round = |v: i32| v.wrapping_add(FIXP16_ROUND_UP) >> FIXP16_SHIFT;
        (round(self.xs), round(self.xe))
    }
}

#[cfg(test)]
mod tests {
    use super::super::float::Lamothe;
    use super::*;
    use crate::methods::test_support::draw;

    #[test]
    fn flat_bottom_rounds_both_ends() {
        // The float version's triangle: row 1, xs = 0.75 rounds to 1 and
        // the rounded difference 1.5 gives 2 + 1 pixels.
        assert_eq!(
            draw(&LamotheFixed, &[(1, 0), (0, 4), (6, 4)]),
            ".#......\n.###....\n.####...\n######..\n#######.\n........\n"
        );
    }

    #[test]
    fn flat_top_starts_both_edges_on_whole_pixels() {
        // xe = 7 (no + 0.5 here); row 1: xs = 0.5 rounds up to 1.
        assert_eq!(
            draw(&LamotheFixed, &[(0, 0), (7, 0), (2, 4)]),
            "########\n.######.\n.#####..\n..###...\n..#.....\n........\n"
        );
    }

    #[test]
    fn split_triangle_draws_the_middle_row_twice() {
        assert_eq!(
            draw(&LamotheFixed, &[(1, 0), (6, 2), (2, 4)]),
            ".#......\n..###...\n..22222.\n..###...\n..#.....\n........\n"
        );
    }

    #[test]
    fn quad_overlaps_on_its_diagonal_and_overshoots_its_right_edge() {
        // Second half, row 2: xs = 3.5 rounds to 4, xe - xs = 2.5 rounds to
        // 3, so 4 pixels from 4 reach x = 7, right of the quad's x = 6.
        assert_eq!(
            draw(&LamotheFixed, &[(1, 0), (6, 0), (6, 4), (1, 4)]),
            ".#####2.\n.####2#.\n.###2###\n.#2####.\n.2#####.\n........\n"
        );
    }

    #[test]
    fn no_clip_path_draws_a_pixel_the_x_clip_path_does_not() {
        // One triangle, inside the target and moved one pixel left. Row 1:
        // xs = 0.5, xe = 1; the no-x-clip path draws round(0.5) + 1 = 2
        // pixels from round(0.5) = 1, past the vertical right edge; the
        // x-clip path draws round(xs) ..= round(xe), one pixel.
        let inside = draw(&LamotheFixed, &[(1, 0), (0, 2), (1, 2)]);
        let crossing = draw(&LamotheFixed, &[(0, 0), (-1, 2), (0, 2)]);
        assert_eq!(inside, ".#......\n.##.....\n##......\n........\n........\n........\n");
        assert_eq!(crossing, "#.......\n#.......\n#.......\n........\n........\n........\n");
    }

    #[test]
    fn slopes_wrap_beyond_32767_pixels() {
        // (40000 << 16) wraps negative: the right edge runs left and the
        // triangle collapses to its apex, where the float version fills.
        let points = [(0, 0), (40000, 5), (0, 5)];
        assert_eq!(draw(&LamotheFixed, &points), "#.......\n........\n........\n........\n........\n........\n");
        assert_eq!(draw(&Lamothe, &points), ["#.......\n", &"########\n".repeat(5)].concat());
    }
}
