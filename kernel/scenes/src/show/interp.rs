//! Attribute interpolation over triangles, written once for every shaded
//! entry: Pendleton's "any value you want to interpolate for each span or
//! each pixel can be treated just like the Z coordinate".
//!
//! Coverage is the fill method's business: the triangle goes to
//! [`Method::fill`] as an ordinary polygon, and the spans it emits go to a
//! private [`SpanSink`] that evaluates every attribute at each span pixel's
//! centre (x + 0.5, y + 0.5) from the triangle's plane equation and hands
//! them to a per-pixel shader. So every method of the lab can draw a
//! Gouraud-shaded, texture-mapped or Z-buffered triangle, each with its own
//! idea of which pixels are in.
//!
//! Arithmetic: integers only. With vertices `p0, p1, p2` in subpixels,
//! twice the signed area `A` and an attribute's values `a0, a1, a2`, the
//! attribute at a point `p` is `a0 + (Ax * (p.x - p0.x) + Ay * (p.y -
//! p0.y)) / A` with the `i64` plane coefficients
//! `Ax = (a1 - a0)(y2 - y0) - (a2 - a0)(y1 - y0)` and
//! `Ay = (a2 - a0)(x1 - x0) - (a1 - a0)(x2 - x0)`: the barycentric weights
//! folded into one numerator, stepped by `256 * Ax` from pixel to pixel and
//! divided once per pixel, rounding to nearest (halves up), so a value is
//! exact at every pixel centre. Vertices and attributes are bounded by
//! [`LIMIT`] and pixels by [`PIXEL_LIMIT`], which keeps every numerator
//! below 2^63 (see [`Plane::new`]); a triangle beyond the bounds is refused
//! as [`Refusal::OutOfRange`], a triangle of zero area draws nothing.

use super::scratch::Scratch;
use super::trig::div_round;
use crate::scene::DrawReport;
use raster::{Framebuffer, Method, Point, Refusal, Size, SpanSink, SUBPIXEL_BITS, SUBPIXEL_ONE};

/// Bound on vertex coordinates (in subpixels, so 2048 px) and on
/// attribute values: both lie in `-LIMIT..=LIMIT`.
const LIMIT: i32 = 1 << 19;
/// Pixels at or beyond this column or row are never shaded, whatever the
/// target's size, so pixel centres stay within [`LIMIT`] subpixels.
const PIXEL_LIMIT: i32 = LIMIT >> SUBPIXEL_BITS;

/// A triangle corner: where it is and the `N` attributes it carries.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Vertex<const N: usize> {
    pub(super) at: Point,
    pub(super) attrs: [i32; N],
}

impl<const N: usize> Vertex<N> {
    pub(super) const fn new(at: Point, attrs: [i32; N]) -> Self {
        Self { at, attrs }
    }
}

/// A triangle's attributes as planes over the screen: attribute `i` at
/// subpixel offset `(dx, dy)` from the first vertex is
/// `(base[i] + ax[i] * dx + ay[i] * dy) / area` (see the module comment).
struct Plane<const N: usize> {
    origin: Point,
    /// Twice the triangle's area, in square subpixels; always positive.
    area: i64,
    /// `a0 * area` for each attribute.
    base: [i64; N],
    ax: [i64; N],
    ay: [i64; N],
}

impl<const N: usize> Plane<N> {
    /// The planes of `v`, `None` when the triangle has no area.
    ///
    /// Bounds, with coordinates and attributes within `±2^19` (so their
    /// differences within `±2^20`): `|area| <= 2 * 2^20 * 2^20 = 2^41`,
    /// `|ax|, |ay| <= 2^41`, and a pixel centre below [`PIXEL_LIMIT`] is
    /// within `2^20` subpixels of the first vertex; so a numerator is at
    /// most `2^19 * 2^41 + 2 * 2^41 * 2^20 + area / 2 < 2^63`.
    fn new(v: &[Vertex<N>; 3]) -> Option<Self> {
        let [p0, p1, p2] = [v[0].at, v[1].at, v[2].at];
        let (x1, y1) = (i64::from(p1.x) - i64::from(p0.x), i64::from(p1.y) - i64::from(p0.y));
        let (x2, y2) = (i64::from(p2.x) - i64::from(p0.x), i64::from(p2.y) - i64::from(p0.y));
        let signed_area = x1 * y2 - x2 * y1;
        if signed_area == 0 {
            return None;
        }
        // Orient the triangle so that the area is positive: the planes are
        // the same, with numerator and denominator both negated.
        let sign = signed_area.signum();
        let area = signed_area.abs();
        let mut plane = Self { origin: p0, area, base: [0; N], ax: [0; N], ay: [0; N] };
        for i in 0..N {
            let a0 = i64::from(v[0].attrs[i]);
            let (a1, a2) = (i64::from(v[1].attrs[i]) - a0, i64::from(v[2].attrs[i]) - a0);
            plane.base[i] = a0 * area;
            plane.ax[i] = sign * (a1 * y2 - a2 * y1);
            plane.ay[i] = sign * (a2 * x1 - a1 * x2);
        }
        Some(plane)
    }
}

/// Whether every coordinate and attribute of `v` is within [`LIMIT`].
fn in_range<const N: usize>(v: &[Vertex<N>; 3]) -> bool {
    let fits = |value: i32| (-LIMIT..=LIMIT).contains(&value);
    v.iter().all(|vertex| fits(vertex.at.x) && fits(vertex.at.y) && vertex.attrs.iter().all(|&a| fits(a)))
}

/// The sink a method fills the triangle into: each pixel of each span,
/// clipped to the target (and to [`PIXEL_LIMIT`]), gets its attributes
/// evaluated and goes to the shader, whose colour is written to the target.
/// A span that breaks the sink contract is counted in the target's
/// `stray_spans`, as the target itself would count it.
struct ShadingSink<'a, const N: usize, F> {
    plane: &'a Plane<N>,
    target: &'a mut Framebuffer,
    shade: &'a mut F,
}

impl<const N: usize, F: FnMut(i32, i32, &[i32; N]) -> Option<u8>> SpanSink for ShadingSink<'_, N, F> {
    fn size(&self) -> Size {
        self.target.size()
    }

    fn span(&mut self, y: i32, x_start: i32, x_end: i32, _color: u8) {
        let size = self.target.size();
        if !size.holds_span(y, x_start, x_end) {
            self.target.note_stray_span();
        }
        let (width, height) = (size.width.min(PIXEL_LIMIT), size.height.min(PIXEL_LIMIT));
        let (x_start, x_end) = (x_start.max(0), x_end.min(width));
        if !(0..height).contains(&y) || x_start >= x_end {
            return;
        }
        let plane = self.plane;
        // The first pixel centre, relative to the first vertex.
        let centre = |pixel: i32, origin: i32| i64::from(pixel * SUBPIXEL_ONE + SUBPIXEL_ONE / 2) - i64::from(origin);
        let (dx, dy) = (centre(x_start, plane.origin.x), centre(y, plane.origin.y));
        let mut numerators = [0; N];
        for (i, numerator) in numerators.iter_mut().enumerate() {
            *numerator = plane.base[i] + plane.ax[i] * dx + plane.ay[i] * dy;
        }
        let mut attrs = [0; N];
        for x in x_start..x_end {
            for i in 0..N {
                // Within ±LIMIT + 1/2, so the quotient fits an i32.
                attrs[i] = div_round(numerators[i], plane.area) as i32;
                numerators[i] += plane.ax[i] * i64::from(SUBPIXEL_ONE);
            }
            if let Some(color) = (self.shade)(x, y, &attrs) {
                self.target.span(y, x, x + 1, color);
            }
        }
    }
}

/// Draws shaded triangles with one method into one target, counting what
/// it did in a [`DrawReport`] as [`Scene::draw`](crate::Scene::draw) does.
/// Allocates nothing: the triangle is built in the [`Scratch`] polygon.
pub(super) struct Painter<'a> {
    method: &'a dyn Method,
    scratch: &'a mut Scratch,
    target: &'a mut Framebuffer,
    report: DrawReport,
}

impl<'a> Painter<'a> {
    pub(super) fn new(method: &'a dyn Method, scratch: &'a mut Scratch, target: &'a mut Framebuffer) -> Self {
        Self { method, scratch, target, report: DrawReport::default() }
    }

    /// Fills the triangle `v` with the painter's method; every pixel the
    /// method covers is set to `shade(x, y, attributes at its centre)`, or
    /// left as it is when that is `None`. A triangle of zero area draws
    /// nothing; one beyond [`LIMIT`] is refused.
    pub(super) fn triangle<const N: usize, F>(&mut self, v: &[Vertex<N>; 3], shade: &mut F)
    where
        F: FnMut(i32, i32, &[i32; N]) -> Option<u8>,
    {
        let result = if in_range(v) {
            match Plane::new(v) {
                Some(plane) => {
                    let polygon = self.scratch.polygon(v.iter().map(|vertex| vertex.at), 0);
                    self.method.fill(polygon, &mut ShadingSink { plane: &plane, target: self.target, shade })
                }
                None => Ok(()),
            }
        } else {
            Err(Refusal::OutOfRange)
        };
        self.report.record(result);
    }

    /// Fills the quadrilateral `v` as the two triangles `v0 v1 v2` and
    /// `v0 v2 v3`, which share the diagonal `v0 v2`.
    pub(super) fn quad<const N: usize, F>(&mut self, v: &[Vertex<N>; 4], shade: &mut F)
    where
        F: FnMut(i32, i32, &[i32; N]) -> Option<u8>,
    {
        self.triangle(&[v[0], v[1], v[2]], shade);
        self.triangle(&[v[0], v[2], v[3]], shade);
    }

    /// What was drawn so far.
    pub(super) fn report(&self) -> DrawReport {
        self.report
    }
}

#[cfg(test)]
mod tests {
    use alloc::vec;
    use alloc::vec::Vec;

    use super::*;
    use raster::methods::Exact;
    use raster::{MethodId, MethodInfo, Polygon, SCREEN};

    fn px(x: i32, y: i32) -> Point {
        Point::from_pixels(x, y)
    }

    /// Runs `draw` with a painter over a fresh screen; the frame and report.
    fn paint(method: &dyn Method, draw: impl FnOnce(&mut Painter)) -> (Framebuffer, DrawReport) {
        let (mut scratch, mut target) = (Scratch::new(), Framebuffer::new(SCREEN));
        let mut painter = Painter::new(method, &mut scratch, &mut target);
        draw(&mut painter);
        let report = painter.report();
        (target, report)
    }

    #[test]
    fn a_constant_attribute_is_that_constant_everywhere() {
        let v = [px(10, 10), px(300, 40), px(90, 190)].map(|at| Vertex::new(at, [-77, 123_456]));
        let mut pixels = 0;
        let (target, report) = paint(&Exact, |p| {
            p.triangle(&v, &mut |_, _, attrs: &[i32; 2]| {
                assert_eq!(*attrs, [-77, 123_456]);
                pixels += 1;
                Some(5)
            })
        });
        assert_eq!(report, DrawReport { polygons: 1, ..DrawReport::default() });
        assert!(pixels > 10_000);
        assert_eq!(target.pixels().iter().filter(|&&p| p == 5).count(), pixels);
    }

    #[test]
    fn a_linear_ramp_is_exact_at_pixel_centres() {
        // Attribute 0 is 256 * x, attribute 1 is 3 * y - 2 * x (in pixels,
        // at the point itself); a centre's values are those at (x + 0.5,
        // y + 0.5), rounded half up.
        let corners = [(-5, -3), (330, 20), (40, 230)];
        let v = corners.map(|(x, y)| Vertex::new(px(x, y), [256 * x, 3 * y - 2 * x]));
        let mut pixels = 0;
        paint(&Exact, |p| {
            p.triangle(&v, &mut |x, y, attrs: &[i32; 2]| {
                // 3 (y + 0.5) - 2 (x + 0.5) = 3y - 2x + 0.5, rounded up.
                assert_eq!(*attrs, [256 * x + 128, 3 * y - 2 * x + 1], "at ({x}, {y})");
                pixels += 1;
                None
            })
        });
        assert!(pixels > 30_000);
    }

    #[test]
    fn values_round_to_nearest_between_subpixel_vertices() {
        // Attribute = subpixel x of the point: at a centre, 256 x + 128,
        // whatever fraction the vertices carry.
        let points = [Point::new(1001, 519), Point::new(60_013, 3_000), Point::new(7_777, 40_404)];
        let v = points.map(|at| Vertex::new(at, [at.x, at.y / 3]));
        paint(&Exact, |p| {
            p.triangle(&v, &mut |x, y, attrs: &[i32; 2]| {
                assert_eq!(attrs[0], 256 * x + 128);
                // (256 y + 128) / 3 to nearest, halves up.
                assert_eq!(attrs[1], (256 * y + 128 + 1) / 3, "at ({x}, {y})");
                None
            })
        });
    }

    #[test]
    fn triangles_sharing_an_edge_shade_each_pixel_once() {
        let corners = [px(20, 15), px(250, 30), px(280, 170), px(35, 190)];
        let v = corners.map(|at| Vertex::new(at, [0]));
        let mut counts = vec![0u8; (SCREEN.width * SCREEN.height) as usize];
        paint(&Exact, |p| {
            p.quad(&v, &mut |x, y, _: &[i32; 1]| {
                counts[(y * SCREEN.width + x) as usize] += 1;
                Some(1)
            })
        });
        let mut whole = Framebuffer::new(SCREEN);
        Exact.fill(&Polygon::new(corners.to_vec(), 1), &mut whole).unwrap();
        let drawn: Vec<u8> = counts.iter().map(|&c| u8::from(c > 0)).collect();
        assert!(counts.iter().all(|&c| c <= 1), "a pixel was shaded twice");
        assert_eq!(drawn, whole.pixels(), "the quad's pixels differ from one fill of it");
    }

    #[test]
    fn a_zero_area_triangle_draws_nothing() {
        for points in [[px(10, 10), px(50, 50), px(90, 90)], [px(7, 7); 3]] {
            let v = points.map(|at| Vertex::new(at, [1]));
            for method in MethodId::ALL.map(MethodId::method) {
                let (target, report) = paint(method, |p| p.triangle(&v, &mut |_, _, _: &[i32; 1]| Some(9)));
                assert!(target.pixels().iter().all(|&p| p == 0), "{} drew a line", method.info().name);
                assert_eq!(report, DrawReport { polygons: 1, ..DrawReport::default() });
            }
        }
    }

    #[test]
    fn triangles_beyond_the_limits_are_refused() {
        let far = [px(0, 0), Point::new(LIMIT + 1, 0), px(0, 100)].map(|at| Vertex::new(at, [0]));
        let loud = [px(0, 0), px(100, 0), px(0, 100)].map(|at| Vertex::new(at, [-LIMIT - 1]));
        let (target, report) = paint(&Exact, |p| {
            p.triangle(&far, &mut |_, _, _: &[i32; 1]| Some(1));
            p.triangle(&loud, &mut |_, _, _: &[i32; 1]| Some(1));
        });
        assert!(target.pixels().iter().all(|&p| p == 0));
        assert_eq!(report, DrawReport { polygons: 2, refused: 2, first_refusal: Some(Refusal::OutOfRange) });
    }

    #[test]
    fn extreme_but_allowed_triangles_do_not_overflow() {
        let corners = [Point::new(-LIMIT, -LIMIT), Point::new(LIMIT, -LIMIT + 1), Point::new(3, LIMIT)];
        let values = [[LIMIT, -LIMIT], [-LIMIT, LIMIT], [LIMIT, LIMIT]];
        let v = [0, 1, 2].map(|i| Vertex::new(corners[i], values[i]));
        let mut pixels = 0;
        paint(&Exact, |p| {
            p.triangle(&v, &mut |_, _, attrs: &[i32; 2]| {
                assert!(attrs.iter().all(|a| a.abs() <= LIMIT));
                pixels += 1;
                None
            })
        });
        assert_eq!(pixels, SCREEN.width * SCREEN.height);
    }

    /// Emits spans everywhere but where it should: off every edge of the
    /// target, empty, reversed, at the `i32` extremes.
    struct Stray;

    impl Method for Stray {
        fn info(&self) -> &'static MethodInfo {
            Exact.info()
        }

        fn fill(&self, _: &Polygon, sink: &mut dyn SpanSink) -> Result<(), Refusal> {
            let size = sink.size();
            for (y, x0, x1) in [
                (-1, 0, 10),
                (size.height, 0, 10),
                (i32::MIN, i32::MIN, i32::MAX),
                (5, -100, 3),
                (6, size.width - 2, i32::MAX),
                (7, 9, 4),
                (8, 4, 4),
                (i32::MAX, 0, 1),
            ] {
                sink.span(y, x0, x1, 1);
            }
            Ok(())
        }
    }

    #[test]
    fn stray_spans_are_counted_and_clipped_never_written_out_of_bounds() {
        let v = [px(0, 0), px(100, 0), px(0, 100)].map(|at| Vertex::new(at, [i32::from(u8::MAX)]));
        let mut shaded = Vec::new();
        let (target, _) = paint(&Stray, |p| {
            p.triangle(&v, &mut |x, y, attrs: &[i32; 1]| {
                shaded.push((x, y));
                Some(attrs[0] as u8)
            })
        });
        let w = SCREEN.width;
        assert_eq!(shaded, [(0, 5), (1, 5), (2, 5), (w - 2, 6), (w - 1, 6)]);
        // Every one of the eight is counted; none is written out of bounds.
        assert_eq!(target.stray_spans(), 8);
        assert_eq!(target.pixels().iter().filter(|&&p| p == 255).count(), 5);
    }
}
