//! Flags into spans: a row's flags read left to right are its crossings
//! in order, and the fill rule pairs them into runs: by parity under the
//! even-odd rule, by the winding of the counters or of the two planes
//! under the non-zero rule.

use core::ops::Range;

use crate::target::SpanSink;

use super::super::spans::{emit, Target};
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
/// the target are not flagged).
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
                emit(row, start, offset + bits.trailing_zeros() as i32, target, sink);
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
                emit(row, start, offset + bits.trailing_zeros() as i32, target, sink);
                bits &= bits - 1;
            }
        }
        if open {
            emit(row, start, target.width, target, sink);
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
        let (mut winding, mut start) = (0u8, 0);
        for i in 0..grid.words {
            let mut bits = core::mem::take(&mut flags[(first + i) % WORDS]);
            while bits != 0 {
                let at = 64 * i + bits.trailing_zeros() as usize;
                bits &= bits - 1;
                let was = winding;
                winding = winding.wrapping_add(core::mem::take(&mut counters[(cells + at) % CELLS]));
                let column = grid.left + at as i32;
                if was == 0 {
                    start = column;
                } else if winding == 0 {
                    emit(row, start, column, target, sink);
                }
            }
        }
        if winding != 0 {
            emit(row, start, target.width, target, sink);
        }
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
        let (mut winding, mut start) = (0i32, 0);
        for i in 0..grid.words {
            let word = (first + i) % WORDS;
            let (downs, ups) = (core::mem::take(&mut down[word]), core::mem::take(&mut up[word]));
            let mut bits = downs ^ ups;
            while bits != 0 {
                let at = bits.trailing_zeros();
                bits &= bits - 1;
                let was = winding;
                winding += 2 * ((downs >> at) & 1) as i32 - 1;
                let column = grid.left + 64 * i as i32 + at as i32;
                if was == 0 {
                    start = column;
                } else if winding == 0 {
                    emit(row, start, column, target, sink);
                }
            }
        }
        if winding != 0 {
            emit(row, start, target.width, target, sink);
        }
        first += grid.words;
    }
}
