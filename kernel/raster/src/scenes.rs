//! The built-in scenes: the sample programs of the seeds, as data.

use alloc::string::ToString;
use alloc::vec::Vec;

use crate::geometry::Polygon;
use crate::scene::{Op, Scene};

/// Names of the built-in scenes, in demo order.
pub const NAMES: &[&str] = &["abrash38-1", "abrash38-2", "abrash38-3"];

/// The built-in scene called `name`.
pub fn by_name(name: &str) -> Option<Scene> {
    let ops = match name {
        "abrash38-1" => listing_38_3(1),
        "abrash38-2" => listing_38_3(2),
        "abrash38-3" => listing_38_3(3),
        _ => return None,
    };
    Some(Scene { name: name.to_string(), ops })
}

/// Listing 38.3 up to its `page`-th keypress (ABRASH_FACTS.md §1). The book
/// never clears between stages, so each page holds the ones before it.
fn listing_38_3(page: u32) -> Vec<Op> {
    const SCREEN_RECTANGLE: &[(i32, i32)] = &[(0, 0), (320, 0), (320, 200), (0, 200)];
    const CONVEX_SHAPE: &[(i32, i32)] = &[
        (0, 0), (121, 0), (320, 0), (200, 51), (301, 51), (250, 51), (319, 143), (320, 200), (22, 200),
        (0, 200), (50, 180), (20, 160), (50, 140), (20, 120), (50, 100), (20, 80), (50, 60), (20, 40), (50, 20),
    ];
    const TRIANGLE_1: &[(i32, i32)] = &[(30, 0), (15, 20), (0, 0)];
    const TRIANGLE_2: &[(i32, i32)] = &[(30, 20), (15, 0), (0, 20)];
    const TRIANGLE_3: &[(i32, i32)] = &[(0, 20), (20, 10), (0, 0)];
    const TRIANGLE_4: &[(i32, i32)] = &[(20, 20), (20, 0), (0, 10)];

    let fill = |points: &[(i32, i32)], offset: (i32, i32), color: u8| Op::Fill(Polygon::from_pixels(points, offset, color));
    let mut ops = Vec::new();
    ops.push(fill(SCREEN_RECTANGLE, (0, 0), 3));
    ops.push(fill(CONVEX_SHAPE, (0, 0), 6));
    if page < 2 {
        return ops;
    }
    for j in (0..=80).step_by(20) {
        for i in (0..290).step_by(30) {
            ops.push(fill(TRIANGLE_1, (i, j), 2));
            ops.push(fill(TRIANGLE_2, (i + 15, j), 4));
        }
    }
    for j in (100..=170).step_by(20) {
        for i in (0..290).step_by(20) {
            ops.push(fill(TRIANGLE_3, (i, j), 40));
        }
        for i in (0..290).step_by(20) {
            ops.push(fill(TRIANGLE_4, (i, j + 10), 1));
        }
    }
    if page < 3 {
        return ops;
    }
    // The book edits the hexagon's static vertices in place after each draw:
    // X moves 3 toward zero and Y 2 (sign test `>= 0`), or, where X is 0, Y
    // moves 3 toward zero.
    let mut hexagon = [(90, -50), (0, -90), (-90, -50), (-90, 50), (0, 90), (90, 50)];
    for color in 0..16u8 {
        ops.push(fill(&hexagon, (160, 100), color));
        for (x, y) in hexagon.iter_mut() {
            let toward_zero = |v: i32, by: i32| if v >= 0 { v - by } else { v + by };
            if *x != 0 {
                *x = toward_zero(*x, 3);
                *y = toward_zero(*y, 2);
            } else {
                *y = toward_zero(*y, 3);
            }
        }
    }
    ops
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Point;

    #[test]
    fn every_name_resolves() {
        for name in NAMES {
            assert_eq!(by_name(name).unwrap().name, *name);
        }
        assert!(by_name("nope").is_none());
    }

    #[test]
    fn pages_are_cumulative() {
        let counts: Vec<usize> = NAMES.iter().map(|n| by_name(n).unwrap().ops.len()).collect();
        // 2 shapes; 5x10 pairs of triangles and 4x(15+15) more; 16 hexagons.
        assert_eq!(counts, [2, 2 + 100 + 120, 2 + 100 + 120 + 16]);
    }

    #[test]
    fn last_hexagon_matches_the_book() {
        let scene = by_name("abrash38-3").unwrap();
        let Some(Op::Fill(last)) = scene.ops.last() else { panic!("no hexagon") };
        let expected: Vec<Point> = [(45, -20), (0, -45), (-45, -20), (-45, 20), (0, 45), (45, 20)]
            .iter()
            .map(|&(x, y)| Point::from_pixels(x + 160, y + 100))
            .collect();
        assert_eq!(last.contours[0], expected);
        assert_eq!(last.color, 15);
    }
}
