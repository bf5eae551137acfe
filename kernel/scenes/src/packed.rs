//! A scene as compact bytes: what the protocol's upload carries to the
//! kernel, where a scene file's text would cost about 20 bytes a vertex.
//!
//! ```text
//! magic     "PLS1"
//! palette   count, then per entry: index, red, green, blue (one byte each, levels 0-63)
//! ops       count, then per op:
//!             0 = clear: colour
//!             1 = fill:  colour, rule (0 evenodd, 1 nonzero), contours, then per
//!                        contour: vertices, then per vertex dx, dy
//! ```
//!
//! Every count is an unsigned LEB128 varint (7 bits a byte, low first), and
//! every dx, dy a zigzag-coded varint: the vertex's offset in 1/256 px
//! from the vertex before it in the whole scene (from (0, 0) for the
//! first), so a vertex of a real outline costs two to four bytes. Reading
//! back is exact ([`unpack`] gives the very scene [`pack`] was given,
//! method aside: a packed scene is drawn with `exact` when none is named,
//! as a scene file is) and refuses anything else with an [`UnpackError`]:
//! it never panics, and never allocates more than the caller's bound.

use alloc::string::String;
use alloc::vec::Vec;
use core::fmt;
use core::mem::size_of;

use raster::{FillRule, Point, Polygon};

use crate::file::writes;
use crate::palette::MAX_LEVEL;
use crate::scene::{Op, PaletteEntry, Scene, FILE_METHOD};

/// The first bytes of every packed scene.
pub const MAGIC: [u8; 4] = *b"PLS1";

const CLEAR: u8 = 0;
const FILL: u8 = 1;

/// Why bytes are not a packed scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum UnpackError {
    /// The bytes do not start with [`MAGIC`].
    NotPacked,
    /// The bytes end inside the scene.
    Truncated,
    /// Bytes left over after the scene.
    Trailing,
    /// A varint of more than 64 bits.
    BadNumber,
    /// An op tag other than clear (0) and fill (1).
    BadOp(u8),
    /// A rule byte other than evenodd (0) and nonzero (1).
    BadRule(u8),
    /// A palette level above 63.
    BadLevel(u8),
    /// A vertex whose coordinate falls outside `i32`.
    CoordinateOutOfRange,
    /// The scene would hold more memory than the bound allows.
    OverBudget { budget: usize },
    /// Memory could not be had for it.
    OutOfMemory,
}

impl fmt::Display for UnpackError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            UnpackError::NotPacked => write!(f, "not a packed scene (no PLS1 at its start)"),
            UnpackError::Truncated => write!(f, "the packed scene ends early"),
            UnpackError::Trailing => write!(f, "bytes after the end of the packed scene"),
            UnpackError::BadNumber => write!(f, "a count or offset longer than 64 bits"),
            UnpackError::BadOp(tag) => write!(f, "unknown operation {tag}"),
            UnpackError::BadRule(rule) => write!(f, "unknown fill rule {rule}"),
            UnpackError::BadLevel(level) => write!(f, "palette level {level} above 63"),
            UnpackError::CoordinateOutOfRange => write!(f, "a vertex outside the 32-bit range"),
            UnpackError::OverBudget { budget } => write!(f, "it needs more than the {budget} bytes it declared"),
            UnpackError::OutOfMemory => write!(f, "out of memory"),
        }
    }
}

impl UnpackError {
    /// Reads back the text `Display` writes (the kernel answers an upload
    /// that does not unpack with it); `None` for any other text.
    pub fn parse(text: &str) -> Option<Self> {
        let fixed = [
            UnpackError::NotPacked,
            UnpackError::Truncated,
            UnpackError::Trailing,
            UnpackError::BadNumber,
            UnpackError::CoordinateOutOfRange,
            UnpackError::OutOfMemory,
        ];
        let number = |before: &str, after: &str| -> Option<u64> {
            let digits = text.strip_prefix(before)?.strip_suffix(after)?;
            digits.bytes().all(|b| b.is_ascii_digit()).then(|| digits.parse().ok()).flatten()
        };
        let error = fixed.into_iter().find(|error| writes(error, text)).or_else(|| {
            let byte = |before, after| number(before, after).and_then(|n| u8::try_from(n).ok());
            byte("unknown operation ", "")
                .map(UnpackError::BadOp)
                .or_else(|| byte("unknown fill rule ", "").map(UnpackError::BadRule))
                .or_else(|| byte("palette level ", " above 63").map(UnpackError::BadLevel))
                .or_else(|| {
                    let budget = number("it needs more than the ", " bytes it declared")?;
                    Some(UnpackError::OverBudget { budget: usize::try_from(budget).ok()? })
                })
        })?;
        writes(&error, text).then_some(error)
    }
}

/// Bytes of memory the unpacked `scene` holds: what [`unpack`] counts
/// against its bound, the same on every 64-bit machine.
pub fn memory(scene: &Scene) -> usize {
    let ops = scene.ops.iter().map(|op| match op {
        Op::Clear(_) => size_of::<Op>(),
        Op::Fill(polygon) => {
            size_of::<Op>()
                + polygon.contours.len() * size_of::<Vec<Point>>()
                + polygon.vertex_count() * size_of::<Point>()
        }
    });
    scene.palette.len() * size_of::<PaletteEntry>() + ops.sum::<usize>()
}

/// `scene` packed (its name and method are not: the protocol names the
/// scene, and a packed scene is drawn with `exact` unless told).
pub fn pack(scene: &Scene) -> Vec<u8> {
    let mut bytes = Vec::from(MAGIC);
    put_count(&mut bytes, scene.palette.len());
    for entry in &scene.palette {
        bytes.push(entry.index);
        bytes.extend_from_slice(&entry.rgb);
    }
    put_count(&mut bytes, scene.ops.len());
    let mut previous = Point::new(0, 0);
    for op in &scene.ops {
        match op {
            Op::Clear(color) => bytes.extend_from_slice(&[CLEAR, *color]),
            Op::Fill(polygon) => {
                let rule = match polygon.rule {
                    FillRule::EvenOdd => 0,
                    FillRule::NonZero => 1,
                };
                bytes.extend_from_slice(&[FILL, polygon.color, rule]);
                put_count(&mut bytes, polygon.contours.len());
                for contour in &polygon.contours {
                    put_count(&mut bytes, contour.len());
                    for &point in contour {
                        put_offset(&mut bytes, point.x, previous.x);
                        put_offset(&mut bytes, point.y, previous.y);
                        previous = point;
                    }
                }
            }
        }
    }
    bytes
}

fn put_count(bytes: &mut Vec<u8>, count: usize) {
    put_varint(bytes, count as u64);
}

/// `value - previous` zigzag-coded: 0, -1, 1, -2, ... as 0, 1, 2, 3, ...
fn put_offset(bytes: &mut Vec<u8>, value: i32, previous: i32) {
    let offset = i64::from(value) - i64::from(previous);
    put_varint(bytes, ((offset << 1) ^ (offset >> 63)) as u64);
}

fn put_varint(bytes: &mut Vec<u8>, mut value: u64) {
    while value >= 0x80 {
        bytes.push((value as u8) | 0x80);
        value >>= 7;
    }
    bytes.push(value as u8);
}

/// The scene `bytes` pack, named `name`, drawn with `exact` unless told;
/// refused if it would hold more than `budget` bytes of memory
/// ([`memory`]), before that memory is taken.
pub fn unpack(name: String, bytes: &[u8], budget: usize) -> Result<Scene, UnpackError> {
    let mut reader = Reader { bytes, budget, used: 0 };
    if reader.take(MAGIC.len())? != MAGIC {
        return Err(UnpackError::NotPacked);
    }
    let mut scene = Scene::new(name, Vec::new(), FILE_METHOD);
    // Each palette entry takes 4 bytes, each op at least 2: a count larger
    // than the bytes left could hold is truncated, whatever it claims.
    let entries = reader.count(4)?;
    reader.reserve(&mut scene.palette, entries)?;
    for _ in 0..entries {
        let [index, r, g, b] = [reader.byte()?, reader.byte()?, reader.byte()?, reader.byte()?];
        if let Some(&level) = [r, g, b].iter().find(|&&level| level > MAX_LEVEL) {
            return Err(UnpackError::BadLevel(level));
        }
        scene.palette.push(PaletteEntry { index, rgb: [r, g, b] });
    }
    let ops = reader.count(2)?;
    reader.reserve(&mut scene.ops, ops)?;
    let mut previous = Point::new(0, 0);
    for _ in 0..ops {
        let op = match reader.byte()? {
            CLEAR => Op::Clear(reader.byte()?),
            FILL => Op::Fill(reader.polygon(&mut previous)?),
            tag => return Err(UnpackError::BadOp(tag)),
        };
        scene.ops.push(op);
    }
    match reader.bytes.is_empty() {
        true => Ok(scene),
        false => Err(UnpackError::Trailing),
    }
}

/// The bytes not yet read, and the memory taken so far against the bound.
struct Reader<'a> {
    bytes: &'a [u8],
    budget: usize,
    used: usize,
}

impl Reader<'_> {
    fn take(&mut self, len: usize) -> Result<&[u8], UnpackError> {
        if self.bytes.len() < len {
            return Err(UnpackError::Truncated);
        }
        let (taken, rest) = self.bytes.split_at(len);
        self.bytes = rest;
        Ok(taken)
    }

    fn byte(&mut self) -> Result<u8, UnpackError> {
        self.take(1).map(|taken| taken[0])
    }

    fn varint(&mut self) -> Result<u64, UnpackError> {
        let mut value = 0u64;
        for shift in (0..64).step_by(7) {
            let byte = self.byte()?;
            let bits = u64::from(byte & 0x7f);
            if shift == 63 && bits > 1 {
                return Err(UnpackError::BadNumber);
            }
            value |= bits << shift;
            if byte & 0x80 == 0 {
                return Ok(value);
            }
        }
        Err(UnpackError::BadNumber)
    }

    /// A count of things that take at least `each` bytes apiece: more than
    /// the bytes left could hold is a truncated scene.
    fn count(&mut self, each: usize) -> Result<usize, UnpackError> {
        let count = self.varint()?;
        match usize::try_from(count) {
            Ok(count) if count <= self.bytes.len() / each => Ok(count),
            _ => Err(UnpackError::Truncated),
        }
    }

    /// Room for `count` more items in `items`, counted against the bound.
    fn reserve<T>(&mut self, items: &mut Vec<T>, count: usize) -> Result<(), UnpackError> {
        let budget = self.budget;
        self.used = count
            .checked_mul(size_of::<T>())
            .and_then(|bytes| self.used.checked_add(bytes))
            .filter(|&used| used <= budget)
            .ok_or(UnpackError::OverBudget { budget })?;
        items.try_reserve_exact(count).map_err(|_| UnpackError::OutOfMemory)
    }

    fn offset(&mut self, previous: i32) -> Result<i32, UnpackError> {
        let zigzag = self.varint()?;
        let offset = ((zigzag >> 1) as i64) ^ -((zigzag & 1) as i64);
        i64::from(previous)
            .checked_add(offset)
            .and_then(|value| i32::try_from(value).ok())
            .ok_or(UnpackError::CoordinateOutOfRange)
    }

    /// A fill's polygon, its vertices offset from `previous`, which is left
    /// at its last vertex.
    fn polygon(&mut self, previous: &mut Point) -> Result<Polygon, UnpackError> {
        let color = self.byte()?;
        let rule = match self.byte()? {
            0 => FillRule::EvenOdd,
            1 => FillRule::NonZero,
            rule => return Err(UnpackError::BadRule(rule)),
        };
        let count = self.count(1)?;
        let mut contours = Vec::new();
        self.reserve(&mut contours, count)?;
        for _ in 0..count {
            // Each vertex takes at least two bytes.
            let vertices = self.count(2)?;
            let mut contour = Vec::new();
            self.reserve(&mut contour, vertices)?;
            for _ in 0..vertices {
                let x = self.offset(previous.x)?;
                let y = self.offset(previous.y)?;
                *previous = Point::new(x, y);
                contour.push(*previous);
            }
            contours.push(contour);
        }
        Ok(Polygon { contours, color, rule })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::builtin;
    use alloc::vec;

    fn scene(ops: Vec<Op>) -> Scene {
        Scene::new(String::from("t"), ops, FILE_METHOD)
    }

    fn square(at: i32, side: i32) -> Vec<Point> {
        vec![Point::new(at, at), Point::new(at + side, at), Point::new(at + side, at + side), Point::new(at, at + side)]
    }

    #[test]
    fn every_built_in_page_unpacks_to_itself_within_its_own_memory() {
        for page in builtin::ALL {
            let mut scene = page.scene();
            scene.method = FILE_METHOD;
            let bytes = pack(&scene);
            let back = unpack(scene.name.clone(), &bytes, memory(&scene)).unwrap();
            assert_eq!(back, scene, "{}", page.name);
            let less = memory(&scene) - 1;
            assert_eq!(unpack(scene.name.clone(), &bytes, less), Err(UnpackError::OverBudget { budget: less }));
        }
    }

    #[test]
    fn extremes_and_a_palette_survive_the_trip() {
        let corners =
            vec![Point::new(i32::MIN, i32::MAX), Point::new(i32::MAX, i32::MIN), Point::new(0, 0), Point::new(-1, 1)];
        let mut scene = scene(vec![
            Op::Clear(255),
            Op::Fill(Polygon { contours: vec![corners, square(5, 10)], color: 7, rule: FillRule::NonZero }),
            Op::Fill(Polygon { contours: vec![Vec::new()], color: 1, rule: FillRule::EvenOdd }),
        ]);
        scene.palette = vec![PaletteEntry { index: 255, rgb: [63, 0, 63] }, PaletteEntry { index: 0, rgb: [1, 2, 3] }];
        let bytes = pack(&scene);
        assert_eq!(unpack(String::from("t"), &bytes, usize::MAX), Ok(scene));
    }

    #[test]
    fn a_vertex_of_an_outline_costs_a_few_bytes() {
        // 1,000 vertices a few pixels apart, as a flattened outline has
        // them: steps of up to 3 px (768 subpixels) each way.
        let mut state = 12345u32;
        let mut at = Point::new(160 << 8, 100 << 8);
        let contour: Vec<Point> = (0..1000)
            .map(|_| {
                state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
                let step = |bits: u32| (bits % 1537) as i32 - 768;
                at = Point::new(at.x + step(state >> 8), at.y + step(state >> 20));
                at
            })
            .collect();
        let scene = scene(vec![Op::Fill(Polygon { contours: vec![contour], color: 3, rule: FillRule::EvenOdd })]);
        let bytes = pack(&scene).len();
        assert!((3000..=4016).contains(&bytes), "{bytes} bytes for 1,000 vertices");
    }

    #[test]
    fn every_error_reads_back_from_its_text() {
        let errors = [
            UnpackError::NotPacked,
            UnpackError::Truncated,
            UnpackError::Trailing,
            UnpackError::BadNumber,
            UnpackError::BadOp(0),
            UnpackError::BadOp(255),
            UnpackError::BadRule(2),
            UnpackError::BadLevel(64),
            UnpackError::CoordinateOutOfRange,
            UnpackError::OverBudget { budget: 1_048_576 },
            UnpackError::OutOfMemory,
        ];
        for error in errors {
            let text = alloc::format!("{error}");
            assert_eq!(UnpackError::parse(&text), Some(error), "{text}");
        }
        for garbage in ["", "unknown operation", "unknown operation 256", "unknown operation 01", "out of memory now"] {
            assert_eq!(UnpackError::parse(garbage), None, "{garbage}");
        }
    }

    #[test]
    fn bad_bytes_are_refused_by_name() {
        let good =
            pack(&scene(vec![Op::Fill(Polygon { contours: vec![square(1, 2)], color: 4, rule: FillRule::EvenOdd })]));
        let name = || String::from("t");
        assert_eq!(unpack(name(), b"PLS0", usize::MAX), Err(UnpackError::NotPacked));
        assert_eq!(unpack(name(), b"PL", usize::MAX), Err(UnpackError::Truncated));
        for cut in MAGIC.len()..good.len() {
            assert_eq!(unpack(name(), &good[..cut], usize::MAX), Err(UnpackError::Truncated), "cut at {cut}");
        }
        let mut longer = good.clone();
        longer.push(0);
        assert_eq!(unpack(name(), &longer, usize::MAX), Err(UnpackError::Trailing));
        // The op tag is the byte after the two counts.
        let mut bad_op = good.clone();
        bad_op[6] = 9;
        assert_eq!(unpack(name(), &bad_op, usize::MAX), Err(UnpackError::BadOp(9)));
        let mut bad_rule = good.clone();
        bad_rule[8] = 2;
        assert_eq!(unpack(name(), &bad_rule, usize::MAX), Err(UnpackError::BadRule(2)));
        assert_eq!(unpack(name(), b"PLS1\x01\x00\x00\x00\x40\x00", usize::MAX), Err(UnpackError::BadLevel(64)));
        let endless = [&MAGIC[..], &[0xff; 11]].concat();
        assert_eq!(unpack(name(), &endless, usize::MAX), Err(UnpackError::BadNumber));
        // A count far beyond what the bytes could hold allocates nothing.
        let huge = [&MAGIC[..], &[0xff, 0xff, 0xff, 0xff, 0x0f], &[0; 8]].concat();
        assert_eq!(unpack(name(), &huge, usize::MAX), Err(UnpackError::Truncated));
        // One vertex at i32::MAX, then one a subpixel past it.
        let mut far = Vec::from(MAGIC);
        far.extend_from_slice(&[0, 1, FILL, 1, 0, 1, 1]);
        put_offset(&mut far, i32::MAX, 0);
        put_offset(&mut far, 0, 0);
        assert!(unpack(name(), &far, usize::MAX).is_ok());
        far[MAGIC.len() + 6] = 2;
        put_varint(&mut far, 2);
        put_offset(&mut far, 0, 0);
        assert_eq!(unpack(name(), &far, usize::MAX), Err(UnpackError::CoordinateOutOfRange));
    }
}
