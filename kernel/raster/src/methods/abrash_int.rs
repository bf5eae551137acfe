//! `abrash_int`: Abrash's fast convex filler of chapter 39: Listing 38.1's
//! `FillConvexPolygon` driven by Listing 39.2's integer-only `ScanEdge`,
//! drawing one whole span per scan line as Listing 39.1's `memset` does.
//! `docs/methods.md#abrash-chapter-39` has the chapter in short.
//!
//! - Convention: the same as `abrash_float`, integer sample points; a point
//!   on a left edge or a flat top is in, on a right edge or a flat bottom
//!   out. Vertices are rounded to whole pixels first.
//! - Arithmetic: integer error terms, in the four cases of Listing 39.2
//!   (vertical, diagonal, Y-major, X-major), so an edge's X on scan line
//!   `Y1 + k` is exactly `X1 + ceil(k * DX / DY)`: the pixels Listing 38.1
//!   means to choose, without the two `ceil`s its `double`s get wrong on the
//!   book's test screen (ch. 39).
//! - Classes: one contour, monotone in y ("convex" in Abrash's sense); other
//!   polygons give what the original gives, within the target.
//!
//! The book's `int` is 16 bits under its Borland compiler; here it is `i32`.
//! C only promises that `int` has at least 16 bits, the listings never rely
//! on the width, and every value they compute lies between two rounded
//! vertex coordinates (at most 2^23 in size) or is an error term smaller
//! than an edge's height, so with `i32` nothing overflows and nothing needs
//! refusing. The driver is `abrash_float`'s, with its safety changes; on top
//! of them, an edge that starts above the target jumps to its first visible
//! line with `ErrorTermStep::skip`, which gives the X and error term the
//! stepping would, so clipping moves no pixel.

use core::ops::Range;

use super::abrash_float::{fill_with, Segment, CONVENTION};
use crate::classify::Class;
use crate::geometry::{FillRule, Polygon};
use crate::methods::info::{Heap, MethodInfo, Refusal};
use crate::methods::interface::Builtin;
use crate::target::SpanSink;

/// Listings 38.1, 39.1 and 39.2.
pub struct AbrashInt;

static INFO: MethodInfo = MethodInfo {
    name: "abrash_int",
    source: "Abrash, Black Book ch. 39: Listings 39.1 and 39.2 in Listing 38.1's driver",
    convention: CONVENTION,
    numeric: "integer vertices; integer error-term edge stepping (i32)",
    handles: Class::Convex,
    rules: &[FillRule::EvenOdd, FillRule::NonZero],
    heap: Heap::EveryPolygon,
};

impl Builtin for AbrashInt {
    const INFO: &'static MethodInfo = &INFO;

    fn fill_into<S: SpanSink + ?Sized>(&self, polygon: &Polygon, sink: &mut S) -> Result<(), Refusal> {
        fill_with(polygon, sink, scan_edge)
    }
}

/// X stepping with an error term, one scan line at a time: `X += whole;
/// ErrorTerm += adj_up; if ErrorTerm > 0 { X += direction; ErrorTerm -=
/// adj_down }`. This is the loop of Listing 39.2's Y-major case (`whole` 0,
/// `adj_up` the width) and X-major case, and Listing 40.1's `AdvanceAET` on
/// an `EdgeState` (`abrash_aet` keeps its edges in this form).
#[derive(Clone, Copy, Debug)]
pub(super) struct ErrorTermStep {
    pub x: i32,
    pub whole: i32,
    pub direction: i32,
    pub error_term: i32,
    pub adj_up: i32,
    pub adj_down: i32,
}

impl ErrorTermStep {
    /// An edge leaving `x` with horizontal extent `delta_x` over `height`
    /// scan lines (`height > 0`), stepping `whole` pixels and `adj_up`
    /// error a line. Both listings start the error term at 0 going right
    /// and at `1 - height` going left, and count `height` per extra pixel;
    /// with their `whole` and `adj_up` (`whole * height + adj_up` is
    /// `|delta_x|`), line `k`'s X is `x + ceil(k * delta_x / height)`.
    pub(super) fn new(x: i32, delta_x: i32, height: i32, whole: i32, adj_up: i32) -> Self {
        Self {
            x,
            whole,
            direction: if delta_x > 0 { 1 } else { -1 },
            error_term: if delta_x >= 0 { 0 } else { 1 - height },
            adj_up,
            adj_down: height,
        }
    }

    /// One scan line down.
    pub(super) fn step(&mut self) {
        self.x += self.whole;
        self.error_term += self.adj_up;
        if self.error_term > 0 {
            self.x += self.direction;
            self.error_term -= self.adj_down;
        }
    }

    /// `lines` scan lines down at once, in `i64` so no product overflows.
    /// Both listings keep `0 <= adj_up <= adj_down` and start with the error
    /// term in `(-adj_down, 0]`, so each step subtracts `adj_down` at most
    /// once and leaves the term in that interval again: after `lines` steps
    /// it has subtracted exactly `ceil((error_term + lines * adj_up) /
    /// adj_down)` times. `lines` must not pass the edge's last line, where
    /// X is back between the edge's ends.
    pub(super) fn skip(&mut self, lines: i64) {
        let adj_down = i64::from(self.adj_down);
        let total = i64::from(self.error_term) + lines * i64::from(self.adj_up);
        // `total > -adj_down`, so the numerator is never negative.
        let extra = (total + adj_down - 1) / adj_down;
        self.error_term = (total - extra * adj_down) as i32;
        self.x = (i64::from(self.x) + lines * i64::from(self.whole) + extra * i64::from(self.direction)) as i32;
    }
}

/// `ScanEdge` of Listing 39.2. The original steps from `Y1`, pre-stepping
/// once when `SkipFirst` is set; here the first stored X comes from
/// stepping `rows.start + skip_first` lines at once (the same X, see
/// [`ErrorTermStep::skip`]), and the rest are stepped as in the book.
fn scan_edge(segment: &Segment, rows: Range<i64>, xs: &mut [i32]) {
    let delta_x = segment.x2 - segment.x1;
    let height = segment.y2 - segment.y1;
    let width = delta_x.abs();
    let advance_amt = if delta_x > 0 { 1 } else { -1 };
    let lines_before = rows.start + i64::from(segment.skip_first);
    if width == 0 {
        // Vertical: the same X on every line.
        xs.fill(segment.x1);
    } else if width == height {
        // Diagonal: one pixel a line.
        let mut x = (i64::from(segment.x1) + lines_before * i64::from(advance_amt)) as i32;
        for slot in xs {
            *slot = x;
            x += advance_amt;
        }
    } else {
        let mut edge = if height > width {
            // Y-major: at most one pixel a line.
            ErrorTermStep::new(segment.x1, delta_x, height, 0, width)
        } else {
            // X-major: `Width / Height` pixels a line, one more when the
            // error term goes positive.
            ErrorTermStep::new(segment.x1, delta_x, height, (width / height) * advance_amt, width % height)
        };
        edge.skip(lines_before);
        for slot in xs {
            *slot = edge.x;
            edge.step();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::methods::abrash_float::tests::{POINTED_TOP, RECTANGLE};
    use crate::methods::test_support::{assert_clipping_changes_no_pixel, draw, empty, full, TALL_TRIANGLES};

    #[test]
    fn rectangle_excludes_right_column_and_bottom_row() {
        assert_eq!(draw(&AbrashInt, RECTANGLE.0), RECTANGLE.1);
    }

    #[test]
    fn pointed_top_skips_the_top_line_and_right_edge_points() {
        assert_eq!(draw(&AbrashInt, POINTED_TOP.0), POINTED_TOP.1);
    }

    #[test]
    fn x_major_and_y_major_edges_take_the_ceiling() {
        // Left chain: (0,0)-(3,2) is X-major, X = ceil(3k/2) = 0, 2 on rows
        // 0, 1; (3,2)-(1,5) is Y-major going left, X = 3 + ceil(-2k/3) = 3,
        // 3, 2 on rows 2, 3, 4. The right edge is vertical at 7, less one.
        let picture = draw(&AbrashInt, &[(0, 0), (7, 0), (7, 5), (1, 5), (3, 2)]);
        assert_eq!(picture, "#######.\n..#####.\n...####.\n...####.\n..#####.\n........\n");
    }

    #[test]
    fn skipping_to_row_k_gives_the_stepped_error_term() {
        for height in 1..=9 {
            for delta_x in -20..=20 {
                let width = i32::abs(delta_x);
                if width == 0 || width == height {
                    continue;
                }
                let advance_amt = if delta_x > 0 { 1 } else { -1 };
                let (whole, adj_up) =
                    if height > width { (0, width) } else { ((width / height) * advance_amt, width % height) };
                let start = ErrorTermStep::new(5, delta_x, height, whole, adj_up);
                let mut stepped = start;
                for k in 0..=i64::from(height) {
                    let mut jumped = start;
                    jumped.skip(k);
                    assert_eq!(
                        (jumped.x, jumped.error_term),
                        (stepped.x, stepped.error_term),
                        "dx {delta_x} h {height} k {k}"
                    );
                    let exact = 5
                        + (k * i64::from(delta_x)).div_euclid(i64::from(height))
                        + i64::from((k * i64::from(delta_x)).rem_euclid(i64::from(height)) != 0);
                    assert_eq!(i64::from(stepped.x), exact);
                    stepped.step();
                }
            }
        }
    }

    #[test]
    fn clipping_changes_no_pixel() {
        for triangle in TALL_TRIANGLES {
            assert_clipping_changes_no_pixel(&AbrashInt, &Polygon::from_pixels(triangle, (0, 0), 1));
        }
    }

    #[test]
    fn huge_and_off_screen_polygons_are_clipped() {
        let big = 1 << 22;
        assert_eq!(draw(&AbrashInt, &[(-big, -big), (big, -big), (big, big), (-big, big)]), full());
        assert_eq!(draw(&AbrashInt, &[(100, 100), (120, 100), (120, 120)]), empty());
    }
}
