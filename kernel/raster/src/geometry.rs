//! Points, polygons and fill rules.

#[cfg(feature = "alloc")]
use alloc::vec::Vec;

/// Fractional bits of a [`Point`] coordinate: 8, so 1/256 of a pixel.
pub const SUBPIXEL_BITS: u32 = 8;
/// One pixel in subpixel units.
pub const SUBPIXEL_ONE: i32 = 1 << SUBPIXEL_BITS;

/// A vertex in fixed point: `x` and `y` count 1/256ths of a pixel, so the
/// pixel grid corner (3, 4) is `Point { x: 768, y: 1024 }` and the centre of
/// pixel (3, 4) is `Point { x: 896, y: 1152 }`. Every `i32` is a valid value.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub struct Point {
    pub x: i32,
    pub y: i32,
}

impl Point {
    /// A point in subpixel units.
    pub const fn new(x: i32, y: i32) -> Self {
        Self { x, y }
    }

    /// A point on the whole-pixel grid, saturating at the `i32` range.
    pub const fn from_pixels(x: i32, y: i32) -> Self {
        Self { x: x.saturating_mul(SUBPIXEL_ONE), y: y.saturating_mul(SUBPIXEL_ONE) }
    }

    /// Rounds to the nearest whole pixel (halves go up), for the classic
    /// methods whose originals take integer coordinates.
    pub const fn round_to_pixel(self) -> PixelPoint {
        PixelPoint { x: round_subpixels(self.x), y: round_subpixels(self.y) }
    }
}

/// Nearest whole pixel to a subpixel value, halves rounding up; never overflows.
const fn round_subpixels(v: i32) -> i32 {
    ((v as i64 + (SUBPIXEL_ONE as i64 / 2)) >> SUBPIXEL_BITS) as i32
}

/// A vertex on the whole-pixel grid: the input of the classic methods.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub struct PixelPoint {
    pub x: i32,
    pub y: i32,
}

/// Which crossings count as inside (`docs/conventions.md#fill-rules`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum FillRule {
    /// Inside where the number of edge crossings to the left is odd
    /// (Abrash's odd/even rule of chapter 40).
    #[default]
    EvenOdd,
    /// Inside where the signed sum of crossings to the left is not zero.
    NonZero,
}

impl FillRule {
    /// The name used in scene files and the protocol.
    pub const fn name(self) -> &'static str {
        match self {
            FillRule::EvenOdd => "evenodd",
            FillRule::NonZero => "nonzero",
        }
    }

    /// Parses a name written by [`FillRule::name`].
    pub fn from_name(name: &str) -> Option<Self> {
        match name {
            "evenodd" => Some(FillRule::EvenOdd),
            "nonzero" => Some(FillRule::NonZero),
            _ => None,
        }
    }
}

/// A filled polygon: one or more closed contours (the last vertex of each
/// joins its first), one colour, one fill rule. Holes are contours of their
/// own, or bridge edges within one contour as in Abrash's Listing 40.4.
/// It owns its vertices (feature `alloc`); [`PolygonRef`] borrows them.
#[cfg(feature = "alloc")]
#[derive(Clone, Debug, PartialEq, Eq, Default)]
pub struct Polygon {
    pub contours: Vec<Vec<Point>>,
    pub color: u8,
    pub rule: FillRule,
}

#[cfg(feature = "alloc")]
impl Polygon {
    /// A single-contour polygon with the even-odd rule.
    pub fn new(vertices: Vec<Point>, color: u8) -> Self {
        Self { contours: alloc::vec![vertices], color, rule: FillRule::EvenOdd }
    }

    /// A single-contour polygon from whole-pixel coordinates, each moved by
    /// `offset` (the `XOffset`/`YOffset` of Abrash's `FillConvexPolygon`).
    pub fn from_pixels(vertices: &[(i32, i32)], offset: (i32, i32), color: u8) -> Self {
        let contour = vertices
            .iter()
            .map(|&(x, y)| Point::from_pixels(x.saturating_add(offset.0), y.saturating_add(offset.1)))
            .collect();
        Self::new(contour, color)
    }

    /// Total vertex count over all contours.
    pub fn vertex_count(&self) -> usize {
        PolygonRef::from(self).vertex_count()
    }

    /// The only contour, or `None` when the polygon has several (for the
    /// classic methods, which take one vertex list).
    pub fn single_contour(&self) -> Option<&[Point]> {
        match self.contours.as_slice() {
            [only] => Some(only),
            _ => None,
        }
    }
}

/// A polygon as `exact` reads it, borrowed: its closed contours, each a
/// slice of [`Point`]s or anything that lends one (`&[Point]`,
/// `[Point; N]`, `Vec<Point>`), one colour, one fill rule. It needs no
/// allocator; a [`Polygon`] lends one (`PolygonRef::from(&polygon)`).
///
/// ```
/// use raster::{FillRule, Point, PolygonRef};
///
/// let square = [(0, 0), (6, 0), (6, 6), (0, 6)].map(|(x, y)| Point::from_pixels(x, y));
/// let hole = [(2, 2), (2, 4), (4, 4), (4, 2)].map(|(x, y)| Point::from_pixels(x, y));
/// let framed = PolygonRef { contours: &[square, hole], color: 1, rule: FillRule::NonZero };
/// assert_eq!(framed.vertex_count(), 8);
/// ```
#[derive(Debug)]
pub struct PolygonRef<'a, C = &'a [Point]> {
    pub contours: &'a [C],
    pub color: u8,
    pub rule: FillRule,
}

// By hand, for every `C`: a derived `Clone` would ask `C: Clone`, and a
// borrowed polygon copies whatever its contours are.
impl<C> Clone for PolygonRef<'_, C> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<C> Copy for PolygonRef<'_, C> {}

impl<C: AsRef<[Point]>> PolygonRef<'_, C> {
    /// Total vertex count over all contours: its number of edges.
    pub fn vertex_count(&self) -> usize {
        self.contours.iter().map(|contour| contour.as_ref().len()).sum()
    }
}

#[cfg(feature = "alloc")]
impl<'a> From<&'a Polygon> for PolygonRef<'a, Vec<Point>> {
    fn from(polygon: &'a Polygon) -> Self {
        PolygonRef { contours: &polygon.contours, color: polygon.color, rule: polygon.rule }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rounding_to_pixels_takes_halves_up_and_never_overflows() {
        assert_eq!(Point::new(383, -129).round_to_pixel(), PixelPoint { x: 1, y: -1 });
        assert_eq!(Point::new(384, -128).round_to_pixel(), PixelPoint { x: 2, y: 0 });
        let far = Point::new(i32::MAX, i32::MIN).round_to_pixel();
        assert_eq!(far, PixelPoint { x: 1 << 23, y: -(1 << 23) });
    }

    #[test]
    fn from_pixels_saturates() {
        assert_eq!(Point::from_pixels(i32::MAX, -3), Point::new(i32::MAX, -768));
    }
}
