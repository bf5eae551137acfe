//! Reusable polygon storage for the animations.

use alloc::vec;
use alloc::vec::Vec;

use raster::{Point, Polygon};

/// Reusable polygon storage: filled in place each frame, so that after the
/// first frame no vertex list is allocated again.
pub(super) struct Scratch {
    polygon: Polygon,
}

/// Vertices a scratch polygon holds without growing.
const SCRATCH_VERTICES: usize = 64;

impl Scratch {
    pub(super) fn new() -> Self {
        Self { polygon: Polygon { contours: vec![Vec::with_capacity(SCRATCH_VERTICES)], ..Polygon::default() } }
    }

    /// The scratch polygon set to one contour of `points` in `color`
    /// (even-odd rule).
    pub(super) fn polygon(&mut self, points: impl IntoIterator<Item = Point>, color: u8) -> &Polygon {
        self.polygon.contours.truncate(1);
        let contour = &mut self.polygon.contours[0];
        contour.clear();
        contour.extend(points);
        self.polygon.color = color;
        self.polygon.rule = raster::FillRule::EvenOdd;
        &self.polygon
    }
}

/// What one animation's `draw` puts on a fresh screen with fresh scratch.
#[cfg(test)]
pub(super) fn drawn_alone(
    draw: fn(u32, &dyn raster::Method, &mut Scratch, &mut raster::Framebuffer) -> crate::DrawReport,
    frame: u32,
    method: &dyn raster::Method,
) -> (raster::Framebuffer, crate::DrawReport) {
    let mut target = raster::Framebuffer::new(raster::SCREEN);
    let report = draw(frame, method, &mut Scratch::new(), &mut target);
    (target, report)
}
