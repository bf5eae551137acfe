//! Flags into spans: a row's flags read left to right are its crossings
//! in order, and the fill rule pairs them into runs: by parity under the
//! even-odd rule, by the winding of the counters or of the two planes
//! under the non-zero rule.

use core::ops::Range;

use crate::target::SpanSink;

use super::super::spans::{emit, emit_irregular, Target};
use super::grid::Grid;

/// Emits the inside runs of every row of `band` from its flags (and
/// counters), clearing them for the next band.
pub(super) fn scan<const NON_ZERO: bool, const WORDS: usize, const CELLS: usize, S: SpanSink + ?Sized>(
    band: Range<i64>,
    grid: Grid,
    flags: &mut [u64; WORDS],
    counters: &mut [[u8; CELLS]],
    target: Target,
    sink: &mut S,
) {
    match counters {
        [counters] if NON_ZERO => non_zero(band, grid, flags, counters, target, sink),
        _ => even_odd(band, grid, flags, target, sink),
    }
}

/// Under the even-odd rule each flag opens or closes a run, in turn; a
/// run still open after the last reaches the right border (edges right of
/// the target are not flagged). The runs go to the sink as irregular
/// spans ([`SpanSink::irregular_span`]): on the stars, whose rows hold
/// runs of every length, the framebuffer's masked store of them is the
/// quicker (docs/lab-history.md#2026-11-29-the-even-odd-runs-in-one-masked-store-1151701).
/// The non-zero rule's runs gained nothing from it.
#[inline(always)]
fn even_odd<const WORDS: usize, S: SpanSink + ?Sized>(
    band: Range<i64>,
    grid: Grid,
    flags: &mut [u64; WORDS],
    target: Target,
    sink: &mut S,
) {
    let mut first = 0;
    for row in band {
        let (mut open, mut start) = (false, 0);
        for i in 0..grid.words {
            let mut bits = core::mem::take(&mut flags[(first + i) % WORDS]);
            let offset = grid.left + 64 * i as i32;
            if open && bits != 0 {
                emit_irregular(row, start, offset + bits.trailing_zeros() as i32, target, sink);
                bits &= bits - 1;
                open = false;
            }
            while bits != 0 {
                start = offset + bits.trailing_zeros() as i32;
                bits &= bits - 1;
                if bits == 0 {
                    open = true;
                    break;
                }
                emit_irregular(row, start, offset + bits.trailing_zeros() as i32, target, sink);
                bits &= bits - 1;
            }
        }
        if open {
            emit_irregular(row, start, target.width, target, sink);
        }
        first += grid.words;
    }
}

/// Under the non-zero rule a flag's counter holds the windings of the
/// crossings at its column: a run opens where their running sum leaves
/// zero and closes where it comes back.
#[inline(always)]
fn non_zero<const WORDS: usize, const CELLS: usize, S: SpanSink + ?Sized>(
    band: Range<i64>,
    grid: Grid,
    flags: &mut [u64; WORDS],
    counters: &mut [u8; CELLS],
    target: Target,
    sink: &mut S,
) {
    let (mut first, mut cells) = (0, 0);
    for row in band {
        let mut runs = Runs::default();
        for i in 0..grid.words {
            let mut bits = core::mem::take(&mut flags[(first + i) % WORDS]);
            while bits != 0 {
                let at = 64 * i + bits.trailing_zeros() as usize;
                bits &= bits - 1;
                let by = core::mem::take(&mut counters[(cells + at) % CELLS]);
                runs.cross(by, grid.left + at as i32, row, target, sink);
            }
        }
        runs.end(row, target, sink);
        (first, cells) = (first + grid.words, cells + grid.columns);
    }
}

/// Under the non-zero rule with two planes of flags, `down` for edges
/// going down and `up` for those going up, neither with two crossings in
/// one cell: a cell flagged in one plane moves the winding by one, in both
/// not at all; a run opens where the winding leaves zero and closes where
/// it comes back.
pub(super) fn planes<const WORDS: usize, S: SpanSink + ?Sized>(
    band: Range<i64>,
    grid: Grid,
    down: &mut [u64; WORDS],
    up: &mut [u64; WORDS],
    target: Target,
    sink: &mut S,
) {
    let mut first = 0;
    for row in band {
        let mut runs = Runs::default();
        for i in 0..grid.words {
            let word = (first + i) % WORDS;
            let (downs, ups) = (core::mem::take(&mut down[word]), core::mem::take(&mut up[word]));
            let mut bits = downs ^ ups;
            while bits != 0 {
                let at = bits.trailing_zeros();
                bits &= bits - 1;
                // One going down adds 1, one going up 255 (-1 modulo 256).
                let by = 2 * ((downs >> at) & 1) as u8;
                runs.cross(by.wrapping_sub(1), grid.left + 64 * i as i32 + at as i32, row, target, sink);
            }
        }
        runs.end(row, target, sink);
        first += grid.words;
    }
}

/// A row's winding under the non-zero rule so far, modulo 256 (exact for
/// the path's polygons, of under 256 edges), and where its open run
/// starts.
#[derive(Default)]
struct Runs {
    winding: u8,
    start: i32,
}

impl Runs {
    /// A crossing at `column` that moves the winding by `by`: a run opens
    /// where the winding leaves zero and closes where it comes back.
    #[inline(always)]
    fn cross<S: SpanSink + ?Sized>(&mut self, by: u8, column: i32, row: i64, target: Target, sink: &mut S) {
        let was = self.winding;
        self.winding = was.wrapping_add(by);
        if was == 0 {
            self.start = column;
        } else if self.winding == 0 {
            emit(row, self.start, column, target, sink);
        }
    }

    /// The row's end: a run still open reaches the right border (edges
    /// right of the target are not flagged).
    #[inline(always)]
    fn end<S: SpanSink + ?Sized>(self, row: i64, target: Target, sink: &mut S) {
        if self.winding != 0 {
            emit(row, self.start, target.width, target, sink);
        }
    }
}
