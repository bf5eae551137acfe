//! Subpixel coordinates as exact decimals: 1/256 is 0.00390625, so every
//! subpixel value has a finite decimal form of at most eight fractional
//! digits, which the scene-file parser snaps back to the very same value.

use std::fmt::Write;

use raster::{Polygon, SUBPIXEL_BITS, SUBPIXEL_ONE};

/// `subpixels / 256` pixels as the shortest exact decimal ("-3.25", "12").
pub fn pixels(subpixels: i32) -> String {
    let magnitude = i64::from(subpixels).unsigned_abs();
    let whole = magnitude >> SUBPIXEL_BITS;
    let fraction = magnitude & (SUBPIXEL_ONE as u64 - 1);
    let sign = if subpixels < 0 { "-" } else { "" };
    if fraction == 0 {
        return format!("{sign}{whole}");
    }
    // fraction / 256 = fraction * 5^8 / 10^8.
    let digits = format!("{:08}", fraction * 390_625);
    format!("{sign}{whole}.{}", digits.trim_end_matches('0'))
}

/// `polygon` as one scene-file `poly` line (the README's "Scene files").
pub fn poly_line(polygon: &Polygon) -> String {
    let mut line = format!("poly color={} rule={}", polygon.color, polygon.rule.name());
    for (i, contour) in polygon.contours.iter().enumerate() {
        if i > 0 {
            line.push_str(" |");
        }
        for point in contour {
            // Writing to a String cannot fail.
            let _ = write!(line, " {},{}", pixels(point.x), pixels(point.y));
        }
    }
    line
}

#[cfg(test)]
mod tests {
    use super::*;
    use raster::{FillRule, Point};
    use scenes::file::parse_poly;

    #[test]
    fn decimals_are_exact_and_shortest() {
        assert_eq!(pixels(0), "0");
        assert_eq!(pixels(256), "1");
        assert_eq!(pixels(-832), "-3.25");
        assert_eq!(pixels(1), "0.00390625");
        assert_eq!(pixels(-1), "-0.00390625");
        assert_eq!(pixels(i32::MAX), "8388607.99609375");
        assert_eq!(pixels(i32::MIN), "-8388608");
    }

    #[test]
    fn a_copied_line_parses_back_to_the_same_polygon() {
        let values = [i32::MIN, i32::MIN + 1, -257, -256, -255, -128, -1, 0, 1, 127, 128, 255, 70_000, i32::MAX];
        let contour: Vec<Point> = values.iter().zip(values.iter().rev()).map(|(&x, &y)| Point::new(x, y)).collect();
        let polygon = Polygon {
            contours: vec![contour, vec![Point::new(5, 6), Point::new(-7, 8), Point::new(9, -10)]],
            color: 200,
            rule: FillRule::NonZero,
        };
        let line = poly_line(&polygon);
        assert!(line.starts_with("poly color=200 rule=nonzero -8388608,8388607.99609375 "), "{line}");
        let back = parse_poly(line.strip_prefix("poly").unwrap()).unwrap();
        assert_eq!(back, polygon);
    }
}
