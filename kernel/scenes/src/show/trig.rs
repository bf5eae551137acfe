//! Integer sine and cosine for the animations, and the rotation built on
//! them: the same bits on the host and in the kernel, no floating point.
//!
//! An angle counts [`TURN`]ths of a full turn; sine and cosine are fixed
//! point with [`SCALE_BITS`] fractional bits, so 1.0 is [`ONE`]. The
//! quarter wave is the Taylor series of `sin(x * pi/2)` for `x` in `[0, 1]`
//! up to `x^9`, evaluated by Horner's rule in Q30 integers. The series'
//! remainder is below `(pi/2)^11 / 11! < 4e-6`, a sixteenth of the output's
//! last bit (`1 / 2^14 = 6.1e-5`), so the result is the correctly rounded
//! sine but for values within 4e-6 of a rounding boundary. The other three
//! quarters are the first one mirrored, which makes `0`, a quarter, a half
//! and three quarters of a turn exact and every symmetry of sine exact.
//!
//! The small integer helpers the animations share live here too:
//! [`div_round`] and [`offset`].

use raster::Point;

/// Angle units in a full turn.
pub(super) const TURN: u32 = 4096;
/// Fractional bits of a sine or cosine.
pub(super) const SCALE_BITS: u32 = 14;
/// 1.0 in the fixed point of [`sin_cos`].
pub(super) const ONE: i32 = 1 << SCALE_BITS;

const QUARTER: u32 = TURN / 4;

/// Fractional bits of the series' arithmetic.
const Q: u32 = 30;

/// `(-1)^k (pi/2)^(2k+1) / (2k+1)!` for k = 0..5, in Q30 (rounded to
/// nearest): the Taylor coefficients of `sin(x * pi/2)`.
const COEFFICIENTS: [i64; 5] = [1_686_629_713, -693_598_668, 85_569_306, -5_026_995, 172_272];

/// `sin(angle * pi/2 / QUARTER)` for `angle` in `0..=QUARTER`, in Q14,
/// rounded to nearest.
fn quarter_sine(angle: u32) -> i32 {
    // x in [0, 1] as Q30; every product below stays under 2^62.
    let x = (i64::from(angle) << Q) / i64::from(QUARTER);
    let x2 = (x * x) >> Q;
    let series = COEFFICIENTS.iter().rev().fold(0, |acc, &c| c + ((acc * x2) >> Q));
    let sine = (series * x) >> Q;
    let shift = Q - SCALE_BITS;
    ((sine + (1 << (shift - 1))) >> shift) as i32
}

/// Sine and cosine of `angle` (taken modulo [`TURN`]), scaled by [`ONE`].
pub(super) fn sin_cos(angle: u32) -> (i32, i32) {
    let angle = angle % TURN;
    let (rising, falling) = {
        let r = angle % QUARTER;
        (quarter_sine(r), quarter_sine(QUARTER - r))
    };
    match angle / QUARTER {
        0 => (rising, falling),
        1 => (falling, -rising),
        2 => (-rising, -falling),
        _ => (-falling, rising),
    }
}

/// `offset` turned by `angle` about the origin (`x cos - y sin`,
/// `x sin + y cos`; y grows downwards, so a growing angle turns clockwise
/// on the screen), rounded to the nearest unit. Exact in `i64` for every
/// `i32` input; the result saturates at the `i32` range.
pub(super) fn rotate(offset: Point, angle: u32) -> Point {
    let (sin, cos) = sin_cos(angle);
    let (x, y) = (i64::from(offset.x), i64::from(offset.y));
    Point::new(unscale(x * i64::from(cos) - y * i64::from(sin)), unscale(x * i64::from(sin) + y * i64::from(cos)))
}

/// The point at `angle` on the ellipse of radii `radius` (x, y) about the
/// origin: `(rx cos, ry sin)`, rounded to the nearest unit.
pub(super) fn polar(radius: (i32, i32), angle: u32) -> Point {
    let (sin, cos) = sin_cos(angle);
    Point::new(unscale(i64::from(radius.0) * i64::from(cos)), unscale(i64::from(radius.1) * i64::from(sin)))
}

/// A product with a sine or cosine back to units: divided by [`ONE`],
/// rounded to nearest (halves up), saturated at the `i32` range.
pub(super) fn unscale(v: i64) -> i32 {
    div_round(v, i64::from(ONE)).clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32
}

/// `n / d` rounded to nearest, halves up; `d > 0` and `n + d / 2` must fit.
pub(super) fn div_round(n: i64, d: i64) -> i64 {
    (n + d / 2).div_euclid(d)
}

/// `centre + by`, saturating at the `i32` range.
pub(super) fn offset(centre: Point, by: Point) -> Point {
    Point::new(centre.x.saturating_add(by.x), centre.y.saturating_add(by.y))
}

/// The angle reached after `turns` full turns (negative: the other way)
/// spread evenly over `frames` frames, at frame `frame`. Frame `frames` is
/// back at angle 0 for any whole number of turns.
pub(super) fn angle_at(frame: u32, frames: u32, turns: i32) -> u32 {
    let frames = i64::from(frames.max(1));
    let units = i64::from(frame) * i64::from(turns) * i64::from(TURN) / frames;
    units.rem_euclid(i64::from(TURN)) as u32
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_at_the_quarters() {
        assert_eq!(sin_cos(0), (0, ONE));
        assert_eq!(sin_cos(QUARTER), (ONE, 0));
        assert_eq!(sin_cos(2 * QUARTER), (0, -ONE));
        assert_eq!(sin_cos(3 * QUARTER), (-ONE, 0));
        assert_eq!(sin_cos(TURN), (0, ONE));
    }

    #[test]
    fn on_the_unit_circle_everywhere() {
        let one = i64::from(ONE);
        for angle in 0..TURN {
            let (s, c) = sin_cos(angle);
            let norm = i64::from(s) * i64::from(s) + i64::from(c) * i64::from(c);
            // Each value is within half a unit of the truth, so the norm is
            // within about 2 * ONE * 0.5 * sqrt(2) of ONE^2.
            assert!((norm - one * one).abs() <= 2 * one, "angle {angle}: {s}, {c}");
        }
    }

    #[test]
    fn symmetric() {
        for angle in 0..TURN {
            let (s, c) = sin_cos(angle);
            assert_eq!(sin_cos(TURN - angle), (-s, c), "reflection at {angle}");
            assert_eq!(sin_cos(angle + QUARTER), (c, -s), "quarter turn at {angle}");
            assert_eq!(sin_cos(angle + 2 * QUARTER), (-s, -c), "half turn at {angle}");
        }
    }

    #[test]
    fn matches_a_few_known_values() {
        // sin 45 degrees = 11585.24 / 16384, sin 22.5 degrees = 6269.92 / 16384.
        assert_eq!(sin_cos(TURN / 8), (11585, 11585));
        assert_eq!(sin_cos(TURN / 16), (6270, 15137));
        // Never decreasing over the first quarter (near its top a step of
        // the angle moves the sine by less than a unit).
        assert!((1..=QUARTER).all(|a| sin_cos(a).0 >= sin_cos(a - 1).0));
    }

    #[test]
    fn rotation_turns_and_rounds() {
        let p = Point::new(256, 0);
        assert_eq!(rotate(p, QUARTER), Point::new(0, 256));
        assert_eq!(rotate(p, 2 * QUARTER), Point::new(-256, 0));
        assert_eq!(rotate(p, TURN / 8), Point::new(181, 181));
        let far = rotate(Point::new(i32::MAX, i32::MAX), TURN / 8);
        assert_eq!(far.y, i32::MAX);
    }

    #[test]
    fn polar_points_lie_on_their_ellipse() {
        assert_eq!(polar((100, 50), 0), Point::new(100, 0));
        assert_eq!(polar((100, 50), QUARTER), Point::new(0, 50));
        assert_eq!(polar((100, 50), TURN / 8), Point::new(71, 35));
    }

    #[test]
    fn division_rounds_halves_up() {
        assert_eq!([-3, -2, -1, 0, 1, 2, 3].map(|n| div_round(n, 2)), [-1, -1, 0, 0, 1, 1, 2]);
        assert_eq!(div_round(-5, 3), -2);
        assert_eq!(div_round(5, 3), 2);
        assert_eq!(unscale(i64::from(ONE) * 3 / 2), 2);
        assert_eq!(unscale(-i64::from(ONE) * 3 / 2), -1);
        assert_eq!(unscale(i64::MAX / 2), i32::MAX);
    }

    #[test]
    fn offsets_add_and_saturate() {
        assert_eq!(offset(Point::new(10, -4), Point::new(-3, 7)), Point::new(7, 3));
        assert_eq!(offset(Point::new(i32::MAX, i32::MIN), Point::new(1, -1)), Point::new(i32::MAX, i32::MIN));
    }

    #[test]
    fn angles_come_full_circle() {
        assert_eq!(angle_at(0, 100, 3), 0);
        assert_eq!(angle_at(100, 100, 3), 0);
        assert_eq!(angle_at(100, 100, -2), 0);
        assert_eq!(angle_at(25, 100, 1), QUARTER);
        assert_eq!(angle_at(25, 100, -1), 3 * QUARTER);
    }
}
