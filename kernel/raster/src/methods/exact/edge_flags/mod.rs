//! The exact method's edge-flag path: Ackland and Weste's edge flags, with
//! the exact crossings of `edge.rs`. Every edge, on each row it meets,
//! flags the column of its crossing in a grid of bits over the polygon's
//! box (`scatter.rs`); a row's flags read left to right are then its
//! crossings in order, with no sort, and the fill rule pairs them into
//! runs (`scan.rs`). Under the even-odd rule a flag is toggled (only the
//! parity of a column's crossings counts). Under the non-zero rule two
//! planes of flags are set, one for the edges going down and one for
//! those going up: a cell flagged in one moves the winding by one, in
//! both not at all. One bit cannot count two crossings of one direction in
//! a cell (where such edges cross each other, as in a self-intersecting
//! star, or lie within a pixel of each other), so the scatter stops at the
//! first, nothing is emitted, and the polygon is flagged again in one
//! plane whose counters, one per cell, add up the windings of its
//! crossings. The planes need no counters to clear, set or read, which
//! makes the glyphs and icons quicker
//! (docs/lab-history.md#2026-11-29-two-planes-for-the-non-zero-rule-5b89133).
//!
//! There is no edge table, no chain and no event: each edge is set up
//! where the scatter reaches it, and a row costs its crossings and the
//! words of its flags. So it suits polygons of many edges for their box
//! (glyphs, icons, stars, holed polygons), where the edge table's setup,
//! events and sorting cost more than its rows. The grid is on the stack,
//! in the smallest of three sizes that holds the box, cleared once a fill
//! and by the scan as it reads: a box larger than the largest is walked
//! in bands, each scattering the edges that meet it.
//!
//! The path takes polygons whose vertices lie within 512 px across (so a
//! row is at most 513 columns, 9 words), and, under the
//! non-zero rule, of under 256 edges, for its counters are bytes: they
//! add up modulo 256, and a winding number is then below 256 in size, so
//! it is zero exactly when its byte is.

mod grid;
mod scan;
mod scatter;

use core::ops::Range;

use crate::geometry::{FillRule, Point, PolygonRef};
use crate::target::{Size, SpanSink};

use super::bounds::Bounds;
use super::clip::{beside_target, columns_fit, visible_column};
use super::edge::{first_sample_at_or_after, Crossing, EdgeStepper, ShortEdge};
use super::spans::Target;
use grid::Grid;

/// Flags on the stack, and their counters, in three sizes: the smallest
/// that holds the whole box is cleared for a fill, so that clearing costs
/// at most a few times the box's own bits and bytes, and a box the largest
/// does not hold is walked in bands of it.
const SMALL: (usize, usize) = (32, 512);
const MEDIUM: (usize, usize) = (128, 4096);
const LARGE: (usize, usize) = (512, 16384);

/// Fills `polygon`, whose box is `bounds` and which the path takes
/// ([`Bounds::takes`]), by its fill rule.
pub(super) fn fill<C: AsRef<[Point]>, S: SpanSink + ?Sized>(
    polygon: PolygonRef<'_, C>,
    bounds: Bounds,
    size: Size,
    sink: &mut S,
) {
    let Some(fill) = Fill::new(polygon, bounds, size) else { return };
    let Bounds { min, max } = bounds;
    let short = ShortEdge::fits((min.x, max.x), (min.y, max.y));
    let clip = !columns_fit(min.x, max.x, size.width);
    match (short, clip) {
        (true, false) => fill.sized::<false, ShortEdge, S>(sink),
        (true, true) => fill.sized::<true, ShortEdge, S>(sink),
        (false, false) => fill.sized::<false, EdgeStepper, S>(sink),
        (false, true) => fill.sized::<true, EdgeStepper, S>(sink),
    }
}

/// One fill of the path.
struct Fill<'a, C> {
    polygon: PolygonRef<'a, C>,
    rows: Range<i64>,
    grid: Grid,
    size: Size,
    target: Target,
}

// By hand, for every `C`, as the polygon's.
impl<C> Clone for Fill<'_, C> {
    fn clone(&self) -> Self {
        Fill { polygon: self.polygon, rows: self.rows.clone(), grid: self.grid, size: self.size, target: self.target }
    }
}

impl<'a, C: AsRef<[Point]>> Fill<'a, C> {
    /// The fill of `polygon`, whose box is `bounds`, on a target of
    /// `size`, or `None` when the box has no visible pixel.
    fn new(polygon: PolygonRef<'a, C>, bounds: Bounds, size: Size) -> Option<Self> {
        let Bounds { min, max } = bounds;
        let rows = first_sample_at_or_after(min.y.into()).max(0)
            ..first_sample_at_or_after(max.y.into()).min(size.height.into());
        let left = visible_column(first_sample_at_or_after(min.x.into()), size.width);
        let right = visible_column(first_sample_at_or_after(max.x.into()), size.width);
        if rows.is_empty() || beside_target(min.x, max.x, size.width) {
            return None;
        }
        let columns = (right - left) as usize + 1;
        let grid = Grid { left, words: columns.div_ceil(64), columns };
        Some(Fill { polygon, rows, grid, size, target: Target { color: polygon.color, width: size.width } })
    }

    /// Fills on the smallest flags (and, under the non-zero rule,
    /// counters) that hold the whole box, or in bands of the largest.
    /// Under the non-zero rule, a box that one band of flags holds is
    /// first tried on two planes of flags, which need no counters.
    #[inline(always)]
    fn sized<const CLIP: bool, E: Crossing, S: SpanSink + ?Sized>(self, sink: &mut S) {
        let rows = (self.rows.end - self.rows.start) as usize;
        let whole = |words: usize| rows * self.grid.words <= words;
        let counted = |cells: usize| self.polygon.rule == FillRule::EvenOdd || rows * self.grid.columns <= cells;
        let fits = |(words, cells): (usize, usize)| whole(words) && counted(cells);
        if self.polygon.rule == FillRule::NonZero {
            let planted = match (whole(SMALL.0), whole(MEDIUM.0), whole(LARGE.0)) {
                (true, _, _) => self.clone().planes::<{ SMALL.0 }, CLIP, E, S>(sink),
                (false, true, _) => self.clone().planes::<{ MEDIUM.0 }, CLIP, E, S>(sink),
                (false, false, true) => self.clone().planes::<{ LARGE.0 }, CLIP, E, S>(sink),
                _ => false,
            };
            if planted {
                return;
            }
        }
        match (self.polygon.rule, fits(SMALL), fits(MEDIUM)) {
            (FillRule::EvenOdd, true, _) => self.bands::<false, 0, { SMALL.0 }, { SMALL.1 }, CLIP, E, S>(sink),
            (FillRule::EvenOdd, false, true) => self.bands::<false, 0, { MEDIUM.0 }, { MEDIUM.1 }, CLIP, E, S>(sink),
            (FillRule::EvenOdd, false, false) => self.bands::<false, 0, { LARGE.0 }, { LARGE.1 }, CLIP, E, S>(sink),
            (FillRule::NonZero, true, _) => self.bands::<true, 1, { SMALL.0 }, { SMALL.1 }, CLIP, E, S>(sink),
            (FillRule::NonZero, false, true) => self.bands::<true, 1, { MEDIUM.0 }, { MEDIUM.1 }, CLIP, E, S>(sink),
            (FillRule::NonZero, false, false) => self.bands::<true, 1, { LARGE.0 }, { LARGE.1 }, CLIP, E, S>(sink),
        }
    }

    /// Fills the whole box as one band under the non-zero rule on two
    /// planes of flags, one for each direction of edge, and returns
    /// `true`; unless two crossings of one direction meet in one cell,
    /// which one bit cannot count: then it has emitted nothing and
    /// returns `false`, for the counters to count them.
    #[inline(never)]
    fn planes<const WORDS: usize, const CLIP: bool, E: Crossing, S: SpanSink + ?Sized>(self, sink: &mut S) -> bool {
        let (mut down, mut up) = ([0u64; WORDS], [0u64; WORDS]);
        let ok = scatter::scatter_planes::<CLIP, E, WORDS>(
            self.polygon,
            self.rows.clone(),
            (self.grid, self.size),
            &mut down,
            &mut up,
        );
        if ok {
            scan::planes::<WORDS, S>(self.rows, self.grid, &mut down, &mut up, self.target, sink);
        }
        ok
    }

    /// Walks the rows in bands of as many rows as the flags (and, under
    /// the non-zero rule, the counters: `COUNTED` blocks of them) hold.
    /// Never inlined, so that the caller's frame holds only the flags of
    /// its size.
    #[inline(never)]
    fn bands<
        const NON_ZERO: bool,
        const COUNTED: usize,
        const WORDS: usize,
        const CELLS: usize,
        const CLIP: bool,
        E: Crossing,
        S: SpanSink + ?Sized,
    >(
        self,
        sink: &mut S,
    ) {
        let mut flags = [0u64; WORDS];
        let mut counters = [[0u8; CELLS]; COUNTED];
        let band =
            if NON_ZERO { (WORDS / self.grid.words).min(CELLS / self.grid.columns) } else { WORDS / self.grid.words };
        let mut start = self.rows.start;
        while start < self.rows.end {
            let rows = start..(start + band as i64).min(self.rows.end);
            scatter::scatter::<NON_ZERO, CLIP, E, WORDS, CELLS>(
                self.polygon,
                rows.clone(),
                (self.grid, self.size),
                &mut flags,
                &mut counters,
            );
            scan::scan::<NON_ZERO, WORDS, CELLS, S>(
                rows.clone(),
                self.grid,
                &mut flags,
                &mut counters,
                self.target,
                sink,
            );
            start = rows.end;
        }
    }
}

#[cfg(test)]
mod tests {
    use alloc::vec::Vec;

    use super::*;
    use crate::coverage::CoverageSink;
    use crate::geometry::Polygon;
    use crate::reference::{self, SampleOffset};

    const SIZE: Size = Size { width: 24, height: 20 };

    fn contour(points: &[(i32, i32)]) -> Vec<Point> {
        points.iter().map(|&(x, y)| Point::from_pixels(x, y)).collect()
    }

    /// Where two crossings of one direction meet in a cell the two planes
    /// give way, having emitted nothing, and the counters count them;
    /// elsewhere the planes fill. Either way the pixels are the
    /// reference's.
    #[test]
    fn the_planes_give_way_to_the_counters_where_crossings_of_one_direction_meet() {
        let square = contour(&[(2, 2), (18, 2), (18, 16), (2, 16)]);
        let mut hole = contour(&[(6, 5), (13, 5), (13, 12), (6, 12)]);
        hole.reverse();
        // The points of a regular five-pointed star, every second one in
        // turn: its edges cross, some of one direction.
        let star = contour(&[(12, 1), (19, 17), (2, 7), (22, 7), (5, 17)]);
        let cases = [
            (Vec::from([square.clone(), hole]), true),
            (Vec::from([square.clone(), square]), false),
            (Vec::from([star]), false),
        ];
        for (contours, planes) in cases {
            let polygon = Polygon { contours, color: 1, rule: FillRule::NonZero };
            let borrowed = PolygonRef::from(&polygon);
            let fill = Fill::new(borrowed, Bounds::of(borrowed), SIZE).unwrap();
            let mut on_planes = CoverageSink::new(SIZE);
            assert_eq!(fill.planes::<{ LARGE.0 }, false, EdgeStepper, _>(&mut on_planes), planes, "{polygon:?}");
            let mut flags = CoverageSink::new(SIZE);
            super::fill(borrowed, Bounds::of(borrowed), SIZE, &mut flags);
            let mut judge = CoverageSink::new(SIZE);
            reference::fill(&polygon, SampleOffset::CENTRE, &mut judge);
            assert_eq!(flags.ascii(), judge.ascii(), "{polygon:?}");
            let expected = if planes { judge.ascii() } else { CoverageSink::new(SIZE).ascii() };
            assert_eq!(on_planes.ascii(), expected, "{polygon:?}");
        }
    }
}
