//! What the peers' tests share: a sink that records spans, a square, and
//! a family of given polygons.

use raster::{Polygon, SpanSink, SCREEN};

use crate::corpus::{Family, Group};

/// Spans recorded as `(y, x_start, x_end)`.
pub struct Spans(pub Vec<(i32, i32, i32)>);

impl SpanSink for Spans {
    fn size(&self) -> raster::Size {
        SCREEN
    }
    fn span(&mut self, y: i32, x_start: i32, x_end: i32, _color: u8) {
        self.0.push((y, x_start, x_end));
    }
}

/// The square of `side` px with its top-left corner at (`x`, `y`).
pub fn square(x: i32, y: i32, side: i32) -> Polygon {
    Polygon::from_pixels(&[(x, y), (x + side, y), (x + side, y + side), (x, y + side)], (0, 0), 7)
}

/// A family of `polygons` and nothing else.
pub fn family(polygons: Vec<Polygon>) -> Family {
    Family { name: "f", group: Group::Random, description: "", polygons, tilings: vec![], sweep: None }
}
