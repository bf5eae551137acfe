//! Edges as the exact method steps them, the first stage of its every path:
//! where pixels are sampled, and on each scan line an edge meets the first
//! pixel column whose centre lies at or right of it, kept exact from row to
//! row by an integer error term (a DDA in the manner of Abrash's chapter 39
//! `ScanEdge`, with a denominator wide enough for any `i32` vertex) or, for
//! short edges, a fixed-point crossing. Nothing here knows the target:
//! that is `clip.rs`'s.

use crate::geometry::{Point, SUBPIXEL_BITS, SUBPIXEL_ONE};

/// Where a pixel is sampled, in subpixels from its top-left corner on both
/// axes: the centre (`docs/conventions.md#pixels-and-sample-points`).
pub(super) const SAMPLE_OFFSET: i32 = SUBPIXEL_ONE / 2;

/// The first pixel index, on either axis, whose sample lies at or after the
/// subpixel coordinate `v`: `ceil((v - SAMPLE_OFFSET) / SUBPIXEL_ONE)`.
/// An arithmetic shift is a floor, so adding `SUBPIXEL_ONE - 1` turns it
/// into the ceiling.
#[inline(always)]
pub(super) fn first_sample_at_or_after(v: i64) -> i64 {
    (v - i64::from(SAMPLE_OFFSET) + i64::from(SUBPIXEL_ONE) - 1) >> SUBPIXEL_BITS
}

/// An edge walking down the scan lines it meets.
///
/// On the current row the edge crosses the sample line at the rational
/// `X = x_top + (ys - y_top) * dx / dy`; `column` is the first pixel whose
/// centre is at or right of `X` (so the crossing counts for that pixel and
/// every pixel right of it). With `D = SUBPIXEL_ONE * dy` and
/// `N = (x_top - SAMPLE_OFFSET) * dy + (ys - y_top) * dx`, `column` is
/// `ceil(N / D)` and `error = column * D - N`, in `0..D`. The next row adds
/// `SUBPIXEL_ONE * dx` to `N`: `column` moves by its floor quotient and
/// `error` by its remainder, with one carry.
///
/// Magnitudes for any `i32` vertices: `dy < 2^32`, so `D < 2^40`; `N` needs
/// 66 bits in general. [`EdgeStepper::at_row`] forms it in `i64` when the
/// edge is shorter than 2^31 subpixels both ways (every edge of a polygon
/// within 2^23 pixels, the screen's included) and in `i128` otherwise; the
/// two give the same stepper. `column` stays within a pixel of the edge's
/// own x range (below 2^24 in size) on every row the edge meets, and moves
/// at most `|dx| / dy + 1 < 2^33` per step, so it fits an `i64` even a step
/// past the edge's last row, where the fills leave it unused.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct EdgeStepper {
    /// First pixel column at or right of the crossing on the current row.
    pub column: i64,
    /// `column * denominator - N`: how far that pixel's centre lies right
    /// of the crossing, in `1 / denominator` pixels.
    error: i64,
    /// Whole columns the crossing moves per row: `floor(dx / dy)`.
    column_step: i64,
    /// What the whole step leaves over: `SUBPIXEL_ONE * dx mod denominator`.
    error_step: i64,
    /// `SUBPIXEL_ONE * dy`.
    denominator: i64,
}

/// Edges shorter than this (in subpixels) on both axes take the `i64` setup.
const NARROW: u64 = 1 << 31;

impl EdgeStepper {
    /// The edge from `top` down to `bottom` on scan line `row`, which it
    /// must meet (`top.y < bottom.y`, `row` in its rows).
    #[inline]
    pub fn at_row(top: Point, bottom: Point, row: i64) -> Self {
        Self::new(top, bottom, row, true)
    }

    /// [`EdgeStepper::at_row`] when `row` is the last row the edge meets
    /// that will be read: `column` is exact there, and stepping leaves it
    /// as it is. Saves the step's division, most of the setup of an edge
    /// that meets one row only (polygons of many vertices have many).
    #[inline]
    pub fn at_last_row(top: Point, bottom: Point, row: i64) -> Self {
        Self::new(top, bottom, row, false)
    }

    #[inline(always)]
    fn new(top: Point, bottom: Point, row: i64, stepped: bool) -> Self {
        let (dx, dy) = (i64::from(bottom.x) - i64::from(top.x), i64::from(bottom.y) - i64::from(top.y));
        let mut stepper = if dx.unsigned_abs() < NARROW && dy.unsigned_abs() < NARROW {
            Self::narrow(top, dx, dy, row, stepped)
        } else {
            Self::wide(top, dx, dy, row)
        };
        if !stepped {
            (stepper.column_step, stepper.error_step) = (0, 0);
        }
        stepper
    }

    /// [`EdgeStepper::at_row`] for `|dx|, dy < 2^31`, in `i64`, with one
    /// 32-bit division on the edge's first row and two divisions on a later
    /// one. Without `stepped`, the step is left zero.
    ///
    /// Split `x_top - SAMPLE_OFFSET = SUBPIXEL_ONE * q + f - SAMPLE_OFFSET`
    /// with `f` in `0..SUBPIXEL_ONE`: `N = q * D + n` with
    /// `n = (f - SAMPLE_OFFSET) * dy + t * dx` and `t = ys - y_top`, so
    /// `ceil(N / D) = q + ceil(n / D)` and the error `column * D - N` is
    /// `ceil(n / D) * D - n`. The row meets the edge, so `0 <= t < dy`:
    /// `|n| < 2^7 * 2^31 + 2^31 * 2^31 < 2^63`, and `D < 2^39`.
    ///
    /// On the first row, `t < SUBPIXEL_ONE`, and the step's division gives
    /// the start too: with `dx = s * dy + r` (`0 <= r < dy`),
    /// `n = a * dy + t * r` where `a = f - SAMPLE_OFFSET + t * s`; with
    /// `a = SUBPIXEL_ONE * a1 + a0` (`0 <= a0 < SUBPIXEL_ONE`),
    /// `n = a1 * D + m` where `m = a0 * dy + t * r` lies in `0..2 * D`, so
    /// `ceil(n / D)` is `a1` plus 0, 1 or 2, as `m` is 0, at most `D`, or
    /// more. (`|a| < 2^8 * 2^31`, `m < 2^40`.)
    #[inline(always)]
    fn narrow(top: Point, dx: i64, dy: i64, row: i64, stepped: bool) -> Self {
        let one = i64::from(SUBPIXEL_ONE);
        let t = row * one + i64::from(SAMPLE_OFFSET) - i64::from(top.y);
        let x = i64::from(top.x);
        let (q, f) = (x >> SUBPIXEL_BITS, x & (one - 1));
        let denominator = one * dy;
        // `dx, dy` fit `i32` and `dy > 0`: one 32-bit division, no overflow.
        let (dx32, dy32) = (dx as i32, dy as i32);
        let (column_step, remainder) = (i64::from(dx32.div_euclid(dy32)), i64::from(dx32.rem_euclid(dy32)));
        if stepped && t < one {
            let a = f - i64::from(SAMPLE_OFFSET) + t * column_step;
            let m = (a & (one - 1)) * dy + t * remainder;
            let up = i64::from(m > 0) + i64::from(m > denominator);
            let column = q + (a >> SUBPIXEL_BITS) + up;
            return Self { column, error: up * denominator - m, column_step, error_step: one * remainder, denominator };
        }
        let n = (f - i64::from(SAMPLE_OFFSET)) * dy + t * dx;
        // One truncating division: `n = quotient * D + remainder`, the
        // remainder of `n`'s sign; the ceiling adds one for a positive one.
        let (quotient, rest) = (n / denominator, n % denominator);
        let (up, error) = if rest > 0 { (1, denominator - rest) } else { (0, -rest) };
        let (column_step, error_step) = if stepped { (column_step, one * remainder) } else { (0, 0) };
        Self { column: q + quotient + up, error, column_step, error_step, denominator }
    }

    /// [`EdgeStepper::at_row`] for any `i32` edge: `N` in `i128`.
    #[cold]
    #[inline(never)]
    fn wide(top: Point, dx: i64, dy: i64, row: i64) -> Self {
        let one = i64::from(SUBPIXEL_ONE);
        let sample_y = row * one + i64::from(SAMPLE_OFFSET);
        let denominator = one * dy;
        let numerator = i128::from(i64::from(top.x) - i64::from(SAMPLE_OFFSET)) * i128::from(dy)
            + i128::from(sample_y - i64::from(top.y)) * i128::from(dx);
        let column = ceil_div(numerator, denominator.into());
        let advance = one * dx;
        Self {
            column: column as i64,
            error: (column * i128::from(denominator) - numerator) as i64,
            column_step: advance.div_euclid(denominator),
            error_step: advance.rem_euclid(denominator),
            denominator,
        }
    }

    /// Moves to the next scan line. Branch-free: the carry is as likely as
    /// not on a random slope, so a branch would be mispredicted half the
    /// time. `error` and `error_step` are in `0..D`, so the difference is in
    /// `-D..D`, and below zero exactly on a carry.
    #[inline(always)]
    pub fn step(&mut self) {
        let error = self.error - self.error_step;
        let carry = error < 0;
        self.error = core::hint::select_unpredictable(carry, error + self.denominator, error);
        self.column += self.column_step + i64::from(carry);
    }
}

/// What the row loops need of an edge: its crossing column on the current
/// row, and the move to the next row.
pub(super) trait Crossing: Copy + Default + core::fmt::Debug {
    /// The edge from `top` down to `bottom` on scan line `row`, which it
    /// must meet.
    fn at_row(top: Point, bottom: Point, row: i64) -> Self;
    /// [`Crossing::at_row`] when `row` is the last row the edge meets that
    /// will be read, where a setup may skip the step.
    #[inline(always)]
    fn at_last_row(top: Point, bottom: Point, row: i64) -> Self {
        Self::at_row(top, bottom, row)
    }
    /// First pixel column at or right of the crossing on the current row.
    fn column(&self) -> i64;
    /// Moves to the next scan line.
    fn step(&mut self);
    /// Where the crossing is `rows` scan lines below the current (a row the
    /// edge meets), as a number that orders crossings: of two edges, the
    /// one with the smaller number there has the column never right of
    /// the other's, and the number moves linearly with the row. `None`
    /// where the stepper cannot tell without stepping there.
    #[inline(always)]
    fn position_in(&self, _rows: i64) -> Option<i64> {
        None
    }
}

impl Crossing for EdgeStepper {
    #[inline(always)]
    fn at_row(top: Point, bottom: Point, row: i64) -> Self {
        EdgeStepper::at_row(top, bottom, row)
    }

    #[inline(always)]
    fn at_last_row(top: Point, bottom: Point, row: i64) -> Self {
        EdgeStepper::at_last_row(top, bottom, row)
    }

    #[inline(always)]
    fn column(&self) -> i64 {
        self.column
    }

    #[inline(always)]
    fn step(&mut self) {
        EdgeStepper::step(self)
    }
}

/// `ceil(a / b)` for `b` in `1..=2^17` and `|a| < 2^53`, on a machine
/// with a floating-point unit, where one `f64` division is several times
/// quicker than an `i64` one (Skylake's `idiv` takes 42 to 95 cycles,
/// `divsd` 13 to 14). The `f64` quotient only estimates; the result is
/// decided in integers. Both operands convert exactly, and every integer
/// under 2^53 is an `f64`: the correctly rounded quotient of `x = a / b`
/// therefore lies between `floor(x)` and `ceil(x)`, both included, and
/// truncating it towards zero gives one of the two, `q`. The remainder
/// `a - q * b` (no overflow: `|q * b| < |a| + b`) is positive exactly when
/// `q` is the floor of a quotient that is not whole.
#[cfg(not(target_os = "none"))]
#[inline(always)]
fn ceil_quotient(a: i64, b: i64) -> i64 {
    let q = (a as f64 / b as f64) as i64;
    let r = a - q * b;
    q + i64::from(r > 0)
}

/// [`ceil_quotient`] in the kernel, whose target has no floating point: an
/// `i64` division, whose truncated quotient is the ceiling less one where
/// a positive remainder is left.
#[cfg(target_os = "none")]
#[inline(always)]
fn ceil_quotient(a: i64, b: i64) -> i64 {
    a / b + i64::from(a % b > 0)
}

/// Fractional bits of [`ShortEdge::position`].
const FRACTION_BITS: u32 = 35;

/// A [`ShortEdge`] takes edges shorter than this, in subpixels (512 px),
/// on both axes: [`ShortEdge::fits`].
const SHORT: i64 = 1 << 17;

/// An edge shorter than 512 px both ways, walked with one fixed-point
/// accumulator instead of a column and an error term: a row costs one
/// addition, and the column is a shift. Exact, as the bound below shows.
///
/// In pixels, the crossing on a row is at `u = (x_top - SAMPLE_OFFSET) /
/// 256 + t * dx / (256 * dy)` with `t = ys - y_top`, a multiple of `1 / D`
/// (`D = 256 * dy`), and the column is `ceil(u)`. `position` holds, in
/// units of `2^-35` px, `u + e + 1 - 2^-25`, where `e` (the rounding) is
/// at least zero and below `2^-25`: then its floor is `ceil(u)`. Write
/// `u = m - j / D` with `m = ceil(u)` and `0 <= j < D`; as `D <= 2^25`,
/// `u + 1 - 2^-25 >= m - (D - 1) / D + 1 - 1 / D = m`, and
/// `u + e + 1 - 2^-25 < m + 1` as `e < 2^-25`.
///
/// The step is `S = ceil(dx * 2^35 / dy)`, at most one unit above the exact
/// one, and the first row's position is the exact
/// `(x_top - SAMPLE_OFFSET) * 2^27` plus `ceil(t * S / 256)`, under
/// `1 + t / 256` units above the exact; `r` rows later the excess is under
/// `1 + (t + 256 r) / 256` units, and `t + 256 r < dy < 2^17` on every row
/// the edge meets: under `2^10` units, `2^-25` px.
///
/// Magnitudes: `|dx|, dy < 2^17`, so `|S| <= 2^52`, and `|t * S| < 2^53` as
/// `t < dy`; `x_top * 2^27` is below `2^58` for any `i32`, and the position
/// stays within a pixel of the edge's x range (in `i32`) on its rows, or a
/// step past them: under `2^59` in size, so no `i64` overflows.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct ShortEdge {
    /// The crossing, rounded up, plus `1 - 2^-25` px, in `2^-35` px.
    position: i64,
    /// What a row adds to `position`: `ceil(dx * 2^35 / dy)`.
    step: i64,
}

impl ShortEdge {
    /// Whether every edge between points in `x_range` and `y_range`
    /// (inclusive) may be a [`ShortEdge`].
    #[inline(always)]
    pub fn fits((min_x, max_x): (i32, i32), (min_y, max_y): (i32, i32)) -> bool {
        i64::from(max_x) - i64::from(min_x) < SHORT && i64::from(max_y) - i64::from(min_y) < SHORT
    }
}

impl Crossing for ShortEdge {
    /// [`Crossing::at_row`] for an edge that [`ShortEdge::fits`].
    #[inline(always)]
    fn at_row(top: Point, bottom: Point, row: i64) -> Self {
        let (dx, dy) = (i64::from(bottom.x) - i64::from(top.x), i64::from(bottom.y) - i64::from(top.y));
        // One division; `dy > 0`, `|scaled| < 2^52`.
        let scaled = dx << FRACTION_BITS;
        let step = ceil_quotient(scaled, dy);
        let t = row * i64::from(SUBPIXEL_ONE) + i64::from(SAMPLE_OFFSET) - i64::from(top.y);
        let start = (i64::from(top.x) - i64::from(SAMPLE_OFFSET)) << (FRACTION_BITS - SUBPIXEL_BITS);
        // An arithmetic shift is a floor: adding 255 first makes it the ceiling.
        let offset = (t * step + i64::from(SUBPIXEL_ONE) - 1) >> SUBPIXEL_BITS;
        let bias = (1 << FRACTION_BITS) - (1 << (FRACTION_BITS - 25));
        Self { position: start + offset + bias, step }
    }

    /// [`Crossing::at_last_row`], with no division for an edge less than
    /// a pixel wide. Its crossing `X = x_top + t * dx / dy` lies between
    /// its ends, `L` the left one, and the first centre at or right of `L`,
    /// column `c`, is under a pixel right of `L`: the next centre is right
    /// of both ends, so the column is `c`, or `c + 1` where `c`'s centre
    /// is left of `X`, that is where `(centre - x_top) * dy < t * dx`
    /// (`dy > 0`; both sides under `2^25` in size). Stepping leaves it
    /// where it is, and its position is the column's first. Not in the
    /// kernel, whose measure is instructions: there a division is one,
    /// and `cargo xtask kbench` counted more with the comparison than
    /// without (docs/lab-history.md#2026-11-29-a-short-edge-set-up-without-a-division-77b1d9c-22bef92).
    #[cfg(not(target_os = "none"))]
    #[inline(always)]
    fn at_last_row(top: Point, bottom: Point, row: i64) -> Self {
        let (dx, dy) = (i64::from(bottom.x) - i64::from(top.x), i64::from(bottom.y) - i64::from(top.y));
        if dx.unsigned_abs() >= SUBPIXEL_ONE as u64 {
            return Self::at_row(top, bottom, row);
        }
        let t = row * i64::from(SUBPIXEL_ONE) + i64::from(SAMPLE_OFFSET) - i64::from(top.y);
        let first = first_sample_at_or_after(top.x.min(bottom.x).into());
        let centre = first * i64::from(SUBPIXEL_ONE) + i64::from(SAMPLE_OFFSET);
        let column = first + i64::from((centre - i64::from(top.x)) * dy < t * dx);
        Self { position: column << FRACTION_BITS, step: 0 }
    }

    #[inline(always)]
    fn column(&self) -> i64 {
        self.position >> FRACTION_BITS
    }

    #[inline(always)]
    fn step(&mut self) {
        self.position += self.step;
    }

    /// The position itself: linear in the row, the column its floor. Within
    /// the rows the edge meets it keeps the bounds above.
    #[inline(always)]
    fn position_in(&self, rows: i64) -> Option<i64> {
        Some(self.position + rows * self.step)
    }
}

/// `ceil(n / d)` for `d > 0`.
fn ceil_div(n: i128, d: i128) -> i128 {
    -(-n).div_euclid(d)
}

#[cfg(test)]
mod tests {
    use core::ops::Range;

    use crate::test_rng::xorshift;

    use super::*;

    #[test]
    fn first_sample_is_the_first_centre_at_or_after() {
        // Row 0's centre is at 128: a coordinate of 128 is on it, 129 past it.
        for (v, first) in [(128, 0), (129, 1), (127, 0), (-128, -1), (-129, -1), (-127, 0), (384, 1)] {
            assert_eq!(first_sample_at_or_after(v), first, "v = {v}");
        }
    }

    /// The stepped column equals the column computed afresh on every row.
    #[test]
    fn stepping_matches_fresh_division() {
        let edges = [
            (Point::new(100, 0), Point::new(3000, 2000)),
            (Point::new(3000, -700), Point::new(-57, 4001)),
            (Point::new(128, 128), Point::new(128, 4000)),
            (Point::new(i32::MIN, i32::MIN), Point::new(i32::MAX, i32::MAX)),
            (Point::new(i32::MAX, -5000), Point::new(i32::MIN, 5000)),
        ];
        for (top, bottom) in edges {
            // The rows it meets, in the first 40.
            let rows = first_sample_at_or_after(top.y.into()).max(0)..first_sample_at_or_after(bottom.y.into()).min(40);
            let mut stepper = EdgeStepper::at_row(top, bottom, rows.start);
            for row in rows {
                let fresh = EdgeStepper::at_row(top, bottom, row);
                assert_eq!(
                    (stepper.column, stepper.error),
                    (fresh.column, fresh.error),
                    "{top:?}-{bottom:?} row {row}"
                );
                stepper.step();
            }
        }
    }

    #[test]
    fn a_crossing_on_a_centre_belongs_to_that_pixel() {
        // Vertical edge through the centres of column 2 (x = 640).
        let stepper = EdgeStepper::at_row(Point::new(640, 0), Point::new(640, 1000), 1);
        assert_eq!(stepper.column, 2);
        let stepper = EdgeStepper::at_row(Point::new(641, 0), Point::new(641, 1000), 1);
        assert_eq!(stepper.column, 3);
    }

    /// The quotient [`ShortEdge`]s are set up with is the exact ceiling,
    /// throughout its range: against `div_euclid`, on random operands and
    /// on those nearest the bounds and nearest whole quotients.
    #[test]
    fn ceil_quotient_is_exact() {
        let exact = |a: i64, b: i64| a.div_euclid(b) + i64::from(a.rem_euclid(b) > 0);
        let (top, widest) = ((1i64 << 53) - 1, 1i64 << 17);
        let mut next = xorshift(0x2545_f491_4f6c_dd1d);
        for i in 0..200_000 {
            let b = match i % 4 {
                0 => widest - (next() % 3) as i64,
                1 => 1 + (next() % 8) as i64,
                _ => 1 + (next() % widest as u64) as i64,
            };
            let a = match i % 5 {
                0 => top - (next() % 3) as i64,
                1 => (top / b) * b + (next() % 3) as i64 - 1,
                _ => (next() >> 11) as i64,
            };
            for a in [a, -a] {
                assert_eq!(ceil_quotient(a, b), exact(a, b), "{a} / {b}");
            }
        }
    }

    /// An edge's `(dx, dy)`, each up to `limit` (`dy` at least 1, `dx` of
    /// either sign): one of `special`, a short one or any, at random.
    fn random_extent(next: &mut impl FnMut() -> u64, i: usize, special: &[i64], limit: i64) -> (i64, i64) {
        let pick = |r: u64, s: usize| -> i64 {
            match r % 4 {
                0 => special[s % special.len()],
                1 => (r >> 8) as i64 % 4096,
                _ => (r >> 8) as i64 % (limit + 1),
            }
        };
        let (r1, r2) = (next(), next());
        let dy = pick(r1, i).max(1);
        let dx = if r2 & 1 == 0 { pick(r2 >> 1, i + 3) } else { -pick(r2 >> 1, i + 5) };
        (dx, dy)
    }

    /// The edge from `(x, y)` by `(dx, dy)` and the rows it meets, if its
    /// end is an `i32` point and it meets a row.
    fn edge_from((x, y): (i32, i32), (dx, dy): (i64, i64)) -> Option<(Point, Point, Range<i64>)> {
        let (bx, by) = (i32::try_from(i64::from(x) + dx).ok()?, i32::try_from(i64::from(y) + dy).ok()?);
        let rows = first_sample_at_or_after(y.into())..first_sample_at_or_after(by.into());
        (!rows.is_empty()).then(|| (Point::new(x, y), Point::new(bx, by), rows))
    }

    /// A [`ShortEdge`] walks the columns of an [`EdgeStepper`] on every row
    /// of every edge it takes: short and longest ones, steep and flat, on
    /// and off the pixel grid, anywhere in the `i32` plane.
    #[test]
    fn short_edges_step_the_exact_columns() {
        let limit = SHORT - 1;
        let mut next = xorshift(0x9e37_79b9_7f4a_7c15);
        let special = [0, 1, 2, 127, 128, 129, 255, 256, 257, 1000, limit - 1, limit];
        let (mut edges, mut walked, mut narrow) = (0, 0, 0);
        for i in 0..20_000 {
            let (dx, dy) = random_extent(&mut next, i, &special, limit);
            let r = next();
            let (x, y) = match i % 3 {
                0 => ((r % 100_000) as i32, (r >> 32) as i32 % 60_000),
                1 => ((r as i32) >> (r % 24), (r >> 32) as i32 >> ((r >> 40) % 24)),
                _ => (if r & 1 == 0 { i32::MIN } else { i32::MAX - limit as i32 }, (r >> 32) as i32),
            };
            let Some((top, bottom, rows)) = edge_from((x, y), (dx, dy)) else {
                continue;
            };
            assert!(ShortEdge::fits((top.x.min(bottom.x), top.x.max(bottom.x)), (top.y, bottom.y)));
            (edges, walked) = (edges + 1, walked + (rows.end - rows.start));
            let (mut short, mut exact) =
                (ShortEdge::at_row(top, bottom, rows.start), EdgeStepper::at_row(top, bottom, rows.start));
            for row in rows.clone() {
                assert_eq!(short.column(), exact.column, "{top:?}-{bottom:?} row {row}");
                short.step();
                exact.step();
            }
            // Set up on a later row, as after clipping at the target's top.
            let row = (rows.start + rows.end) / 2;
            let later = ShortEdge::at_row(top, bottom, row).column();
            assert_eq!(later, EdgeStepper::at_row(top, bottom, row).column, "{top:?}-{bottom:?} row {row}");
            // Set up for one row only, as for an edge that meets one: with
            // no division where it is under a pixel wide.
            let under_a_pixel = dx.abs() < i64::from(SUBPIXEL_ONE);
            narrow += usize::from(under_a_pixel);
            for row in [rows.start, rows.start + (rows.end - rows.start) / 2, rows.end - 1] {
                let last = ShortEdge::at_last_row(top, bottom, row);
                assert_eq!(last.column(), EdgeStepper::at_row(top, bottom, row).column, "{top:?}-{bottom:?} row {row}");
                let mut stepped = last;
                stepped.step();
                assert!(!under_a_pixel || stepped.column() == last.column(), "{top:?}-{bottom:?} row {row}");
            }
        }
        // Most of the 20,000 draws make an edge, and most edges many rows;
        // many edges are under a pixel wide.
        assert!(
            edges > 15_000 && walked > 2_000_000 && narrow > 2_000,
            "{edges} edges, {walked} rows, {narrow} narrow"
        );
    }

    /// The tightest case of [`ShortEdge`]'s bound: the longest edge
    /// (`dy = 2^17 - 1`, so `1 / D` is barely above `2^-25`), stepped
    /// 511 rows to a row where its crossing lies `1 / D` px right of a
    /// centre. A step rounded down instead of up loses that centre.
    #[test]
    fn short_edges_keep_a_crossing_just_right_of_a_centre() {
        let dy = SHORT - 1;
        // On row 0, `t = dy - 1`; `dx = dy - 1` makes `t * dx = 1 (mod dy)`
        // (`dy` is prime), and `x_top` then puts `N` at `1 (mod D)`.
        let (t, dx) = (dy - 1, dy - 1);
        let x_top = 128 + ((1 - t * dx) / dy).rem_euclid(256);
        let top = Point::new(x_top as i32, (128 - t) as i32);
        let bottom = Point::new((x_top + dx) as i32, (128 - t + dy) as i32);
        let rows = first_sample_at_or_after(top.y.into())..first_sample_at_or_after(bottom.y.into());
        assert_eq!(rows.start, -511);
        let (mut short, mut exact) =
            (ShortEdge::at_row(top, bottom, rows.start), EdgeStepper::at_row(top, bottom, rows.start));
        for row in rows {
            assert_eq!(short.column(), exact.column, "row {row}");
            short.step();
            exact.step();
        }
        // The case is the one named: on row 0 the centre is `1 / D` left of the crossing.
        let at_zero = EdgeStepper::at_row(top, bottom, 0);
        assert_eq!(at_zero.error, at_zero.denominator - 1);
        assert_eq!(ShortEdge::at_row(top, bottom, 0).column(), at_zero.column);
    }

    /// A short edge's position some rows ahead is where stepping takes it,
    /// and its floor is the column there; the general stepper cannot tell.
    #[test]
    fn short_edges_know_their_position_rows_ahead() {
        let (top, bottom) = (Point::new(1000, 300), Point::new(-20_000, 60_000));
        let rows = first_sample_at_or_after(top.y.into())..first_sample_at_or_after(bottom.y.into());
        let start = ShortEdge::at_row(top, bottom, rows.start);
        let mut stepped = start;
        for ahead in 0..rows.end - rows.start {
            let position = start.position_in(ahead).expect("a short edge knows");
            assert_eq!(
                (position, position >> FRACTION_BITS),
                (stepped.position, stepped.column()),
                "{ahead} rows ahead"
            );
            stepped.step();
        }
        assert_eq!(EdgeStepper::at_row(top, bottom, rows.start).position_in(1), None);
    }

    #[test]
    fn edges_of_512_pixels_are_not_short() {
        assert!(ShortEdge::fits((0, (1 << 17) - 1), (i32::MAX - ((1 << 17) - 1), i32::MAX)));
        assert!(!ShortEdge::fits((0, 1 << 17), (0, 0)));
        assert!(!ShortEdge::fits((0, 0), (-1, (1 << 17) - 1)));
        assert!(!ShortEdge::fits((i32::MIN, i32::MAX), (0, 0)));
    }

    /// The `i64` setup gives the `i128` one's stepper on every edge it
    /// takes, up to its limits.
    #[test]
    fn narrow_setup_matches_wide_setup() {
        let limit = (NARROW - 1) as i64;
        let mut next = xorshift(0x2545_f491_4f6c_dd1d);
        let special = [0, 1, 127, 128, 129, 255, 256, limit / 2, limit - 1, limit];
        for i in 0..200_000 {
            let (dx, dy) = random_extent(&mut next, i, &special, limit);
            let r = next();
            let (x, y) = ((r as i32) >> (r % 24), (r >> 32) as i32 >> ((r >> 40) % 24));
            let Some((top, bottom, rows)) = edge_from((x, y), (dx, dy)) else {
                continue;
            };
            let row = if next() & 1 == 0 { rows.start } else { rows.end - 1 };
            let (a, b) = (EdgeStepper::narrow(top, dx, dy, row, true), EdgeStepper::wide(top, dx, dy, row));
            let fields = |s: EdgeStepper| (s.column, s.error, s.column_step, s.error_step, s.denominator);
            assert_eq!(fields(a), fields(b), "{top:?}-{bottom:?} row {row}");
        }
    }
}
