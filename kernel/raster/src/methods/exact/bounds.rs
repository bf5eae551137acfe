//! The box of a polygon's vertices: found once, when `fill_auto` chooses
//! between the two general paths by it, and handed to the one chosen,
//! which clips and sizes its work by it.

use crate::geometry::{FillRule, Point, PolygonRef};

/// The widest a polygon the edge flags take may be, in subpixels (512
/// px, a `ShortEdge`'s width).
const WIDEST: i64 = 1 << 17;

/// The box of a polygon's vertices, in subpixels.
#[derive(Clone, Copy, Debug)]
pub struct Bounds {
    pub(super) min: Point,
    pub(super) max: Point,
}

impl Bounds {
    /// The box of `polygon`'s vertices (an empty one at the origin for a
    /// polygon without any, which meets no row).
    #[inline(always)]
    pub(super) fn of<C: AsRef<[Point]>>(polygon: PolygonRef<'_, C>) -> Self {
        let mut vertices = polygon.contours.iter().flat_map(AsRef::as_ref);
        let Some(&first) = vertices.next() else { return Self { min: Point::new(0, 0), max: Point::new(0, 0) } };
        let (mut min, mut max) = (first, first);
        // On the host, contour by contour (the first vertex again), each a
        // loop over a slice, which the compiler vectorizes, as it did not
        // one loop over all the vertices; the kernel has no vector unit to
        // use, and `cargo xtask kbench` counted more instructions with the
        // host's loops (both measured in
        // docs/lab-history.md#2026-11-29-no-classification-for-several-contours-b3d2f46).
        #[cfg(not(target_os = "none"))]
        for contour in polygon.contours {
            for p in contour.as_ref() {
                (min.x, min.y, max.x, max.y) = (min.x.min(p.x), min.y.min(p.y), max.x.max(p.x), max.y.max(p.y));
            }
        }
        #[cfg(target_os = "none")]
        for p in vertices {
            (min.x, min.y, max.x, max.y) = (min.x.min(p.x), min.y.min(p.y), max.x.max(p.x), max.y.max(p.y));
        }
        Self { min, max }
    }

    /// Whether the edge flags take a polygon of this box, with `edges`
    /// edges, under `rule`.
    #[inline(always)]
    pub(super) fn takes(&self, edges: usize, rule: FillRule) -> bool {
        i64::from(self.max.x) - i64::from(self.min.x) < WIDEST && (rule == FillRule::EvenOdd || edges < 256)
    }

    /// The box's height, in whole pixels (what the kernel's choice of path
    /// weighs).
    #[cfg(target_os = "none")]
    #[inline(always)]
    pub(super) fn rows(&self) -> i64 {
        (i64::from(self.max.y) - i64::from(self.min.y)) >> 8
    }

    /// The box's words of flags: its height in whole pixels times the
    /// words of a row (64 pixels each), what the host's choice of path
    /// weighs.
    #[cfg(not(target_os = "none"))]
    #[inline(always)]
    pub(super) fn words(&self) -> i64 {
        let (width, height) =
            (i64::from(self.max.x) - i64::from(self.min.x), i64::from(self.max.y) - i64::from(self.min.y));
        (height >> 8) * ((width >> 14) + 1)
    }
}
