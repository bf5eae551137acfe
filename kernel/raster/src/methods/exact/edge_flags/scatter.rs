//! Edges into flags: each edge, on each row of a band it meets, flags the
//! column of its crossing.

use core::ops::Range;

use crate::geometry::{Point, PolygonRef};
use crate::target::Size;

use super::super::clip::{right_of_target, visible, visible_rows};
use super::super::edge::Crossing;
use super::grid::Grid;

/// Flags every crossing of `polygon`'s edges on the rows of `band`, in
/// `flags` (the band's rows, `grid.words` words each) and, under the
/// non-zero rule, `counters` (`grid.columns` a row): even-odd toggles the
/// crossing column's bit; non-zero sets it and adds the edge's winding to
/// the column's counter.
pub(super) fn scatter<const NON_ZERO: bool, const CLIP: bool, E: Crossing, const WORDS: usize, const CELLS: usize>(
    polygon: PolygonRef<'_, impl AsRef<[Point]>>,
    band: Range<i64>,
    (grid, size): (Grid, Size),
    flags: &mut [u64; WORDS],
    counters: &mut [[u8; CELLS]],
) {
    let _ = match counters {
        [counters] if NON_ZERO => crossings::<CLIP, E>(polygon, band, (grid, size), |downward, word, cell, column| {
            flags[(word + (column >> 6)) % WORDS] |= 1 << (column & 63);
            let count = &mut counters[(cell + column) % CELLS];
            *count = count.wrapping_add(if downward { 1 } else { u8::MAX });
            true
        }),
        _ => crossings::<CLIP, E>(polygon, band, (grid, size), |_, word, _, column| {
            flags[(word + (column >> 6)) % WORDS] ^= 1 << (column & 63);
            true
        }),
    };
}

/// Flags every crossing of `polygon`'s edges on the rows of `band` under
/// the non-zero rule in two planes of bits, `down` for edges that go down
/// and `up` for those that go up, and returns whether it could: it stops
/// at the first crossing that meets another of its direction in one cell,
/// which the planes cannot count (the counters must then be used).
pub(super) fn scatter_planes<const CLIP: bool, E: Crossing, const WORDS: usize>(
    polygon: PolygonRef<'_, impl AsRef<[Point]>>,
    band: Range<i64>,
    (grid, size): (Grid, Size),
    down: &mut [u64; WORDS],
    up: &mut [u64; WORDS],
) -> bool {
    crossings::<CLIP, E>(polygon, band, (grid, size), |downward, word, _, column| {
        let plane = if downward { &mut *down } else { &mut *up };
        let (word, bit) = ((word + (column >> 6)) % WORDS, 1 << (column & 63));
        let alone = plane[word] & bit == 0;
        plane[word] |= bit;
        alone
    })
}

/// Calls `flag(downward, word, cell, column)` for every crossing of
/// `polygon`'s edges on the rows of `band` (the row's first word of flags
/// and first cell of counters, and the column from the grid's left) until
/// it returns `false`, and returns whether it never did. Each edge is set
/// up on its first row in the band.
#[inline(always)]
fn crossings<const CLIP: bool, E: Crossing>(
    polygon: PolygonRef<'_, impl AsRef<[Point]>>,
    band: Range<i64>,
    (grid, size): (Grid, Size),
    mut flag: impl FnMut(bool, usize, usize, usize) -> bool,
) -> bool {
    for contour in polygon.contours {
        let contour = contour.as_ref();
        let Some(&last) = contour.last() else { continue };
        let mut from = last;
        for &to in contour {
            let downward = from.y <= to.y;
            let (upper, lower) = if downward { (from, to) } else { (to, from) };
            from = to;
            let rows = visible_rows(upper.y, lower.y, size.height);
            let rows = rows.start.max(band.start)..rows.end.min(band.end);
            if rows.is_empty() || right_of_target(upper.x.min(lower.x), size.width) {
                continue;
            }
            let mut edge = if rows.end - rows.start == 1 {
                E::at_last_row(upper, lower, rows.start)
            } else {
                E::at_row(upper, lower, rows.start)
            };
            // Visible columns are at or right of `grid.left`, at most
            // `grid.columns - 1` past it: every index is in its array (the
            // remainders only say so to the compiler).
            let row = (rows.start - band.start) as usize;
            let (mut word, mut cell) = (row * grid.words, row * grid.columns);
            for _ in rows {
                let column = (visible::<CLIP>(edge.column(), size.width) - grid.left) as usize;
                if !flag(downward, word, cell, column) {
                    return false;
                }
                (word, cell) = (word + grid.words, cell + grid.columns);
                edge.step();
            }
        }
    }
    true
}
