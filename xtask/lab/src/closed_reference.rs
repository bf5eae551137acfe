//! The reference for the integer peers' own convention
//! ([`Own::Closed`](crate::convention::Own::Closed)): they take whole-pixel
//! vertices (ours rounded, halves up), sample pixel (x, y) at the
//! whole-pixel point (x, y), fill by even-odd, and include both ends of
//! every span, so a point on an edge is in. Allegro and imageproc also
//! draw every edge as a line.
//!
//! The closed polygon is its even-odd fill at whole-pixel points (the
//! reference's, at sample offset (0, 0), which puts points on left and
//! top edges in) together with every whole-pixel point on an edge, which
//! puts the rest in. An edge drawn as a line is, on each step along its
//! longer axis, the pixel nearest the edge (halves up): the pixels any
//! Bresenham line between the same ends draws, up to its ties.

use raster::reference::{self, SampleOffset};
use raster::{CoverageSink, FillRule, Point, Polygon, SpanSink, SCREEN};

use crate::spans;

/// Draws into `sink` (the screen's size) the pixels of `polygon`, its
/// vertices rounded to whole pixels, under the closed convention; with
/// `outline`, its edges drawn as lines too.
pub fn fill(polygon: &Polygon, outline: bool, sink: &mut dyn SpanSink) {
    let contours: Vec<Vec<(i64, i64)>> = polygon
        .contours
        .iter()
        .map(|contour| {
            contour
                .iter()
                .map(|p| {
                    let q = p.round_to_pixel();
                    (i64::from(q.x), i64::from(q.y))
                })
                .collect()
        })
        .collect();
    let mut covered = CoverageSink::new(SCREEN);
    let rounded = Polygon {
        // Whole pixels back in subpixels; only a vertex 2^23 px out (the
        // i32 limit rounded up) saturates, a subpixel short.
        contours: contours
            .iter()
            .map(|c| c.iter().map(|&(x, y)| Point::from_pixels(x as i32, y as i32)).collect())
            .collect(),
        color: polygon.color,
        rule: FillRule::EvenOdd,
    };
    reference::fill(&rounded, SampleOffset { x: 0, y: 0 }, &mut covered);
    for contour in &contours {
        for (i, &a) in contour.iter().enumerate() {
            let b = contour[(i + 1) % contour.len()];
            let mut mark = |x: i64, y: i64| covered.span(y as i32, x as i32, x as i32 + 1, polygon.color);
            if outline {
                line(a, b, &mut mark);
            } else {
                points_on(a, b, &mut mark);
            }
        }
    }
    spans::emit_covered(&covered, |count| count > 0, polygon.color, sink);
}

/// The screen's columns and rows, as inclusive ranges.
const COLUMNS: (i64, i64) = (0, SCREEN.width as i64 - 1);
const ROWS: (i64, i64) = (0, SCREEN.height as i64 - 1);

/// Calls `mark` with every whole-pixel point of segment `a`-`b` on the
/// screen.
fn points_on(a: (i64, i64), b: (i64, i64), mark: &mut dyn FnMut(i64, i64)) {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let steps = gcd(dx.abs(), dy.abs());
    if steps == 0 {
        if on_screen(a) {
            mark(a.0, a.1);
        }
        return;
    }
    let (sx, sy) = (dx / steps, dy / steps);
    let (x_low, x_high) = steps_within(a.0, sx, COLUMNS);
    let (y_low, y_high) = steps_within(a.1, sy, ROWS);
    for k in x_low.max(y_low).max(0)..=x_high.min(y_high).min(steps) {
        mark(a.0 + k * sx, a.1 + k * sy);
    }
}

/// Calls `mark` with the pixels on the screen of segment `a`-`b` drawn as
/// a line: on each whole step along its longer axis, the nearest whole
/// step on the other, halves up.
fn line(a: (i64, i64), b: (i64, i64), mark: &mut dyn FnMut(i64, i64)) {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    if dx == 0 && dy == 0 {
        if on_screen(a) {
            mark(a.0, a.1);
        }
        return;
    }
    // Along x when it is the longer axis, else along y with x and y swapped.
    let along_x = dx.abs() >= dy.abs();
    let (major, minor, d_major, d_minor, major_range, minor_range) =
        if along_x { (a.0, a.1, dx, dy, COLUMNS, ROWS) } else { (a.1, a.0, dy, dx, ROWS, COLUMNS) };
    let (from, to) = (major.min(major + d_major).max(major_range.0), major.max(major + d_major).min(major_range.1));
    for m in from..=to {
        // minor + round((m - major) * d_minor / d_major), halves up.
        let (n, d) = if d_major > 0 { ((m - major) * d_minor, d_major) } else { (-(m - major) * d_minor, -d_major) };
        let other = minor + (2 * n + d).div_euclid(2 * d);
        if (minor_range.0..=minor_range.1).contains(&other) {
            if along_x {
                mark(m, other);
            } else {
                mark(other, m);
            }
        }
    }
}

fn on_screen((x, y): (i64, i64)) -> bool {
    (COLUMNS.0..=COLUMNS.1).contains(&x) && (ROWS.0..=ROWS.1).contains(&y)
}

/// The steps `k` (as an inclusive range, empty when low > high) for which
/// `start + k * step` lies in `range`.
fn steps_within(start: i64, step: i64, (low, high): (i64, i64)) -> (i64, i64) {
    match step {
        0 if (low..=high).contains(&start) => (i64::MIN, i64::MAX),
        0 => (1, 0),
        s if s > 0 => (ceil_div(low - start, s), (high - start).div_euclid(s)),
        s => (ceil_div(high - start, s), floor_div(low - start, s)),
    }
}

fn floor_div(n: i64, d: i64) -> i64 {
    let q = n / d;
    if n % d != 0 && (n < 0) != (d < 0) {
        q - 1
    } else {
        q
    }
}

fn ceil_div(n: i64, d: i64) -> i64 {
    -floor_div(-n, d)
}

fn gcd(a: i64, b: i64) -> i64 {
    if b == 0 {
        a
    } else {
        gcd(b, a % b)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pixels(polygon: &Polygon, outline: bool) -> CoverageSink {
        let mut covered = CoverageSink::new(SCREEN);
        fill(polygon, outline, &mut covered);
        covered
    }

    fn count(covered: &CoverageSink) -> usize {
        covered.ascii().chars().filter(|&c| c == '#').count()
    }

    /// Pick's theorem: a lattice polygon of area A with B lattice points
    /// on its boundary holds A + B / 2 + 1 lattice points, boundary
    /// included. The triangle (10,10) (100,20) (50,90) has area 3,400 and
    /// 10 + 10 + 40 boundary points: 3,431.
    #[test]
    fn the_closed_triangle_holds_picks_count() {
        let triangle = Polygon::from_pixels(&[(10, 10), (100, 20), (50, 90)], (0, 0), 1);
        assert_eq!(count(&pixels(&triangle, false)), 3431);
    }

    /// A 4x3 rectangle at whole pixels holds 5 x 4 points, both ends of
    /// every span; its outline adds nothing, being on those points.
    #[test]
    fn a_rectangle_holds_its_edges() {
        let rectangle = Polygon::from_pixels(&[(2, 1), (6, 1), (6, 4), (2, 4)], (0, 0), 1);
        assert_eq!(count(&pixels(&rectangle, false)), 20);
        assert_eq!(pixels(&rectangle, true), pixels(&rectangle, false));
    }

    /// The slope 1/3 from (0,0) to (6,2) meets whole-pixel points only at
    /// its ends and at (3,1); drawn as a line it has a pixel per column.
    #[test]
    fn an_outline_is_a_pixel_per_step_of_the_longer_axis() {
        let sliver = Polygon::from_pixels(&[(0, 0), (6, 2)], (0, 0), 1);
        let corner = |outline| {
            let picture = pixels(&sliver, outline).ascii();
            picture.lines().take(3).map(|row| row[..7].to_string()).collect::<Vec<_>>()
        };
        assert_eq!(corner(false), ["#......", "...#...", "......#"]);
        assert_eq!(corner(true), ["##.....", "..###..", ".....##"]);
    }

    #[test]
    fn far_edges_are_walked_on_the_screen_only() {
        let far = Polygon::from_pixels(&[(-5_000_000, 100), (5_000_000, 100), (0, -3_000_000)], (0, 0), 1);
        let line = pixels(&far, true);
        assert_eq!(line.out_of_bounds(), 0);
        assert!((0..320).all(|x| line.count(x, 100) > 0));
    }

    #[test]
    fn steps_within_a_range_either_way() {
        assert_eq!(steps_within(5, 2, (0, 9)), (-2, 2));
        assert_eq!(steps_within(5, -2, (0, 9)), (-2, 2));
        assert_eq!(steps_within(5, 0, (0, 9)), (i64::MIN, i64::MAX));
        let (low, high) = steps_within(-5, 0, (0, 9));
        assert!(low > high);
    }
}
