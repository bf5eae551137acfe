//! How far each classic method is from the exact reference on the pages of
//! Listing 38.3 (`docs/scenes.md#chapter-38-sample-program`), under our convention (pixel centres,
//! [`SampleOffset::CENTRE`]) and under the method's own
//! ([`SampleOffset::of`] its [`Convention`](raster::reference::Convention)): the
//! measured counts are pinned, each with the reason it is what it is.
//!
//! Counted polygon by polygon: each polygon the method draws is compared
//! with the reference's drawing of the same polygon, and the differences
//! are summed over the page. The pages never clear, so comparing finished
//! pictures would hide whatever later polygons paint over (LaMothe's fan
//! spills 7 000 pixels over page 1; the triangles of page 2 cover most of
//! them) and the numbers would explain nothing. A [`Count`] holds the gaps
//! (pixels the reference has and the method misses), the extras (pixels it
//! draws that the reference does not) and the pixels it draws twice within
//! one polygon; the differing pixels are the gaps plus the extras.
//!
//! Conventions in short (each method's module doc has them in full): our
//! rule samples a pixel at its centre; Abrash, LaMothe and WGT sample rows
//! and pixels at integer points (the pixel's top-left corner), Pendleton at
//! centres. The pages' vertices are all whole pixels, so an integer-sample
//! method sees its polygon shifted half a pixel right and down from ours:
//! vertical and horizontal edges through pixel corners keep every pixel, a
//! slanted edge flips the pixels whose corner and centre it passes between.

use std::collections::BTreeSet;
use std::fmt::Write as _;

use raster::methods::{AbrashAet, AbrashFloat, AbrashInt, Exact, Lamothe, LamotheFixed, Pendleton, Wgt};
use raster::reference::{self, SampleOffset};
use raster::{CoverageSink, Method, MethodId, Polygon, Size, SpanSink, SCREEN, SUBPIXEL_ONE};
use scenes::{builtin, Op};

/// How one polygon, or a set of them, deviates from the reference.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord)]
struct Count {
    gaps: usize,
    extras: usize,
    twice: usize,
}

const fn count(gaps: usize, extras: usize, twice: usize) -> Count {
    Count { gaps, extras, twice }
}

const SAME: Count = count(0, 0, 0);

impl Count {
    fn add(&mut self, other: Count) {
        self.gaps += other.gaps;
        self.extras += other.extras;
        self.twice += other.twice;
    }
}

/// Deviations by polygon of Listing 38.3.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
struct Kinds {
    /// `ScreenRectangle`, page 1's "clear".
    rectangle: Count,
    /// `ConvexShape`.
    shape: Count,
    /// One copy of `Triangle1` to `Triangle4`; every copy deviates alike
    /// (checked), so page 2's share is 50, 50, 60 and 60 times these.
    triangles: [Count; 4],
    /// The sixteen hexagons of page 3 together.
    hexagons: Count,
}

/// What one method measured under one convention.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
struct Measured {
    /// Differing pixels (gaps plus extras) on pages 1, 2 and 3; each page
    /// holds the polygons of the ones before it.
    pages: [usize; 3],
    kinds: Kinds,
}

const NONE: Measured =
    Measured { pages: [0; 3], kinds: Kinds { rectangle: SAME, shape: SAME, triangles: [SAME; 4], hexagons: SAME } };

/// One method under both conventions, and a few differing pixels of each
/// kind for the failure messages.
struct Measurement {
    ours: Measured,
    own: Measured,
    examples: String,
}

/// The triangles of Listing 38.3 before their offsets.
const TRIANGLES: [[(i32, i32); 3]; 4] = [
    [(30, 0), (15, 20), (0, 0)],
    [(30, 20), (15, 0), (0, 20)],
    [(0, 20), (20, 10), (0, 0)],
    [(20, 20), (20, 0), (0, 10)],
];

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    Rectangle,
    Shape,
    Triangle(usize),
    Hexagon,
}

/// Which of the listing's polygons `polygon` is: by its vertex count, and
/// for triangles by their vertices relative to their top-left corner.
fn kind(polygon: &Polygon) -> Kind {
    let contour = &polygon.contours[0];
    match contour.len() {
        4 => Kind::Rectangle,
        19 => Kind::Shape,
        6 => Kind::Hexagon,
        3 => {
            let pixels: Vec<(i32, i32)> = contour.iter().map(|p| (p.x / SUBPIXEL_ONE, p.y / SUBPIXEL_ONE)).collect();
            let left = pixels.iter().map(|p| p.0).min().unwrap();
            let top = pixels.iter().map(|p| p.1).min().unwrap();
            let shape: Vec<(i32, i32)> = pixels.iter().map(|&(x, y)| (x - left, y - top)).collect();
            Kind::Triangle(TRIANGLES.iter().position(|t| t[..] == shape[..]).expect("a Listing 38.3 triangle"))
        }
        n => panic!("no polygon of Listing 38.3 has {n} vertices"),
    }
}

/// The polygons of page 3, which starts with those of pages 1 and 2, and
/// how many of them each page has.
fn listing_38_3() -> (Vec<Polygon>, [usize; 3]) {
    let polygons = |name: &str| -> Vec<Polygon> {
        let scene = builtin::scene(name).expect("built-in scene");
        scene
            .ops
            .into_iter()
            .map(|op| match op {
                Op::Fill(polygon) => polygon,
                Op::Clear(_) => panic!("Listing 38.3 never clears"),
            })
            .collect()
    };
    let pages = [polygons("abrash38-1"), polygons("abrash38-2"), polygons("abrash38-3")];
    for page in &pages[..2] {
        assert_eq!(page[..], pages[2][..page.len()], "pages are cumulative");
    }
    let lengths = [pages[0].len(), pages[1].len(), pages[2].len()];
    let [.., last] = pages;
    (last, lengths)
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Difference {
    Gap,
    Extra,
}

/// The screen as a method sees it, stored only in a window around one
/// polygon (its vertices' box and 2 pixels more), so comparing 238
/// polygons costs their areas rather than 238 full screens. Spans off the
/// screen and pixels outside the window are counted, not stored.
struct Window {
    left: i32,
    top: i32,
    drawn: CoverageSink,
    off_screen: usize,
    outside: usize,
}

impl Window {
    const MARGIN: i32 = 2;

    fn around(polygon: &Polygon) -> Self {
        let points = || polygon.contours.iter().flatten();
        let pixel_range = |low: i32, high: i32, limit: i32| {
            let low = (low.div_euclid(SUBPIXEL_ONE) - Self::MARGIN).clamp(0, limit);
            let high = (high.div_euclid(SUBPIXEL_ONE) + 1 + Self::MARGIN).clamp(low, limit);
            (low, high - low)
        };
        let (left, width) =
            pixel_range(points().map(|p| p.x).min().unwrap(), points().map(|p| p.x).max().unwrap(), SCREEN.width);
        let (top, height) =
            pixel_range(points().map(|p| p.y).min().unwrap(), points().map(|p| p.y).max().unwrap(), SCREEN.height);
        Self { left, top, drawn: CoverageSink::new(Size { width, height }), off_screen: 0, outside: 0 }
    }

    /// The pixels this window and `wanted` (the same window) disagree on,
    /// row by row, in screen coordinates.
    fn differing_pixels(&self, wanted: &Window) -> Vec<(i32, i32, Difference)> {
        let size = self.drawn.size();
        let mut pixels = Vec::new();
        for y in 0..size.height {
            for x in 0..size.width {
                let at = (x + self.left, y + self.top);
                match (self.drawn.count(x, y) > 0, wanted.drawn.count(x, y) > 0) {
                    (false, true) => pixels.push((at.0, at.1, Difference::Gap)),
                    (true, false) => pixels.push((at.0, at.1, Difference::Extra)),
                    _ => {}
                }
            }
        }
        pixels
    }
}

impl SpanSink for Window {
    fn size(&self) -> Size {
        SCREEN
    }

    fn span(&mut self, y: i32, x_start: i32, x_end: i32, color: u8) {
        if !SCREEN.holds_span(y, x_start, x_end) {
            self.off_screen += 1;
            return;
        }
        let size = self.drawn.size();
        let row = y - self.top;
        let (start, end) = ((x_start - self.left).clamp(0, size.width), (x_end - self.left).clamp(0, size.width));
        if !(0..size.height).contains(&row) {
            self.outside += (x_end - x_start) as usize;
            return;
        }
        self.outside += (x_end - x_start - (end - start)) as usize;
        if start < end {
            self.drawn.span(row, start, end, color);
        }
    }
}

/// `polygon` drawn by `method` and by the reference sampling at `sample`.
fn draw_both(method: &dyn Method, polygon: &Polygon, sample: SampleOffset) -> (Window, Window) {
    let mut drawn = Window::around(polygon);
    method.fill(polygon, &mut drawn).expect("every classic method takes Listing 38.3");
    let mut wanted = Window::around(polygon);
    reference::fill(polygon, sample, &mut wanted);
    let name = method.info().name;
    assert_eq!((drawn.off_screen, drawn.outside), (0, 0), "{name} drew off the screen or far from {polygon:?}");
    (drawn, wanted)
}

/// Compares every polygon of the three pages drawn by `method` with the
/// reference's under `sample`; `examples` gets a few differing pixels of
/// the first deviating polygon of each kind.
fn measure_under(method: &dyn Method, sample: SampleOffset, label: &str, examples: &mut String) -> Measured {
    let (polygons, page_lengths) = listing_38_3();
    let mut measured = Measured::default();
    let mut per_triangle: [BTreeSet<Count>; 4] = Default::default();
    let mut shown: Vec<Kind> = Vec::new();
    let mut differing = 0;
    for (index, polygon) in polygons.iter().enumerate() {
        let (drawn, wanted) = draw_both(method, polygon, sample);
        let report = drawn.drawn.report(&wanted.drawn);
        let deviation = count(report.gaps, report.extras, report.overdrawn);
        let kind = kind(polygon);
        match kind {
            Kind::Rectangle => measured.kinds.rectangle.add(deviation),
            Kind::Shape => measured.kinds.shape.add(deviation),
            Kind::Triangle(t) => {
                per_triangle[t].insert(deviation);
            }
            Kind::Hexagon => measured.kinds.hexagons.add(deviation),
        }
        if deviation != SAME && !shown.contains(&kind) {
            shown.push(kind);
            let few: Vec<_> = drawn.differing_pixels(&wanted).into_iter().take(4).collect();
            let _ = writeln!(examples, "  {label}, {kind:?} (polygon {index}): {deviation:?}, first {few:?}");
        }
        differing += report.gaps + report.extras;
        for (page, &length) in page_lengths.iter().enumerate() {
            if index + 1 == length {
                measured.pages[page] = differing;
            }
        }
    }
    for (t, counts) in per_triangle.iter().enumerate() {
        assert_eq!(counts.len(), 1, "copies of Triangle{} deviate differently: {counts:?}", t + 1);
        measured.kinds.triangles[t] = *counts.first().unwrap();
    }
    measured
}

fn measure(method: &dyn Method) -> Measurement {
    let mut examples = String::from("\nfirst differing pixels:\n");
    let ours = measure_under(method, SampleOffset::CENTRE, "ours", &mut examples);
    let own = measure_under(method, SampleOffset::of(&method.info().convention), "own", &mut examples);
    Measurement { ours, own, examples }
}

/// The three Abrash ports under our convention. Under their own they draw
/// the reference's pixels (but for `abrash_float`'s two), so all of this
/// is the half-pixel shift between integer samples and centres:
/// - rectangle: edges on pixel corners, horizontal or vertical: 0.
/// - `Triangle1` narrows downward (edges x = ¾k and 30 − ¾k on row k):
///   centre samples, half a row lower and half a pixel right, lose the
///   last pixel of 3 rows in 4 on the right edge (not where it passes
///   through a whole pixel) and nothing on the left: 15 extras.
///   `Triangle2` widens downward: mirrored, 15 gaps on its left edge.
/// - `Triangle3` and `Triangle4` have edges of 2 pixels a row: the one
///   widening downward gains a pixel on each of its 10 rows (gaps), the
///   one narrowing loses one (extras): 10 and 10.
/// - hexagon k (k = 0..15) has four slanted edges 90 − 3k pixels wide: the
///   upper pair widens downward, the lower narrows, and each pair flips
///   90 − 3k pixels, so it has 90 − 3k gaps and as many extras:
///   Σ = 1080 of each.
/// - `ConvexShape`: the same on its thirteen slanted edges: 110 and 172.
///
/// Pages: 282; + 50·15 + 50·15 + 60·20 + 60·20 = 4182; + 2160 = 6342.
const ABRASH_OURS: Measured = Measured {
    pages: [282, 4182, 6342],
    kinds: Kinds {
        rectangle: SAME,
        shape: count(110, 172, 0),
        triangles: [count(0, 15, 0), count(15, 0, 0), count(10, 10, 0), count(10, 10, 0)],
        hexagons: count(1080, 1080, 0),
    },
};

#[test]
fn abrash_float() {
    let measured = measure(&AbrashFloat);
    // Its own convention is the reference at integer sample points, and it
    // picks the reference's pixels but two, both on hexagon 2 (colour 2):
    // the "two pixels" of ch. 39 (`docs/methods.md#abrash-chapter-39`), where the f64
    // product (Y − Y1)·DX/DY crept just over a whole number and `ceil` went
    // one too far. The edges pass exactly through both: (202, 35) on the
    // upper right edge is drawn (a right edge is out), (118, 165) on the
    // lower left edge is missing (a left edge is in).
    let own = Measured { pages: [0, 0, 2], kinds: Kinds { hexagons: count(1, 1, 0), ..NONE.kinds } };
    assert_eq!(measured.own, own, "{}", measured.examples);
    let hexagon_2 = listing_38_3().0.into_iter().find(|p| kind(p) == Kind::Hexagon && p.color == 2).unwrap();
    let (drawn, wanted) = draw_both(&AbrashFloat, &hexagon_2, SampleOffset { x: 0, y: 0 });
    assert_eq!(drawn.differing_pixels(&wanted), [(202, 35, Difference::Extra), (118, 165, Difference::Gap)]);
    // Under ours: the shift of every Abrash port (`ABRASH_OURS`), but
    // hexagon 2 is one pixel closer each way: the centre rule, too, has
    // (202, 35) in and (118, 165) out, so the float errors land on pixels
    // the integer version has as a gap and an extra.
    let ours =
        Measured { pages: [282, 4182, 6340], kinds: Kinds { hexagons: count(1079, 1079, 0), ..ABRASH_OURS.kinds } };
    assert_eq!(measured.ours, ours, "{}", measured.examples);
}

#[test]
fn abrash_int() {
    let measured = measure(&AbrashInt);
    // The integer error terms give X1 + ceil(k·DX/DY) exactly, the pixels
    // the reference picks at integer samples with the top-left rule.
    assert_eq!(measured.own, NONE, "{}", measured.examples);
    assert_eq!(measured.ours, ABRASH_OURS, "{}", measured.examples);
}

#[test]
fn abrash_aet() {
    let measured = measure(&AbrashAet);
    // Ch. 40 keeps the pixel choice of ch. 38 and 39 (tops and left
    // crossings in, bottoms and right crossings out), so on the listing's
    // convex polygons it is `abrash_int` to the pixel.
    assert_eq!(measured.own, NONE, "{}", measured.examples);
    assert_eq!(measured.ours, ABRASH_OURS, "{}", measured.examples);
}

#[test]
fn pendleton() {
    let measured = measure(&Pendleton);
    // Pendleton samples centres as we do, so both conventions give the same
    // counts. Nearly all of them come from the "kluge": an edge stores the
    // top vertex's X on its first row and steps (x2 − x1) / max(2, rows −
    // 1) a row, so it ends on the bottom vertex's X. Against the crossings
    // of the centre lines the stored edge is turned about its middle:
    // short at one end, long at the other, the gaps and extras equal in
    // number.
    // - rectangle: vertical edges store the vertex X on every row: 0.
    // - `Triangle1` and `Triangle2` (edges of 20 rows, ¾ px a row, stepped
    //   15/19): each edge is one pixel off on row 3 and one the other way
    //   on row 16: 2 and 2.
    // - `Triangle3` and `Triangle4` (edges of 10 rows, 2 px a row, stepped
    //   20/9 = 2.22 from the vertex where the centre line crosses 1 px
    //   further on): per edge 3 rows short at one end, 3 long at the
    //   other: 6 and 6.
    // - hexagons and `ConvexShape`: the same turn on every slanted edge;
    //   and on the hexagons, ties: 52 stored crossings of page 3 land
    //   exactly on a pixel centre, and Pendleton's ties go down and right
    //   (a right end takes that pixel, a left end leaves it). Breaking them
    //   the other way, as our rule does, leaves 559 and 559: the ties cost
    //   6 and 6.
    // Pages: 134; + 50·4 + 50·4 + 60·12 + 60·12 = 1974; + 1130 = 3104.
    let expected = Measured {
        pages: [134, 1974, 3104],
        kinds: Kinds {
            rectangle: SAME,
            shape: count(67, 67, 0),
            triangles: [count(2, 2, 0), count(2, 2, 0), count(6, 6, 0), count(6, 6, 0)],
            hexagons: count(565, 565, 0),
        },
    };
    assert_eq!(measured.own, expected, "{}", measured.examples);
    assert_eq!(measured.ours, expected, "{}", measured.examples);
}

#[test]
fn lamothe() {
    let measured = measure(&Lamothe);
    // Own convention, integer samples. LaMothe draws closed spans: every
    // row from a half's top vertex to its bottom vertex, both span ends.
    // So right-edge and bottom pixels the half-open rule leaves out are
    // in; shared edges overlap ("rasterized twice"); x is truncated toward
    // zero, which puts the left end one pixel left of a left edge wherever
    // it is not at a whole pixel.
    // - rectangle: split as `Draw_QuadFP_2D` does, into (0, 1, 3) and
    //   (1, 2, 3); both halves draw their shared diagonal (320,0)-(0,200),
    //   1 or 2 pixels on each of rows 1-199: 318 twice. Its right column
    //   and bottom row, which closed spans would add, are off screen.
    // - `ConvexShape` is not convex: the fan from vertex 0 (right only for
    //   convex polygons) covers the notches of its zig-zag left side
    //   (extras) and overlaps itself (twice). The 8 gaps are single pixels
    //   where f32 truncation pulls a right end short: 6 on the shape's
    //   right edge, 2 on seams between fan triangles.
    // - `Triangle1` (flat top, apex (15,20)): 15 left ends truncated one
    //   pixel out (the rows where x = ¾k is not whole); 10 right ends one
    //   past the edge: row 0's vertex (30,0) and rows 4, 8, 12, 16, where
    //   the edge passes through a whole pixel, and rows 3, 7, 11, 15, 19,
    //   where the pixel count (int)(xe − xs + 1), counted from the
    //   truncated start, overshoots; and the apex row: 26 extras.
    // - `Triangle2` (apex (30,0) on top, flat bottom): the apex pixel, the
    //   31-pixel bottom row, 15 truncated left ends and 4 right ends on
    //   whole pixels: 51 extras; the count from the truncated start falls
    //   one short on rows 3, 7, 11, 15, 19: 5 gaps.
    // - `Triangle3` ((0,0), (20,10), (0,20)): split at its middle vertex,
    //   whose row 10 both halves draw (21 twice); its right edges pass
    //   through a whole pixel on every row, drawn on rows 1-19, plus its
    //   top and bottom vertex pixels: 21 extras.
    // - `Triangle4` ((20,0), (0,10), (20,20)): split at (0,10), row 10
    //   twice (21); its vertical right edge x = 20 drawn on all 21 rows.
    // - hexagons: a fan of four triangles, each split in two: the fan's
    //   diagonals and the split rows twice, closed spans and truncation as
    //   above.
    // Pages: 7316; + 50·26 + 50·56 + 60·21 + 60·21 = 13936; + 1377 = 15313.
    let own = Measured {
        pages: [7316, 13936, 15313],
        kinds: Kinds {
            rectangle: count(0, 0, 318),
            shape: count(8, 7308, 11049),
            triangles: [count(0, 26, 0), count(5, 51, 0), count(0, 21, 21), count(0, 21, 21)],
            hexagons: count(260, 1117, 7117),
        },
    };
    assert_eq!(measured.own, own, "{}", measured.examples);
    // Under ours the half-pixel shift of the Abrash ports comes on top:
    // `Triangle1` gains their 15 extras (41); on `Triangle2` the 15 left
    // pixels ours gains are the ones truncation already draws (36 extras);
    // `Triangle4` gains their 10 and 10. `Triangle3` stays at 21 extras,
    // differently: its upper half now matches (the pixels ours gains are
    // the ones the closed ends draw), its lower half has two extras a row
    // and the bottom vertex one.
    let ours = Measured {
        pages: [7378, 15198, 17613],
        kinds: Kinds {
            rectangle: count(0, 0, 318),
            shape: count(8, 7370, 11049),
            triangles: [count(0, 41, 0), count(5, 36, 0), count(0, 21, 21), count(10, 31, 21)],
            hexagons: count(779, 1636, 7117),
        },
    };
    assert_eq!(measured.ours, ours, "{}", measured.examples);
}

#[test]
fn lamothe_fixed() {
    let measured = measure(&LamotheFixed);
    // Own convention. The same closed spans, splits and fan as `lamothe`
    // (see there); x is rounded to nearest instead of truncated, and the
    // no-x-clip path draws round(xe − xs) + 1 pixels from round(xs).
    // - rectangle: the diagonal twice, one pixel a row on rows 1-199 (row
    //   0's is at x = 320, off screen): 199.
    // - `ConvexShape`: the fan's overreach as in `lamothe`; rounding loses
    //   none of the right ends the float version truncates.
    // - `Triangle1`: the right end one past the edge on rows 0-19, the
    //   left end rounded one pixel out on rows 3, 7, 11, 15, 19 (x = ¾k
    //   with a quarter over: the pixel whose corner is left of the edge),
    //   and the apex: 26 extras.
    // - `Triangle2`: the apex, the 31-pixel bottom row, the right end one
    //   past the edge on rows 1-19 and the left end out on rows 1, 5, 9,
    //   13, 17: 56 extras, and no gaps: rounding never falls short.
    // - `Triangle3`, `Triangle4`: their edges are at whole pixels on every
    //   row, where rounding and truncation agree: as `lamothe`.
    // Pages: 7353; + 50·26 + 50·56 + 60·21 + 60·21 = 13973; + 2200 = 16173.
    let own = Measured {
        pages: [7353, 13973, 16173],
        kinds: Kinds {
            rectangle: count(0, 0, 199),
            shape: count(0, 7353, 11216),
            triangles: [count(0, 26, 0), count(0, 56, 0), count(0, 21, 21), count(0, 21, 21)],
            hexagons: count(0, 2200, 7110),
        },
    };
    assert_eq!(measured.own, own, "{}", measured.examples);
    // Under ours, with the half-pixel shift on top: `Triangle1` gains the
    // 15 extras of the Abrash ports; on `Triangle2` ours gains a left
    // pixel on 15 rows, 5 of them the ones rounding already draws (5
    // extras fewer) and 10 gaps; `Triangle3` as in `lamothe`; `Triangle4`
    // gains the Abrash ports' 10 and 10.
    let ours = Measured {
        pages: [7415, 16235, 19745],
        kinds: Kinds {
            rectangle: count(0, 0, 199),
            shape: count(0, 7415, 11216),
            triangles: [count(0, 41, 0), count(10, 51, 0), count(0, 21, 21), count(10, 31, 21)],
            hexagons: count(655, 2855, 7110),
        },
    };
    assert_eq!(measured.ours, ours, "{}", measured.examples);
}

#[test]
fn wgt() {
    let measured = measure(&Wgt);
    // Own convention, integer rows. Every edge skips its first point, so a
    // polygon's top row is never drawn; both ends of a row are drawn, and
    // x is floored from 8.8, so a left end lands one pixel out wherever the
    // edge is not at a whole pixel, a right end on the edge where it is;
    // the bottom vertex's row is drawn.
    // - rectangle: its top row, 320 gaps; its right column and bottom row,
    //   which both-ends drawing would add, are off screen.
    // - `ConvexShape`: its top row (320 gaps) and 49 more on row 51, where
    //   its right side doubles back along y = 51 from x = 200 to 301 and
    //   250: horizontal edges add nothing and the edge leaving (250,51)
    //   skips that row, so it ends at x = 200 where the reference ends at
    //   249. The extras are floored left ends of its zig-zag and right
    //   ends on whole pixels.
    // - `Triangle1` (flat top): its 30-pixel top row skipped (30 gaps); 15
    //   floored left ends, 4 right ends on the edge (rows 4, 8, 12, 16) and
    //   the apex: 20 extras.
    // - `Triangle2` (pointed top, whose skipped row the reference leaves
    //   empty too): 15 floored left ends, 4 right ends on the edge and the
    //   31-pixel bottom row: 50 extras.
    // - `Triangle3`, `Triangle4`: right edges on whole pixels on rows
    //   1-19, drawn, and the bottom vertex: 20 extras each.
    // - hexagons: the same, and 2 gaps where the 8.8 slope, truncated
    //   toward zero ((84 << 8) / 38 = 565 for 565.9 on hexagon 2, (54 <<
    //   8) / 28 = 493 for 493.7 on hexagon 12), leaves a right end 0.08 px
    //   short of a whole pixel its edge just passes: (213, 40), (212, 73).
    // Pages: 814; + 50·50 + 50·50 + 60·20 + 60·20 = 8214; + 2164 = 10378.
    let own = Measured {
        pages: [814, 8214, 10378],
        kinds: Kinds {
            rectangle: count(320, 0, 0),
            shape: count(369, 125, 0),
            triangles: [count(30, 20, 0), count(0, 50, 0), count(0, 20, 0), count(0, 20, 0)],
            hexagons: count(2, 2162, 0),
        },
    };
    assert_eq!(measured.own, own, "{}", measured.examples);
    // Under ours the half-pixel shift comes on top: `Triangle1` gains the
    // Abrash ports' 15 extras on its right edge; on `Triangle2` ours gains
    // the 15 floored left ends (15 extras fewer). `Triangle3`: ours gains
    // a pixel a row on its upper edge, the very pixels the right ends
    // already draw, and its top vertex's pixel, lost to the skipped row (1
    // gap); its lower edge loses one a row, doubling the extras there
    // (21). `Triangle4`: its skipped top row is not empty under ours and
    // its upper left edge widens (10 gaps); its lower left edge narrows
    // (10 extras more).
    let ours = Measured {
        pages: [992, 9712, 13082],
        kinds: Kinds {
            rectangle: count(320, 0, 0),
            shape: count(427, 245, 0),
            triangles: [count(30, 35, 0), count(0, 35, 0), count(1, 21, 0), count(10, 30, 0)],
            hexagons: count(605, 2765, 0),
        },
    };
    assert_eq!(measured.ours, ours, "{}", measured.examples);
}

#[test]
fn exact_is_the_reference_on_every_page() {
    let measured = measure(&Exact);
    assert_eq!(measured.ours, NONE, "{}", measured.examples);
    assert_eq!(measured.own, NONE, "{}", measured.examples);
}

#[test]
fn every_method_has_its_deviations_pinned_here() {
    let pinned = ["abrash_float", "abrash_int", "abrash_aet", "pendleton", "lamothe", "lamothe_fixed", "wgt", "exact"];
    let names = MethodId::ALL.map(MethodId::name);
    assert_eq!(names, pinned, "a method was added or renamed: pin its deviations in a test of its own");
}
