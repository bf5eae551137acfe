//! `wgt`: Chris Egerter's `fillpoly` and `polyline` from WGT Graphics
//! Tutorial #1, "Filled Polygons" (1994; `docs/methods.md#wgt-tutorial-1`).
//! Every edge is scan converted into two arrays, `startx` and `endx`, one
//! entry per row, preset to the "impossible number" -16000: the first x
//! found on a row goes to `startx`, any later one to `endx`. Then every row
//! with a point is drawn with `line(startx, y, endx, y)`.
//!
//! - Convention: integer rows. An edge from (x1, y1) down to (x2, y2)
//!   covers rows `y1 + 1 ..= y2` ("We ALWAYS skip the first point in every
//!   line"), horizontal edges none; its x on a row is the 8.8 value shifted
//!   down (floor). Both ends of a row are drawn, in whichever order the two
//!   crossings came: the tutorial's `line` is its general line "with any
//!   slope" (wgtgfx.c, not in the seed), which joins two points from either
//!   end, so `startx > endx` draws `endx ..= startx`. A polygon's top row is
//!   never drawn; its bottom vertex's row is, as one pixel.
//! - Arithmetic: Turbo C++, so `int` is 16 bits and `long` 32. `x` is
//!   `(long)x1<<8` (8.8 in an `i32`), the step `m = ((long)(x2 -
//!   x1)<<8) / ((long)(y2 - y1))` truncated toward zero, with the
//!   differences taken in 16-bit `int` (they wrap, as `i16` wrapping ops
//!   here, when points are more than 32767 apart), and `x>>8` stored back
//!   into an `int` array (`as i16`).
//! - Classes: one contour, monotone in y (every row crosses the boundary at
//!   most twice: the tutorial's "convex"). Other polygons give what the
//!   original gives: a third crossing on a row overwrites `endx`.
//!
//! Port decisions:
//! - Vertices are rounded with [`Point::round_to_pixel`](crate::Point::round_to_pixel) to
//!   be the original's `int` inputs; those that do not fit its 16-bit `int`
//!   could not be passed to it and are refused ([`Refusal::OutOfRange`]).
//! - The arrays hold the target's rows (the tutorial's 200, "changing the
//!   200 to the number of rows the mode has"), only those the polygon spans;
//!   rows outside the target are skipped as by its `(y >= 0) & (y < 200)`
//!   test, and spans are cut to the target's width.
//! - The sentinel is kept with its flaw: a crossing that lands on x = -16000
//!   counts as no crossing at all.
//! - Zero vertices draw nothing (the original reads `vertexlist[0]`
//!   anyway); one vertex is a horizontal edge to itself and draws nothing;
//!   two vertices give the same edge twice, a line one pixel wide.
//!
//! Safety change: an edge's rows are visited only where they meet the
//! target, its x computed as `(x1<<8) + m*(y - y1)` with wrapping `i32`
//! arithmetic, which is exactly the original's `x += m` repeated in a 32-bit
//! `long`, wraps included. So work is bounded by the target's height per
//! edge, and an edge ending on row 32767, whose 16-bit `y` wraps before it
//! passes `y2` and so loops for ever in the original, ends.

use alloc::vec;
use alloc::vec::Vec;

use crate::classify::Class;
use crate::geometry::{FillRule, Polygon};
use crate::methods::info::{Heap, MethodInfo, Refusal};
use crate::methods::interface::Builtin;
use crate::reference::Convention;
use crate::target::SpanSink;

/// The tutorial's `fillpoly`.
pub struct Wgt;

/// "-16000 as the impossible number that would never be used".
const IMPOSSIBLE: i16 = -16000;

static INFO: MethodInfo = MethodInfo {
    name: "wgt",
    source: "Egerter, WGT tutorial 1: fillpoly, polyline",
    convention: Convention {
        sample_x: 0,
        sample_y: 0,
        summary: "integer rows; each edge skips its top row; x floored from 8.8; both ends of a row drawn",
    },
    numeric: "16-bit int vertices; 8.8 fixed point in a 32-bit long, slope truncated toward zero",
    handles: Class::Convex,
    rules: &[FillRule::EvenOdd, FillRule::NonZero],
    heap: Heap::EveryPolygon,
};

impl Builtin for Wgt {
    const INFO: &'static MethodInfo = &INFO;

    fn fill_into<S: SpanSink + ?Sized>(&self, polygon: &Polygon, sink: &mut S) -> Result<(), Refusal> {
        let contour = polygon.single_contour().ok_or(Refusal::MultipleContours)?;
        let vertices = contour
            .iter()
            .map(|p| {
                let p = p.round_to_pixel();
                Some(Vertex { x: i16::try_from(p.x).ok()?, y: i16::try_from(p.y).ok()? })
            })
            .collect::<Option<Vec<_>>>()
            .ok_or(Refusal::OutOfRange)?;
        fillpoly(&vertices, polygon.color, sink);
        Ok(())
    }
}

/// The tutorial's `point`: `int x, y`, 16 bits.
#[derive(Clone, Copy, Debug)]
struct Vertex {
    x: i16,
    y: i16,
}

/// `startx` and `endx`, for target rows `first_row ..` only.
struct LineArrays {
    first_row: i32,
    startx: Vec<i16>,
    endx: Vec<i16>,
}

impl LineArrays {
    /// Rows `top ..= bottom` that the target (`height` rows) shows, all
    /// set to the impossible number.
    fn new(top: i16, bottom: i16, height: i32) -> Self {
        let first_row = i32::from(top).max(0);
        let rows = (i32::from(bottom) + 1).min(height) - first_row;
        let rows = usize::try_from(rows).unwrap_or(0);
        Self { first_row, startx: vec![IMPOSSIBLE; rows], endx: vec![IMPOSSIBLE; rows] }
    }

    /// The rows of `from ..= to` that the arrays hold.
    fn rows(&self, from: i32, to: i32) -> core::ops::Range<i32> {
        let end = self.first_row + self.startx.len() as i32;
        from.max(self.first_row)..to.saturating_add(1).min(end)
    }

    /// "If it is -16000, this is the first point found on this row."
    fn store(&mut self, y: i32, x: i16) {
        let i = (y - self.first_row) as usize;
        if self.startx[i] == IMPOSSIBLE {
            self.startx[i] = x;
        } else {
            self.endx[i] = x;
        }
    }
}

/// `fillpoly`: every edge, the closing one last, then every row.
fn fillpoly<S: SpanSink + ?Sized>(v: &[Vertex], color: u8, sink: &mut S) {
    let (Some(top), Some(bottom)) = (v.iter().map(|p| p.y).min(), v.iter().map(|p| p.y).max()) else {
        return;
    };
    let mut lines = LineArrays::new(top, bottom, sink.size().height);
    for edge in v.windows(2) {
        polyline(&mut lines, edge[0], edge[1]);
    }
    polyline(&mut lines, v[v.len() - 1], v[0]);

    let width = sink.size().width;
    for (y, (&start, &end)) in (lines.first_row..).zip(lines.startx.iter().zip(&lines.endx)) {
        if start == IMPOSSIBLE {
            continue;
        }
        // "In case there was only one point found on this row"
        let end = if end == IMPOSSIBLE { start } else { end };
        // `line(startx[i], i, endx[i], i)`: both ends, either order.
        let (x0, x1) = (i32::from(start.min(end)).max(0), (i32::from(start.max(end)) + 1).min(width));
        if x0 < x1 {
            sink.span(y, x0, x1, color);
        }
    }
}

/// `polyline`: stores the x of the edge `a`-`b` on each of its rows but
/// the top one.
fn polyline(lines: &mut LineArrays, a: Vertex, b: Vertex) {
    if a.y == b.y {
        return;
    }
    // "Make sure y2 is greater than y1"
    let (top, bottom) = if b.y < a.y { (b, a) } else { (a, b) };
    let x = i32::from(top.x) << 8;
    // Two distinct 16-bit values never differ by a multiple of 2^16, so
    // the wrapped divisor is not zero; the dividend is below 2^23.
    let m = (i32::from(bottom.x.wrapping_sub(top.x)) << 8) / i32::from(bottom.y.wrapping_sub(top.y));
    for y in lines.rows(i32::from(top.y) + 1, i32::from(bottom.y)) {
        let x_at = x.wrapping_add(m.wrapping_mul(y - i32::from(top.y)));
        lines.store(y, (x_at >> 8) as i16);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::coverage::CoverageSink;
    use crate::geometry::Point;
    use crate::methods::interface::Method;
    use crate::methods::test_support::{draw, fill, full, SMALL};
    use crate::target::SCREEN;

    /// The first and last pixel drawn on row `y`, checking the row is one
    /// run drawn once.
    fn row_span(hits: &CoverageSink, y: i32) -> Option<(i32, i32)> {
        let drawn: Vec<i32> = (0..SCREEN.width).filter(|&x| hits.count(x, y) > 0).collect();
        let (&first, &last) = (drawn.first()?, drawn.last()?);
        assert_eq!(drawn.len() as i32, last - first + 1, "row {y} has a gap");
        assert!(drawn.iter().all(|&x| hits.count(x, y) == 1), "row {y} drawn twice");
        Some((first, last))
    }

    #[test]
    fn tutorial_triangle_matches_the_hand_computed_rows() {
        // The seed's test program: (160,30), (50,150), (270,180).
        let hits = fill(&Wgt, &Polygon::from_pixels(&[(160, 30), (50, 150), (270, 180)], (0, 0), 15), SCREEN);
        // Row 30 is every edge's skipped first point. Row 31: left edge
        // m = (-110<<8)/120 = -234, x = 40960-234 = 40726 -> 159; closing
        // edge m = (110<<8)/150 = 187, 41147 -> 160.
        assert_eq!(row_span(&hits, 30), None);
        assert_eq!(row_span(&hits, 31), Some((159, 160)));
        // Row 150: 40960-234*120 = 12880 -> 50; 40960+187*120 = 63400 -> 247.
        assert_eq!(row_span(&hits, 150), Some((50, 247)));
        // Row 180: bottom edge 12800+1877*30 = 69110 -> 269, closing edge
        // 40960+187*150 = 69010 -> 269: one pixel.
        assert_eq!(row_span(&hits, 180), Some((269, 269)));
        assert_eq!(row_span(&hits, 181), None);
        assert!((31..=180).all(|y| row_span(&hits, y).is_some()));
    }

    #[test]
    fn top_row_skipped_bottom_row_and_both_ends_drawn() {
        assert_eq!(
            draw(&Wgt, &[(1, 1), (5, 1), (5, 4), (1, 4)]),
            "........\n........\n.#####..\n.#####..\n.#####..\n........\n"
        );
    }

    #[test]
    fn crossings_in_either_order_draw_the_same_row() {
        // Clockwise, the right edge comes first and fills `startx`. The
        // right edge's m = (4<<8)/5 = 204 (not 204.8) lags: it ends at 6,
        // short of the vertex at 7.
        let counter = draw(&Wgt, &[(3, 0), (0, 5), (7, 5)]);
        let clockwise = draw(&Wgt, &[(3, 0), (7, 5), (0, 5)]);
        assert_eq!(counter, "........\n..##....\n.####...\n.#####..\n#######.\n#######.\n");
        assert_eq!(clockwise, counter);
    }

    #[test]
    fn two_vertices_draw_their_edge_twice_as_a_line() {
        assert_eq!(draw(&Wgt, &[(1, 0), (4, 3)]), "........\n..#.....\n...#....\n....#...\n........\n........\n");
    }

    #[test]
    fn a_crossing_at_the_sentinel_is_lost() {
        // The left edge lies at x = -16000, read back as "no point found":
        // each row keeps only its right end. One pixel further left fills.
        let lost = draw(&Wgt, &[(-16000, 0), (3, 0), (3, 4), (-16000, 4)]);
        let kept = draw(&Wgt, &[(-16001, 0), (3, 0), (3, 4), (-16001, 4)]);
        assert_eq!(lost, "........\n...#....\n...#....\n...#....\n...#....\n........\n");
        assert_eq!(kept, "........\n####....\n####....\n####....\n####....\n........\n");
    }

    #[test]
    fn off_screen_input_is_clipped_and_beyond_16_bits_refused() {
        assert_eq!(draw(&Wgt, &[(-10000, -10000), (10000, -10000), (10000, 10000), (-10000, 10000)]), full());
        let far = Polygon::new(vec![Point::new(0, 0), Point::from_pixels(32768, 5), Point::from_pixels(0, 5)], 1);
        assert_eq!(Wgt.fill(&far, &mut CoverageSink::new(SMALL)), Err(Refusal::OutOfRange));
    }

    #[test]
    fn sixteen_bit_differences_wrap_as_in_turbo_c() {
        // x2 - x1 = 40000 wraps to -25536 in a 16-bit int, so m = -32686
        // instead of 51200 and the long edge runs left; `x>>8` then wraps
        // again when stored into `startx`. Exact edge: x = 0 on row 100,
        // x = 200 on row 101. Wrapped: x = -32768 on row 100 (nothing on
        // screen) and 32640 on row 101 (the whole row).
        let hits = fill(&Wgt, &Polygon::from_pixels(&[(-20000, 0), (20000, 200), (-20000, 200)], (0, 0), 1), SCREEN);
        assert_eq!(row_span(&hits, 100), None);
        assert_eq!(row_span(&hits, 101), Some((0, 319)));
    }
}
