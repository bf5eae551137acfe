//! Test sink and hostile inputs for the classic ports (`lamothe`,
//! `lamothe_fixed`, `wgt`): their conventions draw some pixels twice, which
//! a [`Framebuffer`](crate::Framebuffer) cannot show.

use alloc::string::String;
use alloc::vec;
use alloc::vec::Vec;

use crate::geometry::{Point, Polygon};
use crate::method::Method;
use crate::sink::{Size, SpanSink};

/// Counts how often each pixel is drawn; fails the test on any span that
/// breaks the sink contract (the mock display of embedded-graphics).
pub(crate) struct Hits {
    size: Size,
    counts: Vec<u32>,
}

impl Hits {
    pub(crate) fn new(size: Size) -> Self {
        Self { size, counts: vec![0; (size.width.max(0) * size.height.max(0)) as usize] }
    }

    /// `points` (whole pixels) filled by `method` into an 8x6 target.
    pub(crate) fn drawn(method: &dyn Method, points: &[(i32, i32)]) -> Self {
        let mut hits = Self::new(Size { width: 8, height: 6 });
        method.fill(&Polygon::from_pixels(points, (0, 0), 1), &mut hits).unwrap();
        hits
    }

    /// How often pixel (x, y) was drawn.
    pub(crate) fn at(&self, x: i32, y: i32) -> u32 {
        self.counts[(y * self.size.width + x) as usize]
    }

    /// One text line per row: `.` never drawn, `#` once, a digit for more.
    pub(crate) fn picture(&self) -> String {
        let mut text = String::new();
        for row in self.counts.chunks(self.size.width as usize) {
            text.extend(row.iter().map(|&n| match n {
                0 => '.',
                1 => '#',
                n => char::from_digit(n.min(9), 10).unwrap_or('+'),
            }));
            text.push('\n');
        }
        text
    }
}

impl SpanSink for Hits {
    fn size(&self) -> Size {
        self.size
    }

    fn span(&mut self, y: i32, x_start: i32, x_end: i32, _color: u8) {
        let inside = (0..self.size.height).contains(&y) && 0 <= x_start && x_start < x_end && x_end <= self.size.width;
        assert!(inside, "span y={y} x={x_start}..{x_end} outside {:?}", self.size);
        let row = (y * self.size.width) as usize;
        for n in &mut self.counts[row + x_start as usize..row + x_end as usize] {
            *n += 1;
        }
    }
}

/// The picture of `points` filled by `method`, ignoring overdraw.
pub(crate) fn draw(method: &dyn Method, points: &[(i32, i32)]) -> String {
    Hits::drawn(method, points).picture().replace(|c: char| c.is_ascii_digit(), "#")
}

/// Garbage in: no vertices to thousands, duplicates, collinear points,
/// `i32` extremes. None may panic, hang or draw outside the target.
fn hostile_polygons() -> Vec<Polygon> {
    let (min, max) = (i32::MIN, i32::MAX);
    let contours: Vec<Vec<(i32, i32)>> = vec![
        vec![],
        vec![(5, 5)],
        vec![(0, 0), (2000, 1500)],
        vec![(700, 700), (700, 700), (700, 700)],
        vec![(256, 256), (256, 256), (1024, 1024), (1024, 1024)],
        vec![(0, 0), (512, 512), (1024, 1024)],
        vec![(0, 300), (9000, 300), (-4000, 300)],
        vec![(min, min), (max, min), (min, max)],
        vec![(min, min), (max, min), (max, max), (min, max)],
        vec![(max, max), (min, min), (max, min), (0, 0), (min, max)],
        vec![(min, 0), (max, 256), (0, max)],
        vec![(min, 1000), (max, 1000), (0, 1256)],
        vec![(0, min), (1, max), (-1, max)],
        vec![(8_388_000 * 256, 0), (-8_388_000 * 256, 2560), (0, 5120)],
        vec![(40_000 * 256, -30_000 * 256), (-40_000 * 256, 30_000 * 256), (32_767 * 256, 32_767 * 256)],
    ];
    let mut polygons: Vec<Polygon> =
        contours.into_iter().map(|c| Polygon::new(c.into_iter().map(|(x, y)| Point::new(x, y)).collect(), 7)).collect();
    // Thousands of vertices: a zigzag across the screen, and scattered
    // points from a small LCG reaching the i32 extremes.
    let zigzag = (0..5000).map(|i| Point::from_pixels(i % 400 - 40, if i % 2 == 0 { -10 } else { 210 })).collect();
    polygons.push(Polygon::new(zigzag, 7));
    let mut state = 0x2545_f491_u32;
    let mut next = move || {
        state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
        state as i32
    };
    let scattered = (0..3000).map(|_| Point::new(next(), next() >> (next() as u32 & 31))).collect();
    polygons.push(Polygon::new(scattered, 7));
    let two_contours = Polygon { contours: vec![vec![Point::new(0, 0)], vec![Point::new(1, 1)]], ..Polygon::default() };
    polygons.push(two_contours);
    polygons
}

/// Fills every hostile polygon into a 320x200 [`Hits`] (which fails on a
/// stray span) and into targets with no pixels; refusals are fine.
pub(crate) fn assert_survives_hostile_input(method: &dyn Method) {
    for polygon in hostile_polygons() {
        for size in [Size { width: 320, height: 200 }, Size { width: 0, height: 0 }, Size { width: 3, height: -4 }] {
            let _ = method.fill(&polygon, &mut Hits::new(size));
        }
    }
}
