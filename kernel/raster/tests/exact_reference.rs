//! `exact` and `fill_auto` against the brute-force reference, bit for bit,
//! on generated polygons of every kind and class.

mod exact_support;

use exact_support::{any_polygon, polygon_of, prop_assert_matches_reference, Kind, PX, TARGET};
use proptest::prelude::*;
use proptest::strategy::ValueTree;
use proptest::test_runner::TestRunner;
use raster::methods::exact::Exact;
use raster::{classify, fill_auto, Class, Method, MethodId, Point, Polygon};

fn exact(polygon: &Polygon, sink: &mut dyn raster::SpanSink) -> Result<(), raster::Refusal> {
    Exact.fill(polygon, sink)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1500))]

    #[test]
    fn exact_matches_reference_bit_for_bit((_kind, polygon) in any_polygon()) {
        prop_assert_matches_reference(exact, &polygon, TARGET)?;
    }

    /// Exact over the whole `i32` range, so huge polygons are never refused.
    #[test]
    fn exact_matches_reference_up_to_the_i32_extremes(polygon in polygon_of(Kind::Huge)) {
        prop_assert_matches_reference(exact, &polygon, TARGET)?;
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(500))]

    /// The dispatch is never wrong: whatever class a polygon falls in,
    /// `fill_auto` draws the reference's pixels. Adding a triangle far left
    /// of the target changes no pixel but sends any polygon down the
    /// active-edge path, so that path is held to triangles and monotone
    /// polygons too.
    #[test]
    fn fill_auto_matches_reference_in_every_class((kind, polygon) in any_polygon()) {
        let class = classify(&polygon);
        let expected_classes: &[Class] = match kind {
            Kind::Collinear => &[Class::Degenerate],
            Kind::Triangle => &[Class::Degenerate, Class::Triangle],
            Kind::Monotone => &[Class::Degenerate, Class::Triangle, Class::Convex],
            Kind::Star => &[Class::Degenerate, Class::Triangle, Class::Convex, Class::Simple],
            _ => &[Class::Degenerate, Class::Triangle, Class::Convex, Class::Simple, Class::Complex],
        };
        prop_assert!(expected_classes.contains(&class), "{kind:?} classified {class:?}");
        prop_assert_matches_reference(|p, s| fill_auto(p, s), &polygon, TARGET)?;

        let mut with_far_triangle = polygon.clone();
        with_far_triangle.contours.push(vec![Point::new(-1000 * PX, 0), Point::new(-999 * PX, 30 * PX), Point::new(-1001 * PX, 60 * PX)]);
        prop_assert_matches_reference(|p, s| fill_auto(p, s), &with_far_triangle, TARGET)?;
    }
}

/// The generators feed the dispatch test every class.
#[test]
fn generated_polygons_fall_in_every_class() {
    let mut runner = TestRunner::deterministic();
    let mut seen = std::collections::BTreeSet::new();
    for _ in 0..500 {
        let (_, polygon) = any_polygon().new_tree(&mut runner).unwrap().current();
        seen.insert(classify(&polygon));
    }
    let all = [Class::Degenerate, Class::Triangle, Class::Convex, Class::Simple, Class::Complex];
    assert_eq!(seen.into_iter().collect::<Vec<_>>(), all);
}

#[test]
fn exact_is_registered_as_ours() {
    let registered = "exact".parse::<MethodId>().expect("exact is a method").method();
    assert_eq!(registered.info().seed, "ours");
    assert_eq!(registered.info().handles, Class::Complex);
}
