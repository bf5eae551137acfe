//! The polygons the `methods` and `exact_reference` targets fill, decoded
//! from the fuzzer's bytes, and the encoding the seed corpora are written
//! in.
//!
//! The bytes are read with `arbitrary`'s [`Unstructured`] (integers little
//! endian, zeros once the bytes run out), so every input is a polygon and
//! a mutation of a byte moves one coordinate or one flag:
//!
//! - one byte of flags: bit 0 the fill rule (even-odd, non-zero), the rest
//!   the target it is filled into (an index into the target's list);
//! - then records until the bytes run out, each a tag byte and, unless
//!   the tag says there is none, a vertex. Tag bit 0 starts a new contour
//!   (the first record always does), bit 2 means no vertex (so a contour
//!   can be empty), bit 1 means a small vertex: two `i16` in 1/64 pixel
//!   (within 512 pixels of the origin, around the screen) instead of two
//!   `i32` in 1/256 pixel (anywhere).

use arbitrary::{Arbitrary, Unstructured};
use raster::{FillRule, Point, Polygon};

/// Tag bit: this record starts a new contour.
const NEW_CONTOUR: u8 = 1;
/// Tag bit: the vertex is two `i16` in units of [`SMALL_UNIT`] subpixels.
const SMALL: u8 = 2;
/// Tag bit: the record has no vertex.
const NO_VERTEX: u8 = 4;
/// Subpixels in one unit of a small vertex: 1/64 pixel.
const SMALL_UNIT: i32 = 4;

/// A polygon and the index of the target it is filled into (each target
/// takes it modulo the length of its list).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Fill {
    pub polygon: Polygon,
    pub target: usize,
}

/// The next value; integers never fail to decode (missing bytes are zeros).
fn next<'a, T: Arbitrary<'a> + Default>(bytes: &mut Unstructured<'a>) -> T {
    T::arbitrary(bytes).unwrap_or_default()
}

/// Decodes any bytes into a polygon (colour 1) and a target index.
pub fn decode(data: &[u8]) -> Fill {
    let mut bytes = Unstructured::new(data);
    let flags: u8 = next(&mut bytes);
    let rule = if flags & 1 == 0 { FillRule::EvenOdd } else { FillRule::NonZero };
    let mut contours: Vec<Vec<Point>> = Vec::new();
    while !bytes.is_empty() {
        let tag: u8 = next(&mut bytes);
        if tag & NEW_CONTOUR != 0 || contours.is_empty() {
            contours.push(Vec::new());
        }
        if tag & NO_VERTEX != 0 {
            continue;
        }
        let vertex = if tag & SMALL != 0 {
            let (x, y): (i16, i16) = (next(&mut bytes), next(&mut bytes));
            Point::new(i32::from(x) * SMALL_UNIT, i32::from(y) * SMALL_UNIT)
        } else {
            Point::new(next(&mut bytes), next(&mut bytes))
        };
        if let Some(contour) = contours.last_mut() {
            contour.push(vertex);
        }
    }
    Fill { polygon: Polygon { contours, color: 1, rule }, target: usize::from(flags >> 1) }
}

/// The small form of `value`, if it has one.
fn small(value: i32) -> Option<i16> {
    if value % SMALL_UNIT == 0 {
        i16::try_from(value / SMALL_UNIT).ok()
    } else {
        None
    }
}

/// The bytes [`decode`] reads back as `polygon` (in colour 1) and target
/// `target` (below 128): each vertex small when it can be.
pub fn encode(polygon: &Polygon, target: u8) -> Vec<u8> {
    let rule = u8::from(polygon.rule == FillRule::NonZero);
    let mut bytes = vec![rule | (target << 1)];
    for contour in &polygon.contours {
        if contour.is_empty() {
            bytes.push(NEW_CONTOUR | NO_VERTEX);
        }
        for (i, point) in contour.iter().enumerate() {
            let start = if i == 0 { NEW_CONTOUR } else { 0 };
            match (small(point.x), small(point.y)) {
                (Some(x), Some(y)) => {
                    bytes.push(start | SMALL);
                    bytes.extend(x.to_le_bytes().into_iter().chain(y.to_le_bytes()));
                }
                _ => {
                    bytes.push(start);
                    bytes.extend(point.x.to_le_bytes().into_iter().chain(point.y.to_le_bytes()));
                }
            }
        }
    }
    bytes
}

/// Every polygon of every built-in scene, one seed each, for target
/// `target`.
pub fn builtin_seeds(target: u8) -> Vec<(String, Vec<u8>)> {
    let mut seeds = Vec::new();
    for page in &scenes::builtin::ALL {
        let polygons = page.scene().ops.into_iter().filter_map(|op| match op {
            scenes::Op::Fill(polygon) => Some(polygon),
            scenes::Op::Clear(_) => None,
        });
        for (index, polygon) in polygons.enumerate() {
            seeds.push((format!("{}-{index}", page.name), encode(&polygon, target)));
        }
    }
    seeds
}

#[cfg(test)]
mod tests {
    use super::*;

    fn with_color_1(mut polygon: Polygon) -> Polygon {
        polygon.color = 1;
        polygon
    }

    #[test]
    fn every_built_in_polygon_decodes_from_its_seed() {
        let seeds = builtin_seeds(3);
        assert!(seeds.len() > 300, "{} seeds", seeds.len());
        let mut polygons = scenes::builtin::ALL.iter().flat_map(|page| page.scene().ops).filter_map(|op| match op {
            scenes::Op::Fill(polygon) => Some(with_color_1(polygon)),
            scenes::Op::Clear(_) => None,
        });
        for (name, bytes) in &seeds {
            assert_eq!(decode(bytes), Fill { polygon: polygons.next().unwrap(), target: 3 }, "{name}");
        }
    }

    #[test]
    fn any_vertex_any_contour_count_and_empty_contours_round_trip() {
        let polygon = Polygon {
            contours: vec![
                vec![Point::new(i32::MIN, i32::MAX), Point::new(4, -8), Point::new(3, 1 << 20)],
                vec![],
                vec![Point::new(0, 0)],
            ],
            color: 1,
            rule: FillRule::NonZero,
        };
        assert_eq!(decode(&encode(&polygon, 127)), Fill { polygon, target: 127 });
    }

    #[test]
    fn any_bytes_decode_and_short_records_read_zeros() {
        assert_eq!(decode(&[]), Fill { polygon: with_color_1(Polygon::default()), target: 0 });
        let fill = decode(&[5, SMALL, 1]);
        assert_eq!(fill.target, 2);
        assert_eq!(fill.polygon.rule, FillRule::NonZero);
        assert_eq!(fill.polygon.contours, [vec![Point::new(SMALL_UNIT, 0)]]);
    }
}
