//! What the integer peers (Allegro 4, SDL2_gfx, GD, imageproc) are given,
//! what they decline before they are called, and how the lab drives them
//! ([`IntegerPeer`], over each one's [`IntegerTarget`]).
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

use std::hint::black_box;
use std::marker::PhantomData;
use std::slice;

use raster::{classify, Class, FillRule, Polygon, SpanSink};

use super::peer::{Peer, PeerInfo};
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

/// An integer peer's target, as the lab drives every one of them: made
/// empty, filled with polygons converted from whole-pixel contours, read
/// back as spans. Each peer's file implements it over its library.
pub trait IntegerTarget: Sized + 'static {
    /// A polygon as the library takes it.
    type Input: 'static;

    /// The polygon as the peer is given it, or why it is declined:
    /// [`whole_pixel_contour`] within the library's reach, and whatever
    /// else the library refuses.
    fn contour(polygon: &Polygon) -> Contour;

    /// The contour as the library takes it.
    fn input(contour: &[(i32, i32)]) -> Self::Input;

    /// An empty 320x200 target.
    fn new() -> Result<Self, &'static str>;

    /// Fills each of `polygons`; the first error the library returns, if
    /// it returns any.
    fn fill(&mut self, polygons: &[Self::Input]) -> Result<(), &'static str>;

    /// The painted pixels, as spans into `sink`.
    fn emit_runs(&self, color: u8, sink: &mut dyn SpanSink);
}

/// An integer peer: what it is, and the canvas it fills.
pub struct IntegerPeer<C> {
    info: PeerInfo,
    canvas: PhantomData<fn() -> C>,
}

impl<C> IntegerPeer<C> {
    pub const fn new(info: PeerInfo) -> Self {
        Self { info, canvas: PhantomData }
    }
}

impl<C: IntegerTarget> Peer for IntegerPeer<C> {
    fn info(&self) -> &PeerInfo {
        &self.info
    }

    /// Where it takes at least one polygon (declining the others).
    fn takes(&self, family: &Family) -> bool {
        family.polygons.iter().any(|p| C::contour(p).is_ok())
    }

    fn draw(&self, polygon: &Polygon, sink: &mut dyn SpanSink) -> Result<(), &'static str> {
        let input = C::input(&C::contour(polygon)?);
        let mut canvas = C::new()?;
        canvas.fill(slice::from_ref(&input))?;
        canvas.emit_runs(polygon.color, sink);
        Ok(())
    }

    /// What it takes of `polygons`, converted before the pass; the ones it
    /// declines are left out.
    fn pass<'a>(&self, polygons: &[&'a Polygon]) -> Box<dyn FnMut() + 'a> {
        let inputs: Vec<C::Input> = polygons.iter().filter_map(|p| C::contour(p).ok()).map(|c| C::input(&c)).collect();
        let mut canvas = C::new().unwrap_or_else(|why| panic!("{}: {why}", self.info.name));
        Box::new(move || {
            // An error costs what it costs, as a refusal does.
            let _ = canvas.fill(&inputs);
            black_box(&mut canvas);
        })
    }
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
