//! The built-in book pages through the methods: what the chapters say the
//! book's own fillers do on them, and `exact` against the reference on
//! every polygon they hold.

use raster::methods::Exact;
use raster::reference::{self, SampleOffset};
use raster::{CoverageReport, CoverageSink, Framebuffer, Method, MethodId, Polygon, SCREEN};
use scenes::{builtin, Op};

#[test]
fn the_edge_table_filler_draws_listing_38_3_as_the_fast_convex_filler_does() {
    // Ch. 40: the same pixel choice as ch. 38 and 39.
    let scene = builtin::ABRASH38_3.scene();
    let (mut aet, mut convex) = (Framebuffer::new(SCREEN), Framebuffer::new(SCREEN));
    assert_eq!(scene.draw(MethodId::AbrashAet, &mut aet).refused, 0);
    scene.draw(MethodId::AbrashInt, &mut convex);
    assert!(aet == convex);
}

#[test]
fn integer_and_float_listing_38_3_differ_in_the_two_pixels_chapter_39_reports() {
    // Ch. 39: on Listing 38.3's screen the integer and float images differ
    // in two pixels, where the float product crept just over an integer
    // and `ceil` came out one too large. Both lie on hexagon 2 (colour
    // 2), whose edges pass exactly through them: X = 160 + 19 * 84 / 38
    // = 202 on its upper right edge (out, a right edge) and 76 + 19 * 84
    // / 38 = 118 on its lower left edge (in, a left edge). The integer
    // version is right in both.
    let scene = builtin::ABRASH38_3.scene();
    let (mut int, mut float) = (Framebuffer::new(SCREEN), Framebuffer::new(SCREEN));
    scene.draw(MethodId::AbrashInt, &mut int);
    scene.draw(MethodId::AbrashFloat, &mut float);
    let differing: Vec<(i32, i32, u8, u8)> = (0..SCREEN.height)
        .flat_map(|y| (0..SCREEN.width).map(move |x| (x, y)))
        .filter_map(|(x, y)| {
            let (a, b) = (int.get(x, y).unwrap(), float.get(x, y).unwrap());
            (a != b).then_some((x, y, a, b))
        })
        .collect();
    assert_eq!(differing, [(202, 35, 1, 2), (118, 165, 2, 1)]);
}

/// Every polygon of the built-in scenes, on the real screen. The Listing
/// 38.3 pages repeat the earlier pages' polygons, so each is drawn once.
#[test]
fn exact_matches_the_reference_on_every_polygon_of_the_builtin_scenes() {
    let mut polygons: Vec<Polygon> = Vec::new();
    for op in builtin::ALL.iter().flat_map(|page| page.scene().ops) {
        match op {
            Op::Fill(polygon) if !polygons.contains(&polygon) => polygons.push(polygon),
            _ => {}
        }
    }
    for polygon in &polygons {
        let mut expected = CoverageSink::new(SCREEN);
        reference::fill(polygon, SampleOffset::CENTRE, &mut expected);
        let mut drawn = CoverageSink::new(SCREEN);
        assert_eq!(Exact.fill(polygon, &mut drawn), Ok(()));
        let report = drawn.report(&expected);
        assert_eq!(report, CoverageReport::default(), "{polygon:?}\n{}", drawn.ascii_against(&expected));
    }
}
