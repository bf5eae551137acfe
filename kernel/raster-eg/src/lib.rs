//! Filled polygons for embedded-graphics 0.8, drawn by `raster`'s
//! `exact` fill: any number of contours (holes, self-intersections), the
//! even-odd or the non-zero rule, every pixel decided in integers at its
//! centre, never a pixel drawn twice, no allocator and no `unsafe`.
//!
//! A [`FilledPolygon`] borrows its contours: whole-pixel
//! [`Point`]s ([`FilledPolygon::new`]), or `raster`'s points in 1/256 px
//! ([`FilledPolygon::subpixels`]). Styled with a
//! [`PrimitiveStyle`]'s fill colour, it is [`Drawable`] on any
//! [`DrawTarget`]: each row of it is one `fill_solid` call, clipped to
//! the target's bounding box, whatever its `i32` coordinates.
//!
//! ```
//! use embedded_graphics::mock_display::MockDisplay;
//! use embedded_graphics::pixelcolor::BinaryColor;
//! use embedded_graphics::prelude::*;
//! use embedded_graphics::primitives::PrimitiveStyle;
//! use raster_eg::{FillRule, FilledPolygon};
//!
//! // A 6x6 square with a 2x2 hole, one contour each.
//! let square = [Point::new(0, 0), Point::new(6, 0), Point::new(6, 6), Point::new(0, 6)];
//! let hole = [Point::new(2, 2), Point::new(4, 2), Point::new(4, 4), Point::new(2, 4)];
//! let contours: [&[Point]; 2] = [&square, &hole];
//! let framed = FilledPolygon::new(&contours, FillRule::EvenOdd);
//!
//! // MockDisplay fails on any pixel drawn twice or out of bounds.
//! let mut display = MockDisplay::new();
//! let drawn = framed.into_styled(PrimitiveStyle::with_fill(BinaryColor::On)).draw(&mut display);
//! assert_eq!(drawn, Ok(Ok(())));
//! display.assert_pattern(&[
//!     "######", //
//!     "######",
//!     "##  ##",
//!     "##  ##",
//!     "######",
//!     "######",
//! ]);
//! ```
//!
//! # What is drawn
//!
//! Pixel (x, y) is drawn when its centre, (x + 0.5, y + 0.5), is inside
//! the polygon by its [`FillRule`]; a centre exactly on an edge belongs to
//! a left or top edge, so polygons that share an edge draw every pixel
//! along it once. A polygon of whole-pixel vertices from (0, 0) to (4, 3)
//! covers the pixels (0..4, 0..3), as a `Rectangle` there would.
//!
//! # Memory
//!
//! Nothing is allocated. The fill's tables live on the stack for polygons
//! of up to 256 edges (vertices over all contours; 64 for polygons 512 px
//! or more across); a larger one is refused ([`Refusal::TooManyVertices`])
//! unless it is lent a [`FixedScratch`] ([`FilledPolygon::fill_with`]).
//! Whole-pixel vertices, and 1/256-px ones on a target whose bounding box
//! does not start at (0, 0), are first converted into a buffer on the
//! stack of `VERTICES` points (64 unless chosen with
//! [`FilledPolygon::with_capacity`]); a polygon of more is refused the
//! same way. A refusal draws nothing: it is the `Ok` value of `draw`,
//! `Err(Refusal)`, and never a panic.
//!
//! # Coordinates
//!
//! Every `i32` vertex is taken. 1/256-px vertices are exact over their
//! whole range. Whole-pixel vertices are exact within ±8,388,607 px of the
//! target's top-left corner (2^23 px, where 1/256 px fills an `i32`); one
//! further away is moved to that bound, which keeps the fill exact for the
//! polygon so moved.
#![no_std]
#![forbid(unsafe_code)]

use embedded_graphics::draw_target::DrawTarget;
use embedded_graphics::geometry::{Dimensions, Point, Size};
use embedded_graphics::pixelcolor::PixelColor;
use embedded_graphics::primitives::{Primitive, PrimitiveStyle, Rectangle, StyledDimensions, StyledDrawable};
use raster::{PolygonRef, ScratchMut, SpanSink};

pub use raster::{FillRule, FixedScratch, Refusal};

/// One pixel in `raster`'s 1/256-px units.
const ONE: i64 = raster::SUBPIXEL_ONE as i64;

/// A filled polygon: closed contours (each one's last vertex joins its
/// first), borrowed, and a [`FillRule`]. Its colour is the fill colour of
/// the [`PrimitiveStyle`] it is styled with; a style's stroke is not
/// drawn. `VERTICES` bounds the vertices it converts on the stack (see the
/// crate's "Memory").
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FilledPolygon<'a, const VERTICES: usize = 64> {
    contours: Contours<'a>,
    rule: FillRule,
}

/// A polygon's contours, as the caller gave them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Contours<'a> {
    Pixels(&'a [&'a [Point]]),
    Subpixels(&'a [&'a [raster::Point]]),
}

impl<'a> FilledPolygon<'a> {
    /// A polygon of whole-pixel vertices: the grid corner (x, y), where
    /// pixel (x, y)'s top-left corner is.
    pub const fn new(contours: &'a [&'a [Point]], rule: FillRule) -> Self {
        FilledPolygon { contours: Contours::Pixels(contours), rule }
    }

    /// A polygon of vertices in 1/256 px: `raster::Point { x: 256, y: 0 }`
    /// is the grid corner (1, 0), and `raster::Point::from_pixels` makes
    /// one from whole pixels.
    pub const fn subpixels(contours: &'a [&'a [raster::Point]], rule: FillRule) -> Self {
        FilledPolygon { contours: Contours::Subpixels(contours), rule }
    }
}

impl<'a, const VERTICES: usize> FilledPolygon<'a, VERTICES> {
    /// The same polygon, converting up to `MORE` vertices on the stack.
    pub const fn with_capacity<const MORE: usize>(self) -> FilledPolygon<'a, MORE> {
        FilledPolygon { contours: self.contours, rule: self.rule }
    }

    /// Fills the polygon in `color` into `target`: the target's error if
    /// one of its `fill_solid` calls failed (the rows after it are not
    /// drawn), else `Ok` of the fill's refusal, if any.
    pub fn fill<D: DrawTarget>(&self, color: D::Color, target: &mut D) -> Result<Result<(), Refusal>, D::Error> {
        self.fill_in(color, target, None)
    }

    /// [`FilledPolygon::fill`] with room for a polygon of more edges than
    /// the stack's tables hold: a [`FixedScratch`] (or, where `raster`'s
    /// `alloc` feature is on, a `raster::Scratch`), as `&mut scratch`.
    pub fn fill_with<'s, D: DrawTarget>(
        &self,
        color: D::Color,
        target: &mut D,
        scratch: impl Into<ScratchMut<'s>>,
    ) -> Result<Result<(), Refusal>, D::Error> {
        self.fill_in(color, target, Some(scratch.into()))
    }

    fn fill_in<D: DrawTarget>(
        &self,
        color: D::Color,
        target: &mut D,
        scratch: Option<ScratchMut<'_>>,
    ) -> Result<Result<(), Refusal>, D::Error> {
        let area = target.bounding_box();
        let side = |length: u32| i32::try_from(length).unwrap_or(i32::MAX);
        let size = raster::Size { width: side(area.size.width), height: side(area.size.height) };
        let origin = area.top_left;
        let mut rows = Rows { target, color, origin, size, error: None };
        let filled = match self.contours {
            // Already what the fill reads, where the target starts at (0, 0).
            Contours::Subpixels(contours) if origin == Point::zero() => {
                fill(self.polygon(contours), &mut rows, scratch)
            }
            Contours::Subpixels(contours) => {
                let moved = |p: raster::Point| {
                    let at = |v: i32, from: i32| i64::from(v) - i64::from(from) * ONE;
                    raster::Point::new(clamp(at(p.x, origin.x)), clamp(at(p.y, origin.y)))
                };
                self.converted(contours, moved, &mut rows, scratch)
            }
            Contours::Pixels(contours) => {
                let moved = |p: Point| {
                    let at = |v: i32, from: i32| (i64::from(v) - i64::from(from)) * ONE;
                    raster::Point::new(clamp(at(p.x, origin.x)), clamp(at(p.y, origin.y)))
                };
                self.converted(contours, moved, &mut rows, scratch)
            }
        };
        match rows.error {
            Some(error) => Err(error),
            None => Ok(filled),
        }
    }

    /// The fill's view of the polygon, of these `contours`.
    fn polygon<'c>(&self, contours: &'c [&'c [raster::Point]]) -> PolygonRef<'c> {
        PolygonRef { contours, color: 0, rule: self.rule }
    }

    /// Fills the polygon of `contours` with each vertex `moved` into the
    /// target's 1/256-px coordinates, in a buffer of `VERTICES` on the
    /// stack, or refuses it when it has more.
    fn converted<P: Copy, D: DrawTarget>(
        &self,
        contours: &[&[P]],
        moved: impl Fn(P) -> raster::Point,
        rows: &mut Rows<'_, D>,
        scratch: Option<ScratchMut<'_>>,
    ) -> Result<(), Refusal> {
        let mut vertices = [raster::Point::default(); VERTICES];
        let sources = contours.iter().flat_map(|contour| contour.iter());
        if sources.clone().count() > VERTICES {
            return Err(Refusal::TooManyVertices);
        }
        for (vertex, &source) in vertices.iter_mut().zip(sources) {
            *vertex = moved(source);
        }
        // Each non-empty contour has a vertex, so there are no more of
        // them than vertices; an empty one adds no edge.
        let mut slices: [&[raster::Point]; VERTICES] = [&[]; VERTICES];
        let (mut rest, mut count) = (&vertices[..], 0);
        for contour in contours.iter().filter(|contour| !contour.is_empty()) {
            let (this, after) = rest.split_at(contour.len());
            (slices[count], rest, count) = (this, after, count + 1);
        }
        fill(self.polygon(&slices[..count]), rows, scratch)
    }

    /// The box of the polygon's vertices in 1/256 px, or `None` when it
    /// has none.
    fn vertex_box(&self) -> Option<(i64, i64, i64, i64)> {
        let wide = |p: raster::Point| (i64::from(p.x), i64::from(p.y));
        let points: &mut dyn Iterator<Item = (i64, i64)> = match self.contours {
            Contours::Pixels(contours) => {
                &mut contours.iter().flat_map(|c| c.iter()).map(|p| (i64::from(p.x) * ONE, i64::from(p.y) * ONE))
            }
            Contours::Subpixels(contours) => &mut contours.iter().flat_map(|c| c.iter()).map(|&p| wide(p)),
        };
        let (x, y) = points.next()?;
        Some(points.fold((x, y, x, y), |(x0, y0, x1, y1), (x, y)| (x0.min(x), y0.min(y), x1.max(x), y1.max(y))))
    }
}

/// Fills `polygon` into `rows`, with the caller's scratch if any.
fn fill<D: DrawTarget>(
    polygon: PolygonRef<'_>,
    rows: &mut Rows<'_, D>,
    scratch: Option<ScratchMut<'_>>,
) -> Result<(), Refusal> {
    match scratch {
        Some(scratch) => raster::fill_auto_with(polygon, rows, scratch),
        None => raster::fill_auto(polygon, rows),
    }
}

/// `v` within the `i32` range.
fn clamp(v: i64) -> i32 {
    v.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32
}

/// The bounding box of every pixel the polygon may draw: those whose
/// centres lie within the box of its vertices.
impl<const VERTICES: usize> Dimensions for FilledPolygon<'_, VERTICES> {
    fn bounding_box(&self) -> Rectangle {
        let Some((x0, y0, x1, y1)) = self.vertex_box() else { return Rectangle::zero() };
        // The first and last rows and columns whose centres lie in the box.
        let first = |v: i64| (v - ONE / 2 + ONE - 1).div_euclid(ONE);
        let last = |v: i64| (v - ONE / 2).div_euclid(ONE);
        let length = |from: i64, to: i64| u32::try_from((to - from + 1).max(0)).unwrap_or(u32::MAX);
        let (left, top) = (first(x0), first(y0));
        Rectangle::new(Point::new(clamp(left), clamp(top)), Size::new(length(left, last(x1)), length(top, last(y1))))
    }
}

impl<const VERTICES: usize> Primitive for FilledPolygon<'_, VERTICES> {}

impl<C: PixelColor, const VERTICES: usize> StyledDimensions<PrimitiveStyle<C>> for FilledPolygon<'_, VERTICES> {
    fn styled_bounding_box(&self, _style: &PrimitiveStyle<C>) -> Rectangle {
        self.bounding_box()
    }
}

impl<C: PixelColor, const VERTICES: usize> StyledDrawable<PrimitiveStyle<C>> for FilledPolygon<'_, VERTICES> {
    type Color = C;
    /// `Err` when the fill refused the polygon, which drew nothing.
    type Output = Result<(), Refusal>;

    fn draw_styled<D>(&self, style: &PrimitiveStyle<C>, target: &mut D) -> Result<Self::Output, D::Error>
    where
        D: DrawTarget<Color = C>,
    {
        match style.fill_color {
            Some(color) => self.fill(color, target),
            None => Ok(Ok(())),
        }
    }
}

/// The fill's spans, as rows of the target: `fill_solid` calls, moved
/// back to the target's coordinates; after a failed call, nothing more.
struct Rows<'t, D: DrawTarget> {
    target: &'t mut D,
    color: D::Color,
    origin: Point,
    size: raster::Size,
    error: Option<D::Error>,
}

impl<D: DrawTarget> SpanSink for Rows<'_, D> {
    fn size(&self) -> raster::Size {
        self.size
    }

    fn span(&mut self, y: i32, x_start: i32, x_end: i32, _color: u8) {
        if self.error.is_some() {
            return;
        }
        // Inside the target's box (the fill's contract), so on the target.
        let at = Point::new(self.origin.x.saturating_add(x_start), self.origin.y.saturating_add(y));
        let row = Rectangle::new(at, Size::new(x_end.abs_diff(x_start), 1));
        if let Err(error) = self.target.fill_solid(&row, self.color) {
            self.error = Some(error);
        }
    }
}
