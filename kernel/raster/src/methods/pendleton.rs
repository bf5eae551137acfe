//! `pendleton`: Bob Pendleton's edge-table renderer, `poly()` with
//! `edge()`, `span()` and `adjust()`, from his article "Drawing Polygons"
//! (the 2D versions of its listings; `docs/methods.md#pendleton`).
//!
//! - Convention: pixel centres `(X + 0.5, Y + 0.5)`. `adjust()` rounds a
//!   coordinate to the nearest integer, halves up, so an edge covers the rows
//!   whose centre line `yc` has `top < yc <= bottom`, and a span the pixels
//!   whose centre `xc` has `left < xc <= right`: exact ties go down and
//!   right. (The text states "top and left in, bottom and right out"; the
//!   code gives that for the far more common untied case only. Ties need a
//!   vertex or crossing at an exact half pixel.) The crossing stored for a
//!   row is not the edge's X on that row's centre line: `edge()` puts the
//!   top vertex's X on the edge's first row and steps `(x2 - x1) / max(2,
//!   idy - 1)` a row (the "kluge" of the text), so an edge of three rows or
//!   more ends on the bottom vertex's X, though that vertex lies up to a
//!   row below the last centre line (and the top one up to a row above the
//!   first).
//! - Arithmetic: `fp14`, 32 bits with 14 fraction bits. Vertices come in
//!   exactly (1/256 pixel is 64 fp14 units); the X step is an fp14 quotient
//!   truncated toward zero, so X lags toward the top vertex's by less than
//!   one fp14 unit (1/16384 pixel) a row.
//! - Classes: one contour with one top and one bottom extreme: convex, and
//!   the concave or self-intersecting polygons that are monotone in y, as
//!   the text says (`span()` orders each pair). Other polygons get whatever
//!   the two tables hold, within the target.
//!
//! The seed does not include its `fixed.h`, so its operations are chosen
//! here: `int2fp` is `<< 14`; `fp2int` is `>> 14`, an arithmetic shift
//! that floors (the text converts "with one shift"); `fpFract` is the low
//! 14 bits, the fraction above the floor; `fpDiv(a, b)` is `(a << 14) / b`
//! through a 64-bit intermediate, truncating toward zero as C's `/` does
//! (in `edge()` that is exactly `(x2 - x1) / idy` truncated). With these,
//! `adjust()`'s one-bit nudge off a scan-line centre never changes its
//! result: a value whose fraction is exactly one half rounds up with or
//! without it. It is kept because the seed has it.
//!
//! Range: coordinates must lie in `-32768..32768` pixels, or the polygon is
//! refused with [`Refusal::OutOfRange`]. There every fp14 value (at most
//! 2^29 in size), every difference of two and `int2fp(idy)` fit in 32 bits;
//! beyond it the original's arithmetic would overflow.
//!
//! Safety changes, none of which moves a pixel the original draws: the two
//! edge tables hold only the target's rows (the original's are `HEIGHT`
//! entries indexed by scan line, written out of bounds by a polygon that
//! reaches off the screen), an edge starting above them starts at the first
//! one with the X its stepping would have there, and `span()` writes one
//! clipped span instead of one pixel at a time.

use alloc::vec;
use alloc::vec::Vec;

use crate::classify::Class;
use crate::geometry::{FillRule, Point, Polygon, SUBPIXEL_BITS};
use crate::methods::info::{Heap, MethodInfo, Refusal};
use crate::methods::interface::Builtin;
use crate::reference::Convention;
use crate::target::SpanSink;

/// `poly()` and its helpers.
pub struct Pendleton;

static INFO: MethodInfo = MethodInfo {
    name: "pendleton",
    source: "Pendleton, \"Drawing Polygons\": poly, edge, span, adjust",
    convention: Convention {
        sample_x: 128,
        sample_y: 128,
        summary: "pixel centres; rows with top < centre <= bottom, pixels with left < centre <= right; \
                  row crossings stepped from the top vertex's X by (x2 - x1) / max(2, rows - 1)",
    },
    numeric: "fp14 (32-bit, 14 fraction bits), truncated X step; coordinates within ±32768 px",
    handles: Class::Convex,
    rules: &[FillRule::EvenOdd, FillRule::NonZero],
    heap: Heap::EveryPolygon,
};

impl Builtin for Pendleton {
    const INFO: &'static MethodInfo = &INFO;

    fn fill_into<S: SpanSink + ?Sized>(&self, polygon: &Polygon, sink: &mut S) -> Result<(), Refusal> {
        let contour = polygon.single_contour().ok_or(Refusal::MultipleContours)?;
        let points =
            contour.iter().map(|&p| FpPoint::from_point(p)).collect::<Option<Vec<_>>>().ok_or(Refusal::OutOfRange)?;
        poly(polygon.color, &points, sink);
        Ok(())
    }
}

/// A value in Pendleton's `fp14` format: 32 bits, 14 of them fraction.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
struct Fp14(i32);

impl Fp14 {
    const FRACTION_BITS: u32 = 14;
    /// `fpHalf`.
    const HALF: i32 = 1 << (Self::FRACTION_BITS - 1);
    /// Subpixel coordinates accepted: `-2^23..2^23`, that is -32768..32768
    /// pixels, or fp14 values of at most 2^29 in size.
    const LIMIT_SUBPIXELS: i32 = 1 << 23;

    /// A [`Point`] coordinate, exactly, if within the accepted range.
    fn from_subpixels(v: i32) -> Option<Self> {
        (-Self::LIMIT_SUBPIXELS..Self::LIMIT_SUBPIXELS)
            .contains(&v)
            .then_some(Self(v << (Self::FRACTION_BITS - SUBPIXEL_BITS)))
    }

    /// `int2fp`.
    fn from_int(v: i32) -> Self {
        Self(v << Self::FRACTION_BITS)
    }

    /// `fp2int`: floors.
    fn to_int(self) -> i32 {
        self.0 >> Self::FRACTION_BITS
    }

    /// `fpFract`: the fraction above the floor.
    fn fract(self) -> i32 {
        self.0 & ((1 << Self::FRACTION_BITS) - 1)
    }

    /// `fpDiv`: truncates toward zero. `edge()` divides by `int2fp(idy)`
    /// with `idy >= 2`, so the quotient is at most half the dividend.
    fn div(self, divisor: Self) -> Self {
        Self(((i64::from(self.0) << Self::FRACTION_BITS) / i64::from(divisor.0)) as i32)
    }
}

/// The seed's `point`.
#[derive(Clone, Copy, Debug)]
struct FpPoint {
    x: Fp14,
    y: Fp14,
}

impl FpPoint {
    fn from_point(p: Point) -> Option<Self> {
        Some(Self { x: Fp14::from_subpixels(p.x)?, y: Fp14::from_subpixels(p.y)? })
    }
}

/// `adjust()`: nudges a value lying exactly on a scan-line (or pixel) centre
/// one bit down, then rounds it to the nearest integer.
fn adjust(val: Fp14) -> i32 {
    let mut val = val.0;
    if Fp14(val).fract() == Fp14::HALF {
        val += 1;
    }
    Fp14(val + Fp14::HALF).to_int()
}

/// One of `poly()`'s edge tables (`table1`, `table2`): the crossing X of
/// each of the target's rows `first_row..first_row + x.len()` that lie
/// between the polygon's extremes.
struct EdgeTable {
    first_row: i32,
    x: Vec<Fp14>,
}

/// `edge()`: stores the crossing X of the edge `pt1`-`pt2` for its rows
/// `adjust(top)..adjust(bottom)` that `table` holds.
fn edge(table: &mut EdgeTable, mut pt1: FpPoint, mut pt2: FpPoint) {
    if pt2.y < pt1.y {
        core::mem::swap(&mut pt1, &mut pt2);
    }
    let iy1 = adjust(pt1.y);
    let iy2 = adjust(pt2.y);
    let idy = iy2 - iy1;
    if idy == 0 {
        return;
    }
    let idy = 2.max(idy - 1);
    let dx = Fp14(pt2.x.0 - pt1.x.0).div(Fp14::from_int(idy));

    // The original starts with `x = pt1->x` on row `iy1` and steps `x += dx`
    // a row; X on the first row the table holds is taken by multiplying
    // instead, which is exact. No step overflows: X stays between the two
    // vertices' values, and one step beyond after the last row.
    let end_row = table.first_row + table.x.len() as i32;
    let rows = iy1.max(table.first_row)..iy2.min(end_row);
    let mut x = Fp14((i64::from(pt1.x.0) + i64::from(rows.start - iy1) * i64::from(dx.0)) as i32);
    for row in rows {
        table.x[(row - table.first_row) as usize] = x;
        x = Fp14(x.0 + dx.0);
    }
}

/// `span()`: fills row `y` from one crossing to the other, the pixels
/// `adjust(left)..adjust(right)`, clipped to the target's `width`.
fn span<S: SpanSink + ?Sized>(sink: &mut S, color: u8, y: i32, mut x1: Fp14, mut x2: Fp14, width: i32) {
    if x2 < x1 {
        core::mem::swap(&mut x1, &mut x2);
    }
    let ix1 = adjust(x1);
    let ix2 = adjust(x2);
    if ix2 - ix1 == 0 {
        return;
    }
    let (x_start, x_end) = (ix1.max(0), ix2.min(width));
    if x_start < x_end {
        sink.span(y, x_start, x_end, color);
    }
}

/// `poly()`: finds the top and bottom extremes, fills `table1` along the
/// vertices from the top forward to the bottom and `table2` from the bottom
/// forward to the top, then spans each row between them.
fn poly<S: SpanSink + ?Sized>(color: u8, pnts: &[FpPoint], sink: &mut S) {
    let n = pnts.len();
    if n < 3 {
        return;
    }
    let (mut maxy, mut miny) = (pnts[0].y, pnts[0].y);
    let (mut imaxy, mut iminy) = (0, 0);
    for (i, p) in pnts.iter().enumerate().skip(1) {
        if p.y > maxy {
            maxy = p.y;
            imaxy = i;
        }
        if p.y < miny {
            miny = p.y;
            iminy = i;
        }
    }
    let iy1 = adjust(miny);
    let iy2 = adjust(maxy);
    if iy1 == iy2 {
        return;
    }

    let size = sink.size();
    let (first_row, end_row) = (iy1.max(0), iy2.min(size.height));
    if first_row >= end_row {
        return;
    }
    // Each chain runs from one extreme to the other and `adjust()` never
    // decreases, so both write every row between `iy1` and `iy2`: the
    // initial values are never read.
    let rows = (end_row - first_row) as usize;
    let mut table1 = EdgeTable { first_row, x: vec![Fp14(0); rows] };
    let mut table2 = EdgeTable { first_row, x: vec![Fp14(0); rows] };

    let next = |i: usize| if i + 1 >= n { 0 } else { i + 1 };
    for (table, from, to) in [(&mut table1, iminy, imaxy), (&mut table2, imaxy, iminy)] {
        let mut pnt1 = from;
        loop {
            let pnt2 = next(pnt1);
            edge(table, pnts[pnt1], pnts[pnt2]);
            pnt1 = pnt2;
            if pnt1 == to {
                break;
            }
        }
    }

    for (i, (&x1, &x2)) in table1.x.iter().zip(&table2.x).enumerate() {
        span(sink, color, first_row + i as i32, x1, x2, size.width);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::coverage::CoverageSink;
    use crate::methods::interface::Method;
    use crate::methods::test_support::{
        assert_clipping_changes_no_pixel, draw, empty, fill, full, SMALL, TALL_TRIANGLES,
    };

    /// The picture of a polygon from coordinates in half pixels.
    fn draw_halves(points: &[(i32, i32)]) -> alloc::string::String {
        let polygon = Polygon::new(points.iter().map(|&(x, y)| Point::new(x * 128, y * 128)).collect(), 1);
        fill(&Pendleton, &polygon, SMALL).ascii()
    }

    #[test]
    fn rectangle_on_pixel_corners_covers_its_pixels() {
        let picture = draw(&Pendleton, &[(1, 1), (5, 1), (5, 4), (1, 4)]);
        assert_eq!(picture, "........\n.####...\n.####...\n.####...\n........\n........\n");
    }

    #[test]
    fn crossings_spread_from_vertex_to_vertex_and_ties_go_right() {
        // Edges (3,0)-(6,3) and (3,0)-(0,3) cover rows 0-2. With the divisor
        // max(2, 3 - 1) = 2 they store X 3, 4.5, 6 and 3, 1.5, 0: the
        // vertices' X, not the centre-line crossings 3.5, 4.5, 5.5. On row 1
        // the ends tie with pixel centres 1.5 (out) and 4.5 (in); row 2
        // reaches the bottom vertices' full width.
        let picture = draw(&Pendleton, &[(3, 0), (6, 3), (0, 3)]);
        assert_eq!(picture, "........\n..###...\n######..\n........\n........\n........\n");
    }

    #[test]
    fn rows_tied_with_a_vertex_go_down() {
        // A rectangle from y 0.5 to 3.5: centre line 0.5 is out, 3.5 in.
        let picture = draw_halves(&[(2, 1), (10, 1), (10, 7), (2, 7)]);
        assert_eq!(picture, "........\n.####...\n.####...\n.####...\n........\n........\n");
    }

    #[test]
    fn monotone_hourglass_crosses_over_as_span_orders_each_pair() {
        // One top and one bottom extreme, edges crossing at (4,3). The first
        // and last rows take the vertices' X, so both are full width.
        let picture = draw(&Pendleton, &[(0, 0), (8, 0), (0, 6), (8, 6)]);
        assert_eq!(picture, "########\n..####..\n...##...\n...##...\n..####..\n########\n");
    }

    #[test]
    fn adjust_rounds_halves_up_with_or_without_its_nudge() {
        for v in -3 * (1 << 14)..3 * (1 << 14) {
            assert_eq!(adjust(Fp14(v)), (v + Fp14::HALF) >> 14, "{v}");
        }
    }

    #[test]
    fn fp_div_truncates_toward_zero() {
        let third = Fp14::from_int(-1).div(Fp14::from_int(3));
        assert_eq!(third, Fp14(-5461));
        assert_eq!(Fp14(7).div(Fp14::from_int(2)), Fp14(3));
    }

    #[test]
    fn clipping_changes_no_pixel() {
        for triangle in TALL_TRIANGLES {
            assert_clipping_changes_no_pixel(&Pendleton, &Polygon::from_pixels(triangle, (0, 0), 1));
        }
    }

    #[test]
    fn huge_polygons_are_clipped_within_range_and_refused_beyond() {
        let big = 32767;
        assert_eq!(draw(&Pendleton, &[(-big, -big), (big, -big), (big, big), (-big, big)]), full());
        assert_eq!(draw(&Pendleton, &[(100, 100), (120, 100), (120, 120)]), empty());
        let too_far = Polygon::from_pixels(&[(0, 0), (32768, 0), (0, 5)], (0, 0), 1);
        assert_eq!(Pendleton.fill(&too_far, &mut CoverageSink::new(SMALL)), Err(Refusal::OutOfRange));
    }
}
