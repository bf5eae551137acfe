//! `lamothe`: the float triangle filler printed in LaMothe's "Solid Filled
//! Polygons" (`docs/methods.md#lamothe`: `Draw_Triangle_2D`, `Draw_Top_Tri`,
//! `Draw_Bottom_Tri`); decomposition and clipping in the parent module.
//!
//! - Convention: integer rows, both span ends drawn; x truncated toward
//!   zero by `(int)` casts ("the algorithm truncates the endpoints each
//!   scanline" — he suggests adding 0.5 but his listing only does it for the
//!   right edge of a flat top, `xe = (float)x2+(float)0.5`, and comments it
//!   out in the flat bottom). The no-x-clip path draws `(unsigned
//!   int)(xe-xs+1)` pixels from `(unsigned int)xs`, the x-clip path
//!   `(int)xs ..= (int)xe`: not always the same pixels.
//! - Arithmetic: `float` is `f32` (evaluated as written, no wider
//!   intermediates: the SSE reading of his C, not the x87 one): `dx =
//!   (x3-x1)/height` with `height` a float, `xs += dx` per line, the y clip
//!   `xs + dx * (float)(min_clip_y - y1)`. Rust's `as` truncates toward zero
//!   like C's cast and saturates where C's is undefined; with rounded
//!   vertices (±2^23) and heights of at least one line the values never
//!   come near the `i32` limits.
//! - Classes: triangles; quads and convex polygons through the parent
//!   module's split and fan.

use crate::classify::Class;
use crate::geometry::{FillRule, PixelPoint, Polygon};
use crate::methods::info::{Heap, MethodInfo, Refusal};
use crate::methods::interface::Builtin;
use crate::reference::Convention;
use crate::target::SpanSink;

use super::halves::{fill_polygon, EdgePair, FlatHalves};

/// LaMothe's float `Draw_Triangle_2D`, with his quad split and fan.
pub struct Lamothe;

static INFO: MethodInfo = MethodInfo {
    name: "lamothe",
    source: "LaMothe, \"Solid Filled Polygons\": Draw_Triangle_2D",
    convention: Convention {
        sample_x: 0,
        sample_y: 0,
        summary: "integer rows; flat halves draw their top and bottom rows and both span ends (overlaps); x truncated",
    },
    numeric: "integer vertices; f32 edges stepped by dx/dy, (int) truncation; split point (int)(0.5 + f32)",
    handles: Class::Triangle,
    rules: &[FillRule::EvenOdd, FillRule::NonZero],
    heap: Heap::Never,
};

impl Builtin for Lamothe {
    const INFO: &'static MethodInfo = &INFO;

    fn fill_into<S: SpanSink + ?Sized>(&self, polygon: &Polygon, sink: &mut S) -> Result<(), Refusal> {
        fill_polygon(self, polygon, sink)
    }
}

/// `xs`, `xe`, `dx_left`, `dx_right` of `Draw_Top_Tri` / `Draw_Bottom_Tri`.
pub(super) struct FloatEdges {
    xs: f32,
    xe: f32,
    dx_left: f32,
    dx_right: f32,
}

impl FlatHalves for Lamothe {
    type Edges = FloatEdges;

    /// `Draw_Top_Tri`. The float version has no degenerate test:
    /// `Draw_Triangle_2D` only calls it with `y3 > y1`.
    fn top(&self, p1: PixelPoint, p2: PixelPoint, p3: PixelPoint) -> Option<FloatEdges> {
        let (x1, x2) = if p2.x < p1.x { (p2.x, p1.x) } else { (p1.x, p2.x) };
        let height = (p3.y - p1.y) as f32;
        Some(FloatEdges {
            xs: x1 as f32,
            xe: x2 as f32 + 0.5,
            dx_left: (p3.x - x1) as f32 / height,
            dx_right: (p3.x - x2) as f32 / height,
        })
    }

    /// `Draw_Bottom_Tri`; as in [`Self::top`], no degenerate test.
    fn bottom(&self, p1: PixelPoint, p2: PixelPoint, p3: PixelPoint) -> Option<FloatEdges> {
        let (x2, x3) = if p3.x < p2.x { (p3.x, p2.x) } else { (p2.x, p3.x) };
        let height = (p3.y - p1.y) as f32;
        Some(FloatEdges {
            xs: p1.x as f32,
            xe: p1.x as f32,
            dx_left: (x2 - p1.x) as f32 / height,
            dx_right: (x3 - p1.x) as f32 / height,
        })
    }
}

impl EdgePair for FloatEdges {
    fn skip_lines(&mut self, lines: i32) {
        self.xs += self.dx_left * lines as f32;
        self.xe += self.dx_right * lines as f32;
    }

    fn step(&mut self) {
        self.xs += self.dx_left;
        self.xe += self.dx_right;
    }

    fn memset_span(&self) -> (i64, i64) {
        (self.xs as i64, (self.xe - self.xs + 1.0) as i64)
    }

    fn ends(&self) -> (i32, i32) {
        (self.xs as i32, self.xe as i32)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Point;
    use crate::methods::test_support::{draw, empty, fill, full, SMALL};

    #[test]
    fn flat_bottom_truncates_and_counts_from_the_truncated_start() {
        // dx_left = -0.25, dx_right = 1.25; all rows drawn, apex included.
        // Row 1: xs = 0.75 starts at 0 and `(int)(xe-xs+1)` = 2 pixels end
        // at 1, short of xe = 2.25.
        assert_eq!(
            draw(&Lamothe, &[(1, 0), (0, 4), (6, 4)]),
            ".#......\n##......\n####....\n#####...\n#######.\n........\n"
        );
    }

    #[test]
    fn flat_top_draws_its_top_row_and_apex() {
        // xs = 0, xe = 7 + 0.5; dx_left = 0.5, dx_right = -1.25.
        assert_eq!(
            draw(&Lamothe, &[(0, 0), (7, 0), (2, 4)]),
            "########\n######..\n.#####..\n.###....\n..#.....\n........\n"
        );
    }

    #[test]
    fn split_triangle_draws_the_middle_row_twice() {
        // new_x = 1 + (int)(0.5 + 2 * 1 / 4) = 2 on row 2, drawn by both halves.
        assert_eq!(
            draw(&Lamothe, &[(1, 0), (6, 2), (2, 4)]),
            ".#......\n.###....\n..22222.\n..###...\n..#.....\n........\n"
        );
    }

    #[test]
    fn quad_halves_overlap_on_their_diagonal_and_leave_a_gap() {
        // Draw_QuadFP_2D's split: (0, 1, 3) and (1, 2, 3), diagonal 1-3.
        // The second half's right edge is x = 6, but its no-x-clip count
        // starts from the truncated left end: column 6 is lost on rows 1-3.
        assert_eq!(
            draw(&Lamothe, &[(1, 0), (6, 0), (6, 4), (1, 4)]),
            ".#####2.\n.###22..\n.##22#..\n.#2###..\n.2#####.\n........\n"
        );
    }

    #[test]
    fn x_clip_path_keeps_pixels_the_no_clip_path_drops() {
        // One triangle, inside the target and moved two pixels left so that
        // one vertex is off it. Row 1: xs = 4.75, xe = 6; the no-x-clip path
        // draws (int)(xe-xs+1) = 2 pixels from 4, the x-clip path 4..=6.
        let inside = draw(&Lamothe, &[(6, 0), (6, 4), (1, 4)]);
        let crossing = draw(&Lamothe, &[(4, 0), (4, 4), (-1, 4)]);
        assert_eq!(inside, "......#.\n....##..\n...###..\n..####..\n.######.\n........\n");
        assert_eq!(crossing, "....#...\n..###...\n.####...\n#####...\n#####...\n........\n");
    }

    #[test]
    fn pentagon_is_filled_as_a_fan_from_vertex_zero() {
        // Triangles (0,1,2), (0,2,3), (0,3,4): vertex 0 is drawn three times.
        assert_eq!(
            draw(&Lamothe, &[(3, 0), (6, 2), (5, 5), (1, 5), (0, 2)]),
            "...3....\n.#2##...\n2233222.\n#22###..\n#2##2#..\n#2####..\n"
        );
    }

    #[test]
    fn huge_triangles_are_clipped_and_distant_ones_rejected() {
        let far = [Point::new(i32::MIN, i32::MIN), Point::new(i32::MAX, i32::MIN), Point::new(0, i32::MAX)];
        assert_eq!(fill(&Lamothe, &Polygon::new(far.to_vec(), 1), SMALL).ascii(), full());
        assert_eq!(draw(&Lamothe, &[(100, 100), (120, 100), (120, 120)]), empty());
    }
}
