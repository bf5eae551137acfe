//! Edges into flags: each edge, on each row of a band it meets, flags the
//! column of its crossing.

use core::ops::Range;

use crate::geometry::Polygon;
use crate::target::Size;

use super::super::clip::{right_of_target, visible, visible_rows};
use super::super::edge::Crossing;
use super::grid::Grid;

/// Flags every crossing of `polygon`'s edges on the rows of `band`, in
/// `flags` (the band's rows, `grid.words` words each) and, under the
/// non-zero rule, `counters` (`grid.columns` a row): even-odd toggles the
/// crossing column's bit; non-zero sets it and adds the edge's winding to
/// the column's counter. Each edge is set up on its first row in the band.
pub(super) fn scatter<const NON_ZERO: bool, const CLIP: bool, E: Crossing, const WORDS: usize, const CELLS: usize>(
    polygon: &Polygon,
    band: Range<i64>,
    (grid, size): (Grid, Size),
    flags: &mut [u64; WORDS],
    counters: &mut [[u8; CELLS]],
) {
    for contour in &polygon.contours {
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
            match counters {
                [counters] if NON_ZERO => {
                    let winding = if downward { 1 } else { u8::MAX };
                    for _ in rows {
                        let column = (visible::<CLIP>(edge.column(), size.width) - grid.left) as usize;
                        flags[(word + (column >> 6)) % WORDS] |= 1 << (column & 63);
                        let count = &mut counters[(cell + column) % CELLS];
                        *count = count.wrapping_add(winding);
                        (word, cell) = (word + grid.words, cell + grid.columns);
                        edge.step();
                    }
                }
                _ => {
                    for _ in rows {
                        let column = (visible::<CLIP>(edge.column(), size.width) - grid.left) as usize;
                        flags[(word + (column >> 6)) % WORDS] ^= 1 << (column & 63);
                        word += grid.words;
                        edge.step();
                    }
                }
            }
        }
    }
}
