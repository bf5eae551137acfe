//! What a pane shows: a method's picture of the scene in its palette (the
//! VGA default, with a scene file's own entries over it), or the difference view of the selected polygon against a judge
//! (`exact`, or the reference at the method's own sample point), with the
//! pixels the method adds and the pixels it misses counted for the
//! selected polygon and over every polygon of the scene.

use raster::{CoverageSink, Framebuffer, MethodId, Polygon, SCREEN, SUBPIXEL_BITS};
use scenes::palette::c6_to_8;
use scenes::DrawReport;

use crate::judge::{compare, Counts, Judge};
use crate::model::Explorer;

/// Bytes of a pane's picture: 320x200 pixels of red, green, blue, alpha.
pub const RGBA_BYTES: usize = SCREEN.width as usize * SCREEN.height as usize * 4;

/// Difference view colours (red, green, blue).
pub const ADDED: [u8; 3] = [255, 48, 48];
pub const MISSED: [u8; 3] = [0, 170, 255];
pub const AGREED: [u8; 3] = [230, 230, 230];

/// Which picture a pane shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum View {
    /// The scene as the method draws it, in its palette (the VGA default,
    /// with a scene file's `palette` entries over it).
    Picture,
    /// The scene darkened, the selected polygon's pixels marked: added
    /// ([`ADDED`]), missed ([`MISSED`]), agreed ([`AGREED`]).
    Difference,
}

/// Most pixel-edge tests the reference may make to judge a whole scene
/// under a method's own convention (it tests every edge at every pixel of
/// a polygon's box: a screen-wide zigzag of 1024 vertices alone takes 65
/// million). Past it, the pane judges against `exact` and says why.
pub const REFERENCE_BUDGET: u64 = 16_000_000;

/// What one render of a pane found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PaneReport {
    /// The judge used: the one asked for, or `exact` when the reference
    /// would have taken more than [`REFERENCE_BUDGET`] tests.
    pub judge: Judge,
    /// The reference's pixel-edge tests for the whole scene.
    pub reference_work: u64,
    /// The whole scene drawn with the method.
    pub drawn: DrawReport,
    /// The selected polygon against the judge, if there is one.
    pub selected: Option<Counts>,
    /// Every polygon against the judge, summed (refusal: the first).
    pub scene: Counts,
}

/// `method` against `judge` on polygon `index` of the scene, from the
/// cache when known.
fn polygon_counts(explorer: &mut Explorer, index: usize, method: MethodId, judge: Judge) -> Counts {
    if let Some(counts) = explorer.counts.get(index, method, judge) {
        return counts;
    }
    let Some(polygon) = explorer.polygon(index) else { return Counts::default() };
    let (counts, _, _) = compare(polygon, method, judge);
    explorer.counts.insert(index, method, judge, counts);
    counts
}

/// Draws the pane's picture into `rgba` (resized to [`RGBA_BYTES`]) and
/// reports what the method did.
pub fn render(explorer: &mut Explorer, method: MethodId, view: View, judge: Judge, rgba: &mut Vec<u8>) -> PaneReport {
    let reference_work: u64 = explorer.polygons().map(reference_work).sum();
    let judge = if reference_work > REFERENCE_BUDGET { Judge::Exact } else { judge };
    let mut framebuffer = Framebuffer::new(SCREEN);
    let drawn = explorer.scene().draw(method, &mut framebuffer);
    let dac = explorer.scene().dac();
    rgba.clear();
    rgba.reserve(RGBA_BYTES);
    for &index in framebuffer.pixels() {
        let [r, g, b] = dac[usize::from(index)].map(c6_to_8);
        match view {
            View::Picture => rgba.extend_from_slice(&[r, g, b, 255]),
            View::Difference => rgba.extend_from_slice(&[r / 4, g / 4, b / 4, 255]),
        }
    }
    let mut scene = Counts::default();
    for index in 0..explorer.polygon_count() {
        scene = scene + polygon_counts(explorer, index, method, judge);
    }
    let selected = explorer.selected_polygon().map(|polygon| {
        let (counts, drawn, wanted) = compare(polygon, method, judge);
        if view == View::Difference {
            mark_differences(&drawn, &wanted, rgba);
        }
        counts
    });
    PaneReport { judge, reference_work, drawn, selected, scene }
}

/// The reference's pixel-edge tests for `polygon`: its box's pixels on
/// the screen times its edges.
fn reference_work(polygon: &Polygon) -> u64 {
    let mut points = polygon.contours.iter().flatten();
    let Some(first) = points.next() else { return 0 };
    let (mut low, mut high) = ((first.x, first.y), (first.x, first.y));
    for p in points {
        low = (low.0.min(p.x), low.1.min(p.y));
        high = (high.0.max(p.x), high.1.max(p.y));
    }
    let pixels = |low: i32, high: i32, limit: i32| {
        let first = (low >> SUBPIXEL_BITS).clamp(0, limit);
        let last = ((high >> SUBPIXEL_BITS) + 1).clamp(0, limit);
        u64::try_from(last - first).unwrap_or(0)
    };
    pixels(low.0, high.0, SCREEN.width) * pixels(low.1, high.1, SCREEN.height) * polygon.vertex_count() as u64
}

/// Paints the selected polygon's pixels over the darkened scene.
fn mark_differences(drawn: &CoverageSink, wanted: &CoverageSink, rgba: &mut [u8]) {
    for y in 0..SCREEN.height {
        for x in 0..SCREEN.width {
            let mark = match (drawn.count(x, y) > 0, wanted.count(x, y) > 0) {
                (true, true) => AGREED,
                (true, false) => ADDED,
                (false, true) => MISSED,
                (false, false) => continue,
            };
            let at = (y * SCREEN.width + x) as usize * 4;
            rgba[at..at + 3].copy_from_slice(&mark);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use raster::{Point, Refusal};

    fn count_colour(rgba: &[u8], colour: [u8; 3]) -> usize {
        rgba.as_chunks::<4>().0.iter().filter(|&&[r, g, b, _]| [r, g, b] == colour).count()
    }

    #[test]
    fn the_picture_is_the_scene_in_the_vga_palette() {
        let mut explorer = Explorer::builtin("abrash38-1").unwrap();
        let mut rgba = Vec::new();
        let report = render(&mut explorer, MethodId::AbrashInt, View::Picture, Judge::Exact, &mut rgba);
        assert_eq!(rgba.len(), RGBA_BYTES);
        assert_eq!((report.drawn.polygons, report.drawn.refused), (2, 0));
        // Colour 3 (cyan: 6-bit levels 0, 42, 42) in the top right corner
        // the convex shape leaves, colour 6 (brown: 42, 21, 0) inside it.
        let at = |x: usize, y: usize| (y * 320 + x) * 4;
        assert_eq!(rgba[at(318, 5)..at(318, 5) + 4], [0, 168, 168, 255]);
        assert_eq!(rgba[at(100, 100)..at(100, 100) + 4], [168, 87, 0, 255]);
    }

    #[test]
    fn a_scene_file_shows_in_its_own_palette() {
        let mut explorer = Explorer::from_text("clear 3\npalette 3 63,0,63\n").unwrap();
        let mut rgba = Vec::new();
        render(&mut explorer, MethodId::Exact, View::Picture, Judge::Exact, &mut rgba);
        assert_eq!(rgba[..4], [255, 0, 255, 255]);
    }

    #[test]
    fn the_difference_view_marks_exactly_the_counted_pixels() {
        let mut explorer = Explorer::builtin("abrash38-3").unwrap();
        explorer.select(237);
        explorer.set_vertex(237, 0, Point::new(205 * 256 + 64, 80 * 256 + 200)).unwrap();
        let mut rgba = Vec::new();
        let report = render(&mut explorer, MethodId::AbrashInt, View::Difference, Judge::Exact, &mut rgba);
        let selected = report.selected.unwrap();
        assert!(selected.added > 0 && selected.missed > 0, "{selected:?}");
        assert_eq!(count_colour(&rgba, ADDED), selected.added);
        assert_eq!(count_colour(&rgba, MISSED), selected.missed);
    }

    #[test]
    fn exact_agrees_with_itself_and_abrash_int_with_its_own_convention() {
        let mut explorer = Explorer::builtin("abrash38-3").unwrap();
        let mut rgba = Vec::new();
        let exact = render(&mut explorer, MethodId::Exact, View::Difference, Judge::Exact, &mut rgba);
        assert_eq!((exact.scene.added, exact.scene.missed), (0, 0));
        let own = render(&mut explorer, MethodId::AbrashInt, View::Picture, Judge::OwnConvention, &mut rgba);
        assert_eq!((own.scene.added, own.scene.missed), (0, 0));
        let ours = render(&mut explorer, MethodId::AbrashInt, View::Picture, Judge::Exact, &mut rgba);
        assert!(ours.scene.added + ours.scene.missed > 0);
    }

    #[test]
    fn a_refusal_is_reported_for_the_polygon_and_the_scene() {
        let mut explorer =
            Explorer::from_text("poly color=4 0,0 100,0 100,100 0,100 | 10,10 20,10 20,20 10,20\n").unwrap();
        let mut rgba = Vec::new();
        let report = render(&mut explorer, MethodId::AbrashInt, View::Picture, Judge::Exact, &mut rgba);
        assert_eq!(report.selected.unwrap().refusal, Some(Refusal::MultipleContours));
        assert_eq!(report.scene.refusal, Some(Refusal::MultipleContours));
        assert_eq!((report.drawn.refused, report.selected.unwrap().added), (1, 0));
    }

    #[test]
    fn vertices_at_the_i32_limits_draw_or_are_refused_for_every_method() {
        let text = "poly color=4 -8388608,-8388608 8388607.99609375,-8388608 0,8388607.99609375\n";
        let mut explorer = Explorer::from_text(text).unwrap();
        let mut rgba = Vec::new();
        for method in MethodId::ALL {
            let report = render(&mut explorer, method, View::Difference, Judge::Exact, &mut rgba);
            assert_eq!(report.drawn.polygons, 1, "{method}");
            assert_eq!(report.scene.strays, 0, "{method}");
        }
    }

    #[test]
    fn scenes_too_big_for_the_reference_are_judged_against_exact() {
        let zigzag: Vec<String> = (0..1024).map(|i| format!("{:.3},{}", f64::from(i) * 0.3, (i % 2) * 200)).collect();
        let mut explorer = Explorer::from_text(&format!("poly color=3 {}\n", zigzag.join(" "))).unwrap();
        let mut rgba = Vec::new();
        let report = render(&mut explorer, MethodId::Wgt, View::Picture, Judge::OwnConvention, &mut rgba);
        assert_eq!(report.judge, Judge::Exact);
        assert!(report.reference_work > REFERENCE_BUDGET, "{}", report.reference_work);
        let mut small = Explorer::builtin("abrash38-3").unwrap();
        let report = render(&mut small, MethodId::Wgt, View::Picture, Judge::OwnConvention, &mut rgba);
        assert_eq!(report.judge, Judge::OwnConvention);
    }

    #[test]
    fn counts_follow_an_edit() {
        let mut explorer = Explorer::builtin("abrash38-3").unwrap();
        let mut rgba = Vec::new();
        let before = render(&mut explorer, MethodId::AbrashInt, View::Picture, Judge::Exact, &mut rgba).scene;
        explorer.set_vertex(237, 0, Point::new(205 * 256 + 64, 80 * 256 + 200)).unwrap();
        let after = render(&mut explorer, MethodId::AbrashInt, View::Picture, Judge::Exact, &mut rgba).scene;
        let mut fresh = Explorer::from_text(&explorer.scene_text()).unwrap();
        let recomputed = render(&mut fresh, MethodId::AbrashInt, View::Picture, Judge::Exact, &mut rgba).scene;
        assert_ne!(before, after);
        assert_eq!(after, recomputed);
    }
}
