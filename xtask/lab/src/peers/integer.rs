//! What the integer peers (Allegro 4, SDL2_gfx, GD, imageproc) are given,
//! and what they decline before they are called.
//!
//! Each takes one list of whole-pixel vertices (one contour) and fills it
//! by the parity of a row's sorted crossings (even-odd): our vertices are
//! rounded to the nearest whole pixel, halves up
//! ([`raster::Point::round_to_pixel`], as embedded-graphics is given
//! them). A polygon of several contours is declined, as is one with the
//! non-zero rule that is not simple ([`raster::classify`]: on a simple
//! polygon both rules fill the same pixels, so even-odd is its fill too),
//! and one with a vertex beyond the reach of the peer's arithmetic (each
//! peer says why its reach is what it is): the C libraries compute in
//! `int` and overflow past it, which C leaves undefined.

use raster::{classify, Class, FillRule, Polygon};

use crate::corpus::Family;

/// An integer peer's polygon: its one contour in whole pixels, or why the
/// peer declines it.
pub type Contour = Result<Vec<(i32, i32)>, &'static str>;

/// How far from the origin a peer's arithmetic holds, in whole pixels on
/// either axis, and what it declines beyond.
#[derive(Clone, Copy, Debug)]
pub struct Reach {
    pub pixels: i32,
    pub beyond: &'static str,
}

impl Reach {
    /// No limit of its own: a peer computing in `i32` and `f32` with no
    /// overflow at any rounded `i32` subpixel vertex (at most 2^23 px).
    pub const ANY: Reach = Reach { pixels: i32::MAX, beyond: "" };
}

/// The polygon's one contour in whole pixels, or why the peer declines it.
pub fn whole_pixel_contour(polygon: &Polygon, reach: Reach) -> Contour {
    let contour = match polygon.contours.as_slice() {
        [] => return Err("no contour"),
        [contour] => contour,
        _ => return Err("several contours (it fills one)"),
    };
    if contour.is_empty() {
        return Err("a contour without vertices");
    }
    let pixels: Vec<(i32, i32)> = contour
        .iter()
        .map(|p| {
            let q = p.round_to_pixel();
            (q.x, q.y)
        })
        .collect();
    if pixels.iter().any(|&(x, y)| x.unsigned_abs().max(y.unsigned_abs()) > reach.pixels.unsigned_abs()) {
        return Err(reach.beyond);
    }
    if polygon.rule == FillRule::NonZero && classify(polygon) == Class::Complex {
        return Err("the non-zero rule on a self-intersecting polygon (it fills by even-odd)");
    }
    Ok(pixels)
}

/// Whether a peer that takes polygons as `contour` makes them runs on
/// `family`: where it takes at least one (declining the others).
pub fn takes_any(family: &Family, contour: fn(&Polygon) -> Contour) -> bool {
    family.polygons.iter().any(|p| contour(p).is_ok())
}

/// What such a peer takes of `polygons`, each converted by `convert`
/// before a pass is timed; the ones it declines are left out.
pub fn inputs<T>(polygons: &[&Polygon], contour: fn(&Polygon) -> Contour, convert: fn(&[(i32, i32)]) -> T) -> Vec<T> {
    polygons.iter().filter_map(|p| contour(p).ok()).map(|c| convert(&c)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use raster::Point;

    const NEAR: Reach = Reach { pixels: 100, beyond: "too far" };

    #[test]
    fn vertices_are_rounded_to_the_nearest_pixel_halves_up() {
        let polygon = Polygon::new(vec![Point::new(127, 128), Point::new(-129, 640), Point::new(2560, -128)], 1);
        assert_eq!(whole_pixel_contour(&polygon, NEAR), Ok(vec![(0, 1), (-1, 3), (10, 0)]));
    }

    #[test]
    fn several_or_empty_contours_and_far_vertices_are_declined() {
        let triangle = Polygon::from_pixels(&[(0, 0), (100, 0), (0, 100)], (0, 0), 1);
        assert!(whole_pixel_contour(&triangle, NEAR).is_ok());
        let mut two = triangle.clone();
        two.contours.push(two.contours[0].clone());
        assert_eq!(whole_pixel_contour(&two, NEAR), Err("several contours (it fills one)"));
        assert_eq!(whole_pixel_contour(&Polygon::default(), NEAR), Err("no contour"));
        assert_eq!(whole_pixel_contour(&Polygon::new(vec![], 1), NEAR), Err("a contour without vertices"));
        let far = Polygon::from_pixels(&[(0, 0), (101, 0), (0, 100)], (0, 0), 1);
        assert_eq!(whole_pixel_contour(&far, NEAR), Err("too far"));
        assert!(whole_pixel_contour(&far, Reach::ANY).is_ok());
    }

    /// Even-odd and non-zero fill a simple polygon alike; a pentagram's
    /// centre is in by non-zero, out by even-odd.
    #[test]
    fn the_non_zero_rule_is_declined_only_where_it_differs() {
        let mut square = Polygon::from_pixels(&[(0, 0), (10, 0), (10, 10), (0, 10)], (0, 0), 1);
        square.rule = FillRule::NonZero;
        assert!(whole_pixel_contour(&square, NEAR).is_ok());
        let mut star = Polygon::from_pixels(&[(50, 0), (80, 90), (5, 35), (95, 35), (20, 90)], (0, 0), 1);
        assert!(whole_pixel_contour(&star, NEAR).is_ok());
        star.rule = FillRule::NonZero;
        assert!(whole_pixel_contour(&star, NEAR).is_err());
    }
}
