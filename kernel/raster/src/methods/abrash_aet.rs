//! `abrash_aet`: Abrash's general polygon filler of chapter 40, Listing 40.1
//! (`FillPolygon` with a global and an active edge table) of the Black
//! Book (`docs/methods.md#abrash-chapter-40`).
//!
//! - Convention: integer sample points, as chapters 38 and 39: an edge
//!   covers scan lines `StartY..EndY` (tops in, bottoms out) at X
//!   `StartX + ceil(k * DX / DY)`, and each pair of crossings draws
//!   `left.X..=right.X - 1` (left crossings in, right ones out). Vertices
//!   are rounded to whole pixels first.
//! - Rule: odd/even only. A polygon marked non-zero is still filled
//!   odd/even, as the book has no other rule; [`MethodInfo::rules`] tells
//!   callers not to send one here.
//! - Arithmetic: integer X stepping with error terms, `BuildGET`'s field
//!   rules (an `ErrorTermStep` per edge); the GET sorted by `StartY` then
//!   X, the AET kept in X order by one merging pass per scan line and the
//!   book's bubble sort after each step. The bubble sort keeps the book's
//!   cost profile too: next to nothing when X coherence holds, quadratic in
//!   the active edges on rows where many of them cross (a 20 000-vertex
//!   random scribble takes about a second on a desktop host).
//! - Classes: any polygon (complex). Holes work as in Listing 40.4: bridge
//!   edges run in and back out along the same line, so their crossings
//!   pair up and draw nothing. Extension: a polygon with several contours
//!   builds one GET from all their edges, so under odd/even an inner
//!   contour is a hole just as a bridged one is.
//!
//! Departures, none of which moves a pixel the original draws:
//! - Linked lists become vectors; the GET is sorted once (stable, ties in
//!   the order the book's insertion leaves them: a later edge goes before
//!   an earlier one with the same `StartY` and X), not by insertion, which
//!   would cost quadratic time on thousands of vertices.
//! - An edge that starts above the target enters the GET at row 0, with
//!   the X and error term its stepping would have there (see
//!   `ErrorTermStep::skip`); edges wholly above or below the target are
//!   left out, and scan lines from the target's bottom on are not processed.
//!   Work is then bounded by the edge count and the visible rows.
//! - The book's `int` is 16 bits; here it is `i32`, wide enough for every
//!   value (see `abrash_int`), so nothing overflows or is refused for range.
//! - A contour of fewer than three vertices adds no edges (the book returns
//!   without drawing for such a vertex list); when no edge has height the
//!   fill draws nothing, where the book reads `StartY` through a null GET.
//! - The edge tables are reserved before use, and failing that is the
//!   book's `malloc` failure: [`Refusal::OutOfMemory`].

use alloc::vec::Vec;

use super::abrash_int::ErrorTermStep;
use crate::classify::Class;
use crate::geometry::{FillRule, Polygon};
use crate::methods::info::{Heap, MethodInfo, Refusal};
use crate::methods::interface::Builtin;
use crate::reference::Convention;
use crate::target::SpanSink;

/// Listing 40.1.
pub struct AbrashAet;

static INFO: MethodInfo = MethodInfo {
    name: "abrash_aet",
    source: "Abrash, Black Book ch. 40: Listing 40.1",
    convention: Convention {
        sample_x: 0,
        sample_y: 0,
        summary: "integer sample points; odd/even; left crossings and tops in, right crossings and bottoms out",
    },
    numeric: "integer vertices; integer error-term X stepping (i32)",
    handles: Class::Complex,
    rules: &[FillRule::EvenOdd],
    heap: Heap::EveryPolygon,
};

impl Builtin for AbrashAet {
    const INFO: &'static MethodInfo = &INFO;

    fn fill_into<S: SpanSink + ?Sized>(&self, polygon: &Polygon, sink: &mut S) -> Result<(), Refusal> {
        let size = sink.size();
        let get = build_get(polygon, size.height)?;
        let Some(first) = get.first() else {
            return Ok(());
        };
        let mut aet = Vec::new();
        let mut merged = Vec::new();
        for table in [&mut aet, &mut merged] {
            table.try_reserve_exact(get.len()).map_err(|_| Refusal::OutOfMemory)?;
        }
        let mut next = 0;
        let mut y = first.start_y;
        while (next < get.len() || !aet.is_empty()) && y < size.height {
            move_x_sorted_to_aet(&get, &mut next, &mut aet, &mut merged, y);
            scan_out_aet(&aet, y, polygon.color, size.width, sink);
            advance_aet(&mut aet);
            x_sort_aet(&mut aet);
            y += 1;
        }
        Ok(())
    }
}

/// Listing 40.1's `EdgeState`, without `NextEdge`: `X`, `WholePixelXMove`,
/// `XDirection` and the error terms live in `step`.
#[derive(Clone, Copy, Debug)]
struct EdgeState {
    start_y: i32,
    /// Scan lines left, the current one included.
    count: i32,
    step: ErrorTermStep,
}

/// `BuildGET`: every edge of every contour with some height, running top to
/// bottom, limited to the target's rows `0..height`, in GET order.
fn build_get(polygon: &Polygon, height: i32) -> Result<Vec<EdgeState>, Refusal> {
    let mut get = Vec::new();
    get.try_reserve_exact(polygon.vertex_count()).map_err(|_| Refusal::OutOfMemory)?;
    for contour in polygon.contours.iter().filter(|c| c.len() >= 3) {
        // Edge i runs from vertex i to vertex i - 1, vertex 0 to the last.
        for (i, start) in contour.iter().enumerate() {
            let end = if i == 0 { contour[contour.len() - 1] } else { contour[i - 1] };
            let (mut top, mut bottom) = (start.round_to_pixel(), end.round_to_pixel());
            if top.y > bottom.y {
                core::mem::swap(&mut top, &mut bottom);
            }
            let delta_y = bottom.y - top.y;
            if delta_y == 0 || top.y >= height || bottom.y <= 0 {
                continue;
            }
            let delta_x = bottom.x - top.x;
            let width = delta_x.abs();
            let (whole, adj_up) = if delta_y >= width {
                // Y-major, diagonal included.
                (0, width)
            } else {
                ((width / delta_y) * if delta_x > 0 { 1 } else { -1 }, width % delta_y)
            };
            let mut edge = EdgeState {
                start_y: top.y,
                count: delta_y,
                step: ErrorTermStep::new(top.x, delta_x, delta_y, whole, adj_up),
            };
            if top.y < 0 {
                edge.step.skip(i64::from(-top.y));
                edge.count += top.y;
                edge.start_y = 0;
            }
            get.push(edge);
        }
    }
    // The book inserts each edge before the first with a larger StartY, or
    // the same StartY and an X at least its own: a stable sort of the edges
    // in reverse order gives the same list.
    get.reverse();
    get.sort_by_key(|edge| (edge.start_y, edge.step.x));
    Ok(get)
}

/// `MoveXSortedToAET`: the GET edges starting on line `y` (the next ones,
/// X-sorted) join the AET, each before the first AET edge with X at least
/// its own, the search going on from the last insertion: one merging pass
/// into `merged`, which then becomes the AET.
fn move_x_sorted_to_aet(
    get: &[EdgeState],
    next: &mut usize,
    aet: &mut Vec<EdgeState>,
    merged: &mut Vec<EdgeState>,
    y: i32,
) {
    let first = *next;
    while get.get(*next).is_some_and(|edge| edge.start_y == y) {
        *next += 1;
    }
    if first == *next {
        return;
    }
    merged.clear();
    let mut active = aet.iter().copied().peekable();
    for &edge in &get[first..*next] {
        while let Some(before) = active.next_if(|e| e.step.x < edge.step.x) {
            merged.push(before);
        }
        merged.push(edge);
    }
    merged.extend(active);
    core::mem::swap(aet, merged);
}

/// `ScanOutAET`: for each pair of crossings, `DrawHorizontalLineSeg(y,
/// left.X, right.X - 1)`, clipped to the target. Closed contours always give
/// pairs; an odd edge out would be the book's null dereference, and is left
/// alone here.
fn scan_out_aet<S: SpanSink + ?Sized>(aet: &[EdgeState], y: i32, color: u8, width: i32, sink: &mut S) {
    for [left, right] in aet.as_chunks::<2>().0 {
        let (x_start, x_end) = (left.step.x.max(0), right.step.x.min(width));
        if x_start < x_end {
            sink.span(y, x_start, x_end, color);
        }
    }
}

/// `AdvanceAET`: counts off a line for each edge, drops the finished ones
/// and steps the others' X.
fn advance_aet(aet: &mut Vec<EdgeState>) {
    aet.retain_mut(|edge| {
        edge.count -= 1;
        if edge.count == 0 {
            return false;
        }
        edge.step.step();
        true
    });
}

/// `XSortAET`: the book's bubble sort, swapping neighbours whose X values
/// are out of order until a pass swaps nothing; equal X values keep their
/// order. Cheap because X coherence leaves the AET nearly sorted.
fn x_sort_aet(aet: &mut [EdgeState]) {
    let mut swap_occurred = true;
    while swap_occurred {
        swap_occurred = false;
        for i in 1..aet.len() {
            if aet[i - 1].step.x > aet[i].step.x {
                aet.swap(i - 1, i);
                swap_occurred = true;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Point;
    use crate::methods::test_support::{assert_clipping_changes_no_pixel, empty, fill, full, SMALL};

    /// A polygon of whole-pixel `contours`.
    fn polygon(contours: &[&[(i32, i32)]]) -> Polygon {
        let contours = contours.iter().map(|c| c.iter().map(|&(x, y)| Point::from_pixels(x, y)).collect()).collect();
        Polygon { contours, color: 1, rule: FillRule::EvenOdd }
    }

    /// The picture of `contours` (whole pixels) filled into [`SMALL`].
    fn draw(contours: &[&[(i32, i32)]]) -> alloc::string::String {
        fill(&AbrashAet, &polygon(contours), SMALL).ascii()
    }

    #[test]
    fn triangle_keeps_left_and_top_and_drops_right_and_bottom() {
        // Row 1 meets the left edge at x=2 (drawn) and the right at x=4 (not);
        // the pointed top's row 0 pairs two crossings at x=3 and draws nothing.
        let picture = draw(&[&[(3, 0), (6, 3), (0, 3)]]);
        assert_eq!(picture, "........\n..##....\n.####...\n........\n........\n........\n");
    }

    #[test]
    fn bridge_edges_cut_a_hole_as_in_listing_40_4() {
        // Polygon2 of Listing 40.4 in small: in along (0,0)-(2,2), round the
        // hole, and back out along the same edge.
        let rectangle_with_hole = [(0, 0), (8, 0), (8, 6), (0, 6), (0, 0), (2, 2), (6, 2), (6, 4), (2, 4), (2, 2)];
        let picture = draw(&[&rectangle_with_hole]);
        assert_eq!(picture, "########\n########\n##....##\n##....##\n########\n########\n");
    }

    #[test]
    fn overlapping_contours_cancel_under_odd_even() {
        let a: &[(i32, i32)] = &[(0, 0), (5, 0), (5, 4), (0, 4)];
        let b: &[(i32, i32)] = &[(3, 2), (8, 2), (8, 6), (3, 6)];
        let picture = draw(&[a, b]);
        assert_eq!(picture, "#####...\n#####...\n###..###\n###..###\n...#####\n...#####\n");
    }

    #[test]
    fn self_intersecting_bowtie_fills_both_lobes() {
        // The diagonals cross at (4,3). Row 1 meets them at ceil(4/3) = 2 and
        // 8 - floor(4/3) = 7: the left lobe gets x 0-1 (its right crossing is
        // out), the right lobe x 7 only (its right side is the edge at 8).
        let picture = draw(&[&[(0, 0), (8, 6), (8, 0), (0, 6)]]);
        assert_eq!(picture, "........\n##.....#\n###...##\n########\n###...##\n##.....#\n");
    }

    #[test]
    fn get_ties_go_in_front_as_the_books_insertion_puts_them() {
        // Two edges start at (2,0): the contour's edge 1 (vertex 1 to 0) and
        // edge 2 (vertex 2 to 1) are built in that order; the book inserts
        // edge 2 before edge 1.
        let kite = polygon(&[&[(0, 3), (2, 0), (4, 3), (0, 6)]]);
        let get = build_get(&kite, 10).unwrap();
        let heads: Vec<(i32, i32, i32)> = get.iter().map(|e| (e.start_y, e.step.x, e.step.direction)).collect();
        assert_eq!(heads, [(0, 2, 1), (0, 2, -1), (3, 0, -1), (3, 4, -1)]);
    }

    #[test]
    fn clipping_changes_no_pixel() {
        // Listing 40.4's Polygon1 and Polygon3 stretched tall, and a ring of
        // two contours, drawn whole and with their first 1000 rows above.
        let tall = |points: &[(i32, i32)]| -> Vec<(i32, i32)> { points.iter().map(|&(x, y)| (x, y * 9)).collect() };
        let polygon1 = tall(&[(0, 0), (100, 150), (320, 0), (0, 200), (220, 50), (320, 200)]);
        #[rustfmt::skip]
        let polygon3 = tall(&[
            (0, 0), (10, 0), (105, 185), (260, 30), (15, 150), (5, 150), (5, 140), (260, 5), (300, 5), (300, 15),
            (110, 200), (100, 200), (0, 10),
        ]);
        let outer: &[(i32, i32)] = &[(-500, 0), (900, 300), (300, 1900)];
        let inner: &[(i32, i32)] = &[(100, 500), (200, 1300), (250, 900)];
        let shapes: [&[&[(i32, i32)]]; 3] = [&[&polygon1], &[&polygon3], &[outer, inner]];
        for shape in shapes {
            assert_clipping_changes_no_pixel(&AbrashAet, &polygon(shape));
        }
    }

    #[test]
    fn huge_and_off_screen_polygons_are_clipped() {
        let big = 1 << 22;
        assert_eq!(draw(&[&[(-big, -big), (big, -big), (big, big), (-big, big)]]), full());
        assert_eq!(draw(&[&[(100, 100), (120, 100), (120, 120)], &[(0, -9), (5, -9), (5, -1)]]), empty());
    }
}
