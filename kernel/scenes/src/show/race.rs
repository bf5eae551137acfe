//! The method race: one slowly turning scene, drawn by each method of
//! [`MethodId::ALL`] in turn for [`FRAMES_PER_METHOD`] frames, with the
//! cycles each draw took in the label.
//!
//! The scene is one every method fills: single-contour convex polygons,
//! triangles and quads. In the middle a wheel of [`SPOKES`] thin triangles
//! in the palette's 24 hues shares its edges and its wobbling hub, so each
//! method's rounding shows as gaps or overlaps along the spokes and at the
//! hub (the exact method draws every pixel of the wheel once); on each side
//! two columns of small squares spin one way and the other. It turns once
//! over [`FRAMES`], slowly enough that the pixels a method gains or loses
//! stay visible while it is on.

use super::lamothe::regular;
use super::pace::FRAMES_PER_SECOND;
use super::ramp::Ramp;
use super::scratch::Scratch;
use super::trig::{angle_at, offset, polar, TURN};
use crate::scene::DrawReport;
use raster::{Framebuffer, Method, MethodId, Point, SUBPIXEL_ONE};

/// How long each method is on: 2 seconds.
const FRAMES_PER_METHOD: u32 = 2 * FRAMES_PER_SECOND;
/// Every method once.
pub(super) const FRAMES: u32 = FRAMES_PER_METHOD * MethodId::ALL.len() as u32;

/// Triangles in the wheel: one per hue of the palette's first ring
/// (entries 32-55).
const SPOKES: u32 = 24;
const FIRST_HUE: u8 = 32;
/// The wheel's centre and radius, and how far its hub wobbles, in pixels.
const WHEEL_CENTRE: (i32, i32) = (160, 100);
const WHEEL_RADIUS: i32 = 86;
const HUB_WOBBLE: i32 = 5;

/// The squares' columns (x of each, in pixels, left side then right side)
/// and rows (y of each), and their circumradius in pixels.
const SQUARE_COLUMNS: [i32; 4] = [22, 56, 264, 298];
const SQUARE_ROWS: [i32; 5] = [30, 65, 100, 135, 170];
const SQUARE_RADIUS: i32 = 16;

/// The method whose turn it is at `frame` (modulo [`FRAMES`]).
pub(super) fn method_at(frame: u32) -> MethodId {
    MethodId::ALL[(frame / FRAMES_PER_METHOD) as usize % MethodId::ALL.len()]
}

/// Draws frame `frame` of the race scene with `method`.
pub(super) fn draw(frame: u32, method: &dyn Method, scratch: &mut Scratch, target: &mut Framebuffer) -> DrawReport {
    let mut report = DrawReport::default();
    let turn = angle_at(frame, FRAMES, 1);
    let back = angle_at(frame, FRAMES, -1);

    let centre = Point::from_pixels(WHEEL_CENTRE.0, WHEEL_CENTRE.1);
    let wobble = polar((HUB_WOBBLE * SUBPIXEL_ONE, HUB_WOBBLE * SUBPIXEL_ONE), angle_at(frame, FRAMES, 3));
    let hub = offset(centre, wobble);
    let rim = |k: u32| {
        let radius = WHEEL_RADIUS * SUBPIXEL_ONE;
        offset(centre, polar((radius, radius), turn.wrapping_add(k * TURN / SPOKES)))
    };
    for (k, hue) in (0..SPOKES).zip(FIRST_HUE..) {
        report.record(method.fill(scratch.polygon([hub, rim(k), rim(k + 1)], hue), target));
    }

    for (column, &x) in SQUARE_COLUMNS.iter().enumerate() {
        for (row, &y) in SQUARE_ROWS.iter().enumerate() {
            let spin = if (row + column) % 2 == 0 { turn } else { back };
            let color = if column < 2 { Ramp::Gold } else { Ramp::Blue }.color(15 + 4 * row as i32);
            let square = regular(Point::from_pixels(x, y), SQUARE_RADIUS, 4, spin.wrapping_add(TURN / 8));
            report.record(method.fill(scratch.polygon(square, color), target));
        }
    }
    report
}

#[cfg(test)]
mod tests {
    use super::*;
    use alloc::vec::Vec;

    fn frame(frame: u32, method: &dyn Method) -> (Framebuffer, DrawReport) {
        super::super::scratch::drawn_alone(draw, frame, method)
    }

    #[test]
    fn the_methods_take_turns() {
        let order: Vec<MethodId> = (0..FRAMES).step_by(FRAMES_PER_METHOD as usize).map(method_at).collect();
        assert_eq!(order, MethodId::ALL);
        assert_eq!(method_at(FRAMES_PER_METHOD - 1), MethodId::ALL[0]);
        assert_eq!(method_at(FRAMES), MethodId::ALL[0]);
    }

    #[test]
    fn the_exact_wheel_has_no_gaps() {
        // Every pixel whose centre is well inside the rim is drawn.
        for f in (0..FRAMES).step_by(10) {
            let (target, _) = frame(f, &raster::methods::Exact);
            let r = WHEEL_RADIUS - 2;
            for y in -r..=r {
                for x in -r..=r {
                    if x * x + y * y < r * r {
                        let pixel = target.get(WHEEL_CENTRE.0 + x, WHEEL_CENTRE.1 + y).unwrap();
                        assert!((FIRST_HUE..FIRST_HUE + SPOKES as u8).contains(&pixel), "frame {f} at {x},{y}");
                    }
                }
            }
        }
    }

    #[test]
    fn methods_differ_on_the_same_frame() {
        let exact = frame(100, &raster::methods::Exact).0;
        let lamothe = frame(100, &raster::methods::Lamothe).0;
        assert_ne!(exact, lamothe);
    }
}
