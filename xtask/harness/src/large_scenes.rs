//! Scenes too large for a command line, made to order for the tests that
//! prove an upload: one polygon of many contours, and a scene file of
//! hundreds of kilobytes. Both are seeded, so every run draws the same.

use std::f64::consts::TAU;
use std::fmt::Write as _;

use raster::{FillRule, MethodId, Point, Polygon, SUBPIXEL_ONE};
use scenes::{Op, Scene};

/// One polygon of `rings` contours of `each` vertices: wavy rings around
/// the screen's centre, every other one turning the other way, at
/// subpixel positions, filled under the non-zero rule (so the rings'
/// directions decide what is inside) over a clear to colour 1.
pub fn rings(rings: usize, each: usize) -> Scene {
    let contours = (0..rings)
        .map(|ring| {
            let radius = 6.0 + 2.3 * ring as f64;
            let turn = if ring % 2 == 0 { 1.0 } else { -1.0 };
            (0..each)
                .map(|i| {
                    let angle = turn * TAU * i as f64 / each as f64;
                    let wave = 1.0 + 0.07 * (5.0 * angle + ring as f64).sin();
                    let at = |centre: f64, v: f64| ((centre + radius * wave * v) * f64::from(SUBPIXEL_ONE)).round();
                    Point::new(at(160.0, angle.cos()) as i32, at(100.0, 0.9 * angle.sin()) as i32)
                })
                .collect()
        })
        .collect();
    let polygon = Polygon { contours, color: 14, rule: FillRule::NonZero };
    Scene::new("rings".to_string(), vec![Op::Clear(1), Op::Fill(polygon)], MethodId::Exact)
}

/// A scene file of at least `bytes` bytes: a palette of 32 entries, then
/// polygons of 3 to 12 vertices with two decimals, some with a hole, both
/// rules, some reaching past the screen's edges.
pub fn large_file(bytes: usize) -> String {
    let mut seeded = Seeded(0x5eed);
    let mut text = String::from("# seeded: a palette, then polygons until the file is large enough\nclear 0\n");
    for entry in 0..32u64 {
        let [r, g, b] = [seeded.below(64), seeded.below(64), seeded.below(64)];
        let _ = writeln!(text, "palette {} {r},{g},{b}", 200 + entry);
    }
    while text.len() < bytes {
        let vertices = 3 + seeded.below(10);
        let rule = if seeded.below(2) == 0 { "evenodd" } else { "nonzero" };
        let _ = write!(text, "poly color={} rule={rule}", 1 + seeded.below(255));
        let holes = if seeded.below(4) == 0 { 1 } else { 0 };
        for contour in 0..1 + holes {
            if contour > 0 {
                text.push_str(" |");
            }
            for _ in 0..if contour == 0 { vertices } else { 3 } {
                let _ = write!(text, " {},{}", seeded.coordinate(320), seeded.coordinate(200));
            }
        }
        text.push('\n');
    }
    text
}

/// A 64-bit linear congruential generator (Knuth's MMIX constants).
struct Seeded(u64);

impl Seeded {
    /// A number below `bound`.
    fn below(&mut self, bound: u64) -> u64 {
        self.0 = self.0.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 33) % bound
    }

    /// A coordinate with two decimals, from 20 px before 0 to 20 px past
    /// `span`.
    fn coordinate(&mut self, span: u64) -> String {
        let whole = self.below(span + 40) as i64 - 20;
        format!("{whole}.{:02}", self.below(100))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_rings_have_the_vertices_and_contours_asked_for_and_fit_the_screen() {
        let scene = rings(40, 50);
        let Op::Fill(polygon) = &scene.ops[1] else { panic!("the second op is the polygon") };
        assert_eq!((polygon.contours.len(), polygon.vertex_count()), (40, 2000));
        let inside = |p: &Point| (0..320 * 256).contains(&p.x) && (0..200 * 256).contains(&p.y);
        assert!(polygon.contours.iter().flatten().all(inside));
    }

    #[test]
    fn the_large_file_parses_and_is_as_large_as_asked() {
        let text = large_file(350_000);
        assert!((350_000..351_000).contains(&text.len()), "{}", text.len());
        let scene = scenes::file::parse("large", &text).unwrap();
        assert_eq!(scene.palette.len(), 32);
        assert!(scene.ops.len() > 2000, "{} ops", scene.ops.len());
        assert_eq!(text, large_file(350_000), "seeded: the same every time");
    }
}
