//! `abrash_float`: Abrash's first convex filler, Listing 38.1
//! (`FillConvexPolygon` with the floating-point `ScanEdge`) of the Black
//! Book's chapter 38 (`docs/methods.md#abrash-chapter-38`).
//!
//! - Convention: samples at integer grid points; a point on a left edge or a
//!   flat top is in, on a right edge or a flat bottom out. Vertices are
//!   rounded to whole pixels first (the original takes `int`s).
//! - Arithmetic: `f64` inverse slope `DX / DY`, `X = X1 + ceil((Y - Y1) *
//!   slope)`, right-edge X values moved one pixel left, so the float error
//!   the book reports (ch. 39: two pixels off on its test screen) is kept.
//! - Classes: one contour, monotone in y ("convex" in Abrash's sense). Other
//!   polygons give what the original gives, within the target.
//!
//! Safety changes, none of which moves a pixel the original draws: the
//! line list only holds visible rows, entries an edge chain never reaches
//! draw nothing (the original leaves them uninitialised), a chain that runs
//! past the last line stops (the original writes past its `malloc`), and the
//! 16-bit `int` products become `i64`.

use alloc::vec;
use alloc::vec::Vec;

use crate::classify::Class;
use crate::geometry::{FillRule, PixelPoint, Polygon};
use crate::methods::info::{Heap, MethodInfo, Refusal};
use crate::methods::interface::Builtin;
use crate::reference::Convention;
use crate::target::SpanSink;

/// Listing 38.1.
pub struct AbrashFloat;

/// The convention of chapter 38, which chapter 39 keeps.
pub(super) const CONVENTION: Convention = Convention {
    sample_x: 0,
    sample_y: 0,
    summary: "integer sample points; left edges and flat tops in, right edges and flat bottoms out",
};

static INFO: MethodInfo = MethodInfo {
    name: "abrash_float",
    source: "Abrash, Black Book ch. 38: Listing 38.1",
    convention: CONVENTION,
    numeric: "integer vertices; f64 inverse slope with ceil",
    handles: Class::Convex,
    rules: &[FillRule::EvenOdd, FillRule::NonZero],
    heap: Heap::EveryPolygon,
};

impl Builtin for AbrashFloat {
    const INFO: &'static MethodInfo = &INFO;

    fn fill_into<S: SpanSink + ?Sized>(&self, polygon: &Polygon, sink: &mut S) -> Result<(), Refusal> {
        fill_with(polygon, sink, scan_edge)
    }
}

/// `Method::fill` of chapters 38 and 39: one contour, its vertices rounded
/// to the whole pixels the listings take, filled by [`fill_convex_polygon`]
/// with the chapter's `scan_edge`.
pub(super) fn fill_with<S: SpanSink + ?Sized>(
    polygon: &Polygon,
    sink: &mut S,
    scan_edge: ScanEdge,
) -> Result<(), Refusal> {
    let contour = polygon.single_contour().ok_or(Refusal::MultipleContours)?;
    let vertices: Vec<PixelPoint> = contour.iter().map(|p| p.round_to_pixel()).collect();
    fill_convex_polygon(&vertices, polygon.color, sink, scan_edge);
    Ok(())
}

/// One `ScanEdge` call of Listing 38.1: the segment from (`x1`, `y1`) down
/// to (`x2`, `y2`), X already moved one pixel left on right edges, and
/// whether its first scan line is skipped (`SkipFirst`).
pub(super) struct Segment {
    pub x1: i32,
    pub y1: i32,
    pub x2: i32,
    pub y2: i32,
    pub skip_first: bool,
}

/// A port of `ScanEdge`: stores the X of the segment's stored scan lines
/// `rows` into `xs`, one each. Row 0 is scan line `y1 + skip_first`, the
/// first the original stores. The driver calls it only for `y2 > y1` (every
/// `ScanEdge` returns at once otherwise) and only with the rows the target
/// shows, so a port must compute the X of `rows.start` without stepping
/// through the rows before it.
pub(super) type ScanEdge = fn(&Segment, core::ops::Range<i64>, &mut [i32]);

/// The horizontal line list of Listing 38.1, limited to the rows the target
/// shows. Entry `i` is scan line `y_start + i`; ends are inclusive.
struct LineList {
    y_start: i64,
    lines: i64,
    first_visible: i64,
    x_start: Vec<i32>,
    x_end: Vec<i32>,
}

impl LineList {
    fn new(y_start: i64, lines: i64, height: i32) -> Self {
        let first_visible = (0 - y_start).clamp(0, lines);
        let last_visible = (i64::from(height) - y_start).clamp(first_visible, lines);
        let visible = (last_visible - first_visible) as usize;
        // Unreached entries draw nothing: start right of end.
        Self { y_start, lines, first_visible, x_start: vec![i32::MAX; visible], x_end: vec![i32::MIN; visible] }
    }

    /// Visible slots `first..last` among entries `from..to` (line-list indices).
    fn visible(&self, from: i64, to: i64) -> core::ops::Range<i64> {
        let last_visible = self.first_visible + self.x_start.len() as i64;
        from.max(self.first_visible)..to.min(last_visible).min(self.lines)
    }
}

/// `FillConvexPolygon` of Listing 38.1, with offsets already applied; the
/// edges are scanned by `scan_edge`: Listing 38.1's float one here, Listing
/// 39.2's integer one in `abrash_int` (chapter 39 keeps this driver and
/// replaces only `ScanEdge`).
fn fill_convex_polygon<S: SpanSink + ?Sized>(v: &[PixelPoint], color: u8, sink: &mut S, scan_edge: ScanEdge) {
    let n = v.len();
    if n == 0 {
        return;
    }
    let forward = |i: usize| if i + 1 == n { 0 } else { i + 1 };
    let backward = |i: usize| if i == 0 { n - 1 } else { i - 1 };

    // Top and bottom: first strictly smaller Y, first largest Y (`else if`).
    let (mut min_index, mut max_index) = (0, 0);
    let (mut min_y, mut max_y) = (v[0].y, v[0].y);
    for (i, p) in v.iter().enumerate().skip(1) {
        if p.y < min_y {
            min_y = p.y;
            min_index = i;
        } else if p.y > max_y {
            max_y = p.y;
            max_index = i;
        }
    }
    if min_y == max_y {
        return;
    }

    // Ends of the top edge; the walks stop because some vertex is lower.
    let mut min_index_r = min_index;
    while v[min_index_r].y == min_y {
        min_index_r = forward(min_index_r);
    }
    min_index_r = backward(min_index_r);
    let mut min_index_l = min_index;
    while v[min_index_l].y == min_y {
        min_index_l = backward(min_index_l);
    }
    min_index_l = forward(min_index_l);

    let mut left_edge_forward = false;
    let top_is_flat = v[min_index_l].x != v[min_index_r].x;
    if top_is_flat {
        if v[min_index_l].x > v[min_index_r].x {
            left_edge_forward = true;
            core::mem::swap(&mut min_index_l, &mut min_index_r);
        }
    } else {
        let next = v[forward(min_index_r)];
        let previous = v[backward(min_index_l)];
        let top = v[min_index_l];
        let (dxn, dyn_) = (i64::from(next.x) - i64::from(top.x), i64::from(next.y) - i64::from(top.y));
        let (dxp, dyp) = (i64::from(previous.x) - i64::from(top.x), i64::from(previous.y) - i64::from(top.y));
        if dxn * dyp - dyn_ * dxp < 0 {
            left_edge_forward = true;
            core::mem::swap(&mut min_index_l, &mut min_index_r);
        }
    }

    let flat = i64::from(top_is_flat);
    let lines = i64::from(max_y) - i64::from(min_y) - 1 + flat;
    if lines <= 0 {
        return;
    }
    let y_start = i64::from(min_y) + 1 - flat;
    let mut list = LineList::new(y_start, lines, sink.size().height);

    for (start, step_forward, x_shift, is_left) in
        [(min_index_l, left_edge_forward, 0, true), (min_index_r, !left_edge_forward, -1, false)]
    {
        let mut slot = 0i64;
        let mut skip_first = !top_is_flat;
        let mut current = start;
        loop {
            let previous = current;
            current = if step_forward { forward(current) } else { backward(current) };
            let (a, b) = (v[previous], v[current]);
            let segment = Segment {
                x1: a.x.saturating_add(x_shift),
                y1: a.y,
                x2: b.x.saturating_add(x_shift),
                y2: b.y,
                skip_first,
            };
            scan_segment(&mut list, &mut slot, &segment, is_left, scan_edge);
            skip_first = false;
            if current == max_index {
                break;
            }
        }
    }

    let width = sink.size().width;
    for (i, (&xs, &xe)) in list.x_start.iter().zip(&list.x_end).enumerate() {
        let y = list.y_start + list.first_visible + i as i64;
        let (x0, x1) = (i64::from(xs).max(0), (i64::from(xe) + 1).min(i64::from(width)));
        if x0 < x1 {
            sink.span(y as i32, x0 as i32, x1 as i32, color);
        }
    }
}

/// Runs `scan_edge` on `segment`, whose stored lines take the line-list
/// slots from `*slot` on, for the visible ones only, then moves `*slot` past
/// them as the original's `EdgePointPtr` moves.
fn scan_segment(list: &mut LineList, slot: &mut i64, segment: &Segment, is_left: bool, scan_edge: ScanEdge) {
    // `ScanEdge`'s own guard against horizontal and zero-length segments.
    let delta_y = i64::from(segment.y2) - i64::from(segment.y1);
    if delta_y <= 0 {
        return;
    }
    let count = delta_y - i64::from(segment.skip_first);
    let slots = list.visible(*slot, *slot + count);
    if !slots.is_empty() {
        let index = |s: i64| (s - list.first_visible) as usize;
        let (from, to) = (index(slots.start), index(slots.end));
        let xs = if is_left { &mut list.x_start } else { &mut list.x_end };
        scan_edge(segment, slots.start - *slot..slots.end - *slot, &mut xs[from..to]);
    }
    *slot += count;
}

/// `ScanEdge` of Listing 38.1: stored line `row` is scan line
/// `Y = Y1 + skip_first + row`, at `X1 + ceil((Y - Y1) * DX / DY)` (in `f64`).
fn scan_edge(segment: &Segment, rows: core::ops::Range<i64>, xs: &mut [i32]) {
    let delta_y = i64::from(segment.y2) - i64::from(segment.y1);
    let inverse_slope = (f64::from(segment.x2) - f64::from(segment.x1)) / delta_y as f64;
    for (row, x) in rows.zip(xs) {
        let y_minus_y1 = row + i64::from(segment.skip_first);
        *x = segment.x1.saturating_add(ceil(y_minus_y1 as f64 * inverse_slope) as i32);
    }
}

/// `ceil` without `std`: `f64::ceil` lives in std, so round toward zero and
/// correct the positive fractions.
fn ceil(v: f64) -> f64 {
    let t = v as i64 as f64;
    if t < v {
        t + 1.0
    } else {
        t
    }
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use crate::methods::test_support::{draw, empty, full};

    /// Vertices and the picture Listing 38.1's rule gives them. Chapter
    /// 39's integer `ScanEdge` keeps the pixel choice: `abrash_int` is held
    /// to the same pictures.
    pub(in crate::methods) type Picture = (&'static [(i32, i32)], &'static str);

    /// A rectangle: its right column and bottom row are out.
    pub(in crate::methods) const RECTANGLE: Picture =
        (&[(1, 1), (5, 1), (5, 4), (1, 4)], "........\n.####...\n.####...\n.####...\n........\n........\n");

    /// A pointed top: its top line is skipped, and row 1 meets the left
    /// edge at x=2 (drawn) and the right at x=4 (not).
    pub(in crate::methods) const POINTED_TOP: Picture =
        (&[(3, 0), (6, 3), (0, 3)], "........\n..##....\n.####...\n........\n........\n........\n");

    #[test]
    fn rectangle_excludes_right_column_and_bottom_row() {
        assert_eq!(draw(&AbrashFloat, RECTANGLE.0), RECTANGLE.1);
    }

    #[test]
    fn pointed_top_skips_the_top_line_and_right_edge_points() {
        assert_eq!(draw(&AbrashFloat, POINTED_TOP.0), POINTED_TOP.1);
    }

    #[test]
    fn off_screen_and_huge_polygons_are_clipped() {
        assert_eq!(
            draw(&AbrashFloat, &[(-1 << 22, -1 << 22), (1 << 22, -1 << 22), (1 << 22, 1 << 22), (-1 << 22, 1 << 22)]),
            full()
        );
        assert_eq!(draw(&AbrashFloat, &[(100, 100), (120, 100), (120, 120)]), empty());
    }

    #[test]
    fn ceil_matches_the_definition() {
        for (v, c) in [(-1.5, -1.0), (-0.0, 0.0), (0.25, 1.0), (2.0, 2.0), (-3.0, -3.0)] {
            assert_eq!(ceil(v), c);
        }
    }
}
