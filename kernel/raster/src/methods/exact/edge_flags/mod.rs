//! The exact method's edge-flag path: Ackland and Weste's edge flags, with
//! the exact crossings of `edge.rs`. Every edge, on each row it meets,
//! flags the column of its crossing in a grid of bits over the polygon's
//! box (`scatter.rs`); a row's flags read left to right are then its
//! crossings in order, with no sort, and the fill rule pairs them into
//! runs (`scan.rs`). Under the even-odd rule a flag is toggled (only the
//! parity of a column's crossings counts); under the non-zero rule it is
//! set, and a counter per cell adds up the windings of its crossings.
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

use crate::geometry::{FillRule, Polygon};
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
pub(super) fn fill<S: SpanSink + ?Sized>(polygon: &Polygon, bounds: Bounds, size: Size, sink: &mut S) {
    let Bounds { min, max } = bounds;
    let rows =
        first_sample_at_or_after(min.y.into()).max(0)..first_sample_at_or_after(max.y.into()).min(size.height.into());
    let left = visible_column(first_sample_at_or_after(min.x.into()), size.width);
    let right = visible_column(first_sample_at_or_after(max.x.into()), size.width);
    if rows.is_empty() || beside_target(min.x, max.x, size.width) {
        return;
    }
    let columns = (right - left) as usize + 1;
    let grid = Grid { left, words: columns.div_ceil(64), columns };
    let fill = Fill { polygon, rows, grid, size, target: Target { color: polygon.color, width: size.width } };
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
#[derive(Clone)]
struct Fill<'a> {
    polygon: &'a Polygon,
    rows: Range<i64>,
    grid: Grid,
    size: Size,
    target: Target,
}

impl Fill<'_> {
    /// Fills on the smallest flags (and, under the non-zero rule,
    /// counters) that hold the whole box, or in bands of the largest.
    #[inline(always)]
    fn sized<const CLIP: bool, E: Crossing, S: SpanSink + ?Sized>(self, sink: &mut S) {
        let rows = (self.rows.end - self.rows.start) as usize;
        let counted = |cells: usize| self.polygon.rule == FillRule::EvenOdd || rows * self.grid.columns <= cells;
        let fits = |(words, cells): (usize, usize)| rows * self.grid.words <= words && counted(cells);
        match (self.polygon.rule, fits(SMALL), fits(MEDIUM)) {
            (FillRule::EvenOdd, true, _) => self.bands::<false, 0, { SMALL.0 }, { SMALL.1 }, CLIP, E, S>(sink),
            (FillRule::EvenOdd, false, true) => self.bands::<false, 0, { MEDIUM.0 }, { MEDIUM.1 }, CLIP, E, S>(sink),
            (FillRule::EvenOdd, false, false) => self.bands::<false, 0, { LARGE.0 }, { LARGE.1 }, CLIP, E, S>(sink),
            (FillRule::NonZero, true, _) => self.bands::<true, 1, { SMALL.0 }, { SMALL.1 }, CLIP, E, S>(sink),
            (FillRule::NonZero, false, true) => self.bands::<true, 1, { MEDIUM.0 }, { MEDIUM.1 }, CLIP, E, S>(sink),
            (FillRule::NonZero, false, false) => self.bands::<true, 1, { LARGE.0 }, { LARGE.1 }, CLIP, E, S>(sink),
        }
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
