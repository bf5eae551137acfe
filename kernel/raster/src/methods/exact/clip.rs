//! Where the target cuts a polygon, for every path of `exact`, in one
//! place: the rows an edge meets inside the target, the edges wholly right
//! of it, and the crossing columns, clamped to it only where they may
//! leave it.
//!
//! Rows are cut before any is visited, so a polygon spanning the whole
//! `i32` plane costs the target's rows, never 2^24. Columns are clamped
//! rather than cut: a crossing left of the target still counts for every
//! pixel of its row, one right of it for none, so clamping every crossing
//! to the target's `0..=width` leaves the inside test of each visible pixel
//! as it was.

use core::ops::Range;

use super::edge::first_sample_at_or_after;

/// The scan lines an edge from `top_y` down to `bottom_y` meets
/// (`top_y <= ys < bottom_y`), limited to the target's rows `0..height`.
/// Empty for horizontal and upward edges.
#[inline(always)]
pub(super) fn visible_rows(top_y: i32, bottom_y: i32, height: i32) -> Range<i64> {
    let first = first_sample_at_or_after(top_y.into()).max(0);
    let end = first_sample_at_or_after(bottom_y.into()).min(height.into());
    first..end.max(first)
}

/// The visible `rows` above the first row at or below `y`, and the rest;
/// either may be empty.
#[inline(always)]
pub(super) fn split_rows(rows: Range<i64>, y: i32) -> (Range<i64>, Range<i64>) {
    let split = first_sample_at_or_after(y.into()).clamp(rows.start, rows.end);
    (rows.start..split, split..rows.end)
}

/// Whether an edge whose leftmost point is at `x` lies right of the last
/// pixel centre of a target `width` wide: its crossings count for no
/// visible pixel, so it can be left out.
#[inline(always)]
pub(super) fn right_of_target(x: i32, width: i32) -> bool {
    first_sample_at_or_after(x.into()) >= i64::from(width)
}

/// Whether a polygon whose vertices' x lie in `min_x..=max_x` draws
/// nothing on a target `width` wide for lying beside it: every crossing's
/// column at or left of the first pixel (then each row's crossings all
/// count for every visible pixel, and a row's crossings of closed contours
/// add up to nothing under either rule) or at or right of the last's
/// right (none counts for any). The monotone fill asks it only of
/// contours whose columns do not fit ([`columns_fit`]): one that fits and
/// lies beside the target has every crossing at column 0 (or every one at
/// `width`) and draws nothing through the ordinary walk, so a contour
/// inside the target pays for one test, not two (`cargo xtask kbench`:
/// 411 to 941 fewer instructions on the Listing 38.3 pages). The triangle
/// fill asks it first: asked after the fit there, the triangle pages took
/// 624 and 1,033 more.
#[inline(always)]
pub(super) fn beside_target(min_x: i32, max_x: i32, width: i32) -> bool {
    first_sample_at_or_after(max_x.into()) <= 0 || right_of_target(min_x, width)
}

/// Whether every crossing column of edges with x in `min_x..=max_x` lies in
/// the target's `0..=width`, so that no column needs clamping: a crossing
/// lies on its edge, and [`first_sample_at_or_after`] keeps order. Where
/// they do, the paths walk their rows with `CLIP` off.
#[inline(always)]
pub(super) fn columns_fit(min_x: i32, max_x: i32, width: i32) -> bool {
    first_sample_at_or_after(min_x.into()) >= 0 && first_sample_at_or_after(max_x.into()) <= i64::from(width)
}

/// A pixel column clamped to the target's `0..=width`. (Not `clamp`,
/// whose check that the bounds are in order would be made on every row:
/// `width` is never negative here.)
#[inline(always)]
pub(super) fn visible_column(column: i64, width: i32) -> i32 {
    column.max(0).min(width.into()) as i32
}

/// A crossing's visible column (in `0..=width`): clamped under `CLIP`;
/// without it the column must already be in range ([`columns_fit`]).
#[inline(always)]
pub(super) fn visible<const CLIP: bool>(column: i64, width: i32) -> i32 {
    if CLIP {
        visible_column(column, width)
    } else {
        column as i32
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_are_half_open_and_clipped() {
        assert_eq!(visible_rows(128, 384, 10), 0..1);
        assert_eq!(visible_rows(129, 385, 10), 1..2);
        assert_eq!(visible_rows(200, 200, 10), 1..1);
        assert_eq!(visible_rows(i32::MIN, i32::MAX, 10), 0..10);
        assert!(visible_rows(i32::MAX - 1, i32::MAX, 10).is_empty());
        assert!(visible_rows(300, 100, 10).is_empty());
    }

    #[test]
    fn a_split_stays_within_the_visible_rows() {
        // Row 3's centre is at 896: a vertex on it starts the lower part.
        assert_eq!(split_rows(0..10, 896), (0..3, 3..10));
        assert_eq!(split_rows(0..10, 897), (0..4, 4..10));
        assert_eq!(split_rows(2..10, i32::MIN), (2..2, 2..10));
        assert_eq!(split_rows(2..10, i32::MAX), (2..10, 10..10));
    }

    #[test]
    fn columns_are_clamped_to_the_target() {
        assert_eq!([-5, 0, 7, 10, 11, i64::MAX].map(|c| visible_column(c, 10)), [0, 0, 7, 10, 10, 10]);
        // The last centre of a target 10 wide is at 9.5 px (2432).
        assert!(!right_of_target(2432, 10) && right_of_target(2433, 10));
        // Columns 0 to 10 are those of x from -127 to 2688.
        assert!(columns_fit(-127, 2688, 10) && !columns_fit(-128, 2688, 10) && !columns_fit(-127, 2689, 10));
    }

    #[test]
    fn a_polygon_beside_the_target_is_known_by_its_x_range() {
        // Column 0's centre is at 128: up to it every crossing counts for
        // every pixel; one subpixel past it, pixel 0 has one crossing left.
        assert!(beside_target(-5000, 128, 10) && !beside_target(-5000, 129, 10));
        // The last centre of a target 10 wide is at 2432.
        assert!(beside_target(2433, 9000, 10) && !beside_target(2432, 9000, 10));
        assert!(!beside_target(i32::MIN, i32::MAX, 10));
    }
}
