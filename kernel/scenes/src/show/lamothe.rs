//! LaMothe's rotation test ("Solid Filled Polygons"; `docs/methods.md#lamothe`): "it's always
//! a good idea to test if it can successfully render an object as it
//! rotates ... by rotating an object, you get all kinds of tweaked-out
//! values. If the function can hang through a complete 360-degree rotation,
//! you know it's good to go!"
//!
//! In the middle, his `Draw_Filled_Polygon2D` example square, (-50,-50) ..
//! (50,50), at the centre of the screen as his (320,240) is the centre of
//! 640x480; its 100 pixels fit our 200 rows at any angle, so it keeps his
//! size. Inside it an octagon and a triangle turn the other ways, and four
//! small squares orbit the three on an ellipse, spinning as they go. Every
//! shape makes a whole number of turns over [`FRAMES`], so frame `FRAMES`
//! is frame 0 again. Vertices are rotated at 1/256 px, so the classic
//! methods get his "tweaked-out values" after their own rounding. Everything
//! stays on the screen and out of the label rows: his
//! `Draw_Filled_Polygon2D` does not clip, "all vertex points must be within
//! the clipping region".

use super::scratch::Scratch;
use super::trig::{angle_at, offset, polar, rotate, TURN};
use crate::scene::DrawReport;
use raster::{Framebuffer, Method, Point};

/// Frames in one full turn of the big square (7.3 s at 35 frames a second).
pub(super) const FRAMES: u32 = 256;

/// The screen's centre, where everything turns.
const CENTRE: Point = Point::from_pixels(160, 100);

/// LaMothe's `square_vertices`, in pixels.
const SQUARE: [(i32, i32); 4] = [(-50, -50), (50, -50), (50, 50), (-50, 50)];

/// Turns over [`FRAMES`] of each shape (negative: counter-clockwise).
const SQUARE_TURNS: i32 = 1;
const OCTAGON_TURNS: i32 = -2;
const TRIANGLE_TURNS: i32 = 3;
const ORBIT_TURNS: i32 = -1;
const SPIN_TURNS: i32 = 3;

/// Circumradii of the octagon and the triangle, radii of the orbit, and the
/// orbiting squares' scale (in fiftieths of his square), in pixels.
const OCTAGON_RADIUS: i32 = 44;
const TRIANGLE_RADIUS: i32 = 30;
const ORBIT_RADII: (i32, i32) = (124, 64);
const SMALL_SQUARE_FIFTIETHS: i32 = 15;

/// Colours: light blue square, yellow octagon, light red triangle, and the
/// orbiting squares green, magenta, cyan, orange.
const SQUARE_COLOR: u8 = 9;
const OCTAGON_COLOR: u8 = 14;
const TRIANGLE_COLOR: u8 = 12;
const ORBIT_COLORS: [u8; 4] = [10, 13, 11, 42];

/// Draws frame `frame` of the rotation test with `method`.
pub(super) fn draw(frame: u32, method: &dyn Method, scratch: &mut Scratch, target: &mut Framebuffer) -> DrawReport {
    let mut report = DrawReport::default();
    let angle = |turns| angle_at(frame, FRAMES, turns);

    let square = SQUARE.map(|(x, y)| Point::from_pixels(x, y));
    report.record(method.fill(scratch.polygon(turned(CENTRE, &square, angle(SQUARE_TURNS)), SQUARE_COLOR), target));
    let octagon = regular(CENTRE, OCTAGON_RADIUS, 8, angle(OCTAGON_TURNS));
    report.record(method.fill(scratch.polygon(octagon, OCTAGON_COLOR), target));
    let triangle = regular(CENTRE, TRIANGLE_RADIUS, 3, angle(TRIANGLE_TURNS));
    report.record(method.fill(scratch.polygon(triangle, TRIANGLE_COLOR), target));

    let small = square.map(|p| Point::new(p.x * SMALL_SQUARE_FIFTIETHS / 50, p.y * SMALL_SQUARE_FIFTIETHS / 50));
    let radii = (ORBIT_RADII.0 * raster::SUBPIXEL_ONE, ORBIT_RADII.1 * raster::SUBPIXEL_ONE);
    for (k, color) in (0..).zip(ORBIT_COLORS) {
        let at = offset(CENTRE, polar(radii, angle(ORBIT_TURNS).wrapping_add(TURN / 8 + k * TURN / 4)));
        report.record(method.fill(scratch.polygon(turned(at, &small, angle(SPIN_TURNS)), color), target));
    }
    report
}

/// `vertices` turned by `angle` about their origin, then moved to `centre`
/// (his `Rotate_Polygon2D` with `x0`, `y0`).
fn turned(centre: Point, vertices: &[Point], angle: u32) -> impl Iterator<Item = Point> + '_ {
    vertices.iter().map(move |&v| offset(centre, rotate(v, angle)))
}

/// A regular polygon of `sides` vertices on the circle of `radius` pixels
/// about `centre`, its first vertex at `angle`.
pub(super) fn regular(centre: Point, radius: i32, sides: u32, angle: u32) -> impl Iterator<Item = Point> {
    let radius = radius * raster::SUBPIXEL_ONE;
    (0..sides).map(move |k| offset(centre, polar((radius, radius), angle.wrapping_add(k * TURN / sides))))
}

#[cfg(test)]
mod tests {
    use super::*;
    use alloc::vec::Vec;
    use raster::methods;
    use raster::SCREEN;

    fn frame(frame: u32, method: &dyn Method) -> (Framebuffer, DrawReport) {
        super::super::scratch::drawn_alone(draw, frame, method)
    }

    #[test]
    fn shapes_stay_clear_of_the_label_rows() {
        for f in 0..FRAMES {
            let (target, _) = frame(f, &methods::Exact);
            let rows = target.pixels().chunks(SCREEN.width as usize);
            for (y, row) in rows.enumerate().filter(|(y, _)| !(12..188).contains(y)) {
                assert!(row.iter().all(|&p| p == 0), "frame {f} draws on row {y}");
            }
        }
    }

    #[test]
    fn regular_polygons_close_on_their_circle() {
        let octagon: Vec<Point> = regular(Point::new(0, 0), 10, 8, 0).collect();
        assert_eq!(octagon[0], Point::from_pixels(10, 0));
        assert_eq!(octagon[2], Point::from_pixels(0, 10));
        assert_eq!(octagon[4], Point::from_pixels(-10, 0));
        // 2560 * 11585 / 16384 = 1810.2
        assert_eq!(octagon[1], Point::new(1810, 1810));
    }
}
