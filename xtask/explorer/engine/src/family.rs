//! Which family of the lab's corpus (`cargo xtask lab`, `results.json`) a
//! polygon is nearest to, so the page can show a method's speed and error
//! figures beside the one polygon it is looking at. The families are the
//! lab's, by name; the tests pin the shapes each rule is for.

use raster::{classify, Class, Polygon, SCREEN, SUBPIXEL_BITS};

/// A lab family and, in words, why it was chosen.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Nearest {
    pub family: &'static str,
    pub reason: String,
}

/// Past this distance from the origin (1024 px) a polygon is one of the
/// magnitude sweep's, which goes out to the `i32` limits.
const FAR: i64 = 1 << 18;

/// The lab family nearest to `polygon`.
pub fn nearest(polygon: &Polygon) -> Nearest {
    let nearest = |family, reason: String| Nearest { family, reason };
    let class = classify(polygon);
    let vertices = polygon.vertex_count();
    let points = || polygon.contours.iter().flatten();
    let Some(first) = points().next() else {
        return nearest("degenerate", "no vertices".to_string());
    };
    let mut low = (i64::from(first.x), i64::from(first.y));
    let mut high = low;
    for p in points() {
        low = (low.0.min(i64::from(p.x)), low.1.min(i64::from(p.y)));
        high = (high.0.max(i64::from(p.x)), high.1.max(i64::from(p.y)));
    }
    let farthest = [low.0, low.1, high.0, high.1].into_iter().map(i64::abs).max().unwrap_or(0);
    let screen = (i64::from(SCREEN.width) << SUBPIXEL_BITS, i64::from(SCREEN.height) << SUBPIXEL_BITS);
    let outside = high.0 <= 0 || high.1 <= 0 || low.0 >= screen.0 || low.1 >= screen.1;
    let straddles = low.0 < 0 || low.1 < 0 || high.0 > screen.0 || high.1 > screen.1;
    let extent_px = (high.0 - low.0).max(high.1 - low.1) as f64 / f64::from(1u32 << SUBPIXEL_BITS);
    match class {
        Class::Degenerate => nearest("degenerate", "no area".to_string()),
        _ if farthest > FAR => nearest("magnitude_sweep", format!("a vertex {} px away", farthest >> SUBPIXEL_BITS)),
        _ if outside => nearest("offscreen", "wholly off screen".to_string()),
        _ if straddles => nearest("partly_offscreen", "straddles a screen edge".to_string()),
        Class::Complex if polygon.contours.len() > 1 => {
            nearest("holes", format!("{} contours", polygon.contours.len()))
        }
        Class::Complex => nearest("stars", "self-intersecting".to_string()),
        Class::Simple if vertices > 16 => nearest("nonconvex_shapes", format!("simple, {vertices} vertices")),
        Class::Simple => nearest("concave", "simple, not monotone in y".to_string()),
        Class::Convex if vertices > 16 => nearest("vertex_sweep", format!("monotone, {vertices} vertices")),
        _ if narrowest_px(polygon) < 2.0 => nearest("slivers", "under 2 px wide".to_string()),
        Class::Triangle if extent_px <= 50.0 => {
            nearest("small_triangles", format!("a triangle {extent_px:.0} px across"))
        }
        _ if extent_px <= 120.0 => nearest("medium_convex", format!("monotone, {extent_px:.0} px across")),
        _ => nearest("large_convex", format!("monotone, {extent_px:.0} px across")),
    }
}

/// Twice the area over the longest edge, in pixels: how wide the polygon
/// is across its longest side.
fn narrowest_px(polygon: &Polygon) -> f64 {
    let mut twice_area = 0.0;
    let mut longest: f64 = 0.0;
    for contour in &polygon.contours {
        for (a, b) in contour.iter().zip(contour.iter().cycle().skip(1)) {
            let (ax, ay, bx, by) = (f64::from(a.x), f64::from(a.y), f64::from(b.x), f64::from(b.y));
            twice_area += ax * by - bx * ay;
            longest = longest.max((bx - ax).hypot(by - ay));
        }
    }
    if longest == 0.0 {
        return 0.0;
    }
    twice_area.abs() / longest / f64::from(1u32 << SUBPIXEL_BITS)
}

#[cfg(test)]
mod tests {
    use super::*;
    use scenes::file::parse_poly;

    fn family_of(spec: &str) -> &'static str {
        nearest(&parse_poly(spec).unwrap()).family
    }

    #[test]
    fn each_shape_finds_its_family() {
        assert_eq!(family_of("color=1 10,10 40,10 20,35"), "small_triangles");
        assert_eq!(family_of("color=1 10,10 110,10 60,90"), "medium_convex");
        assert_eq!(family_of("color=1 10,10 300,10 300,190 10,190"), "large_convex");
        assert_eq!(family_of("color=1 10,10 200,11 10,11.5"), "slivers");
        assert_eq!(family_of("color=1 10,10 50,10 60,40 70,10 100,10 100,60 10,60"), "concave");
        assert_eq!(family_of("color=1 100,10 130,100 50,45 150,45 70,100"), "stars");
        assert_eq!(family_of("color=1 0,0 90,0 90,90 0,90 | 10,10 20,10 20,20"), "holes");
        assert_eq!(family_of("color=1 -20,10 40,10 20,35"), "partly_offscreen");
        assert_eq!(family_of("color=1 400,10 440,10 420,35"), "offscreen");
        assert_eq!(family_of("color=1 -8388608,0 40,10 20,35"), "magnitude_sweep");
        assert_eq!(family_of("color=1 10,10 20,20 30,30"), "degenerate");
        assert_eq!(family_of("color=1"), "degenerate");
    }

    #[test]
    fn many_vertices_go_to_the_sweeps() {
        let circle: Vec<String> = (0..40)
            .map(|i| {
                let a = f64::from(i) * std::f64::consts::TAU / 40.0;
                format!("{:.2},{:.2}", 160.0 + 80.0 * a.cos(), 100.0 + 80.0 * a.sin())
            })
            .collect();
        assert_eq!(family_of(&format!("color=1 {}", circle.join(" "))), "vertex_sweep");
        let comb: Vec<String> =
            (0..20).flat_map(|i| [format!("{},10", 10 + i * 10), format!("{},50", 15 + i * 10)]).collect();
        assert_eq!(family_of(&format!("color=1 {} 300,100 10,100", comb.join(" "))), "nonconvex_shapes");
    }
}
