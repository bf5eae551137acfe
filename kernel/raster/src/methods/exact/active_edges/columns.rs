//! Rows with a crossing for every four columns or more (scribbles of
//! thousands of edges): their crossings summed per column instead of
//! sorted, the running sum from the left being each pixel's winding number.

use crate::target::SpanSink;

use super::super::clip::visible_column;
use super::super::edge::Crossing;
use super::super::spans::{emit, Target};
use super::runs::is_inside;
use super::tables::{Active, Edge};

/// Emits the inside runs of `row` without sorting the crossings and steps
/// every edge to the next row: each crossing's winding is added at its
/// visible column in `windings` (`width + 1` of them), and the running sum
/// from the left is each pixel's winding number. `O(edges + width)` a
/// row; the runs are the maximal ones, left to right.
pub(super) fn emit_by_columns<const NON_ZERO: bool, E: Crossing, S: SpanSink + ?Sized>(
    row: i64,
    active: &mut [Active<E>],
    edges: &[Edge<E>],
    windings: &mut [i32],
    target: Target,
    sink: &mut S,
) {
    windings.fill(0);
    for chain in active {
        windings[visible_column(chain.stepper.column(), target.width) as usize] += i32::from(chain.winding);
        chain.advance(row + 1, edges);
    }
    // Which pixels are inside, 64 a word, without a branch per pixel; then
    // one step per change of state, where a run opens or closes.
    let (mut sum, mut inside, mut start) = (0i32, false, 0i64);
    for (word, chunk) in windings[..target.width as usize].chunks(64).enumerate() {
        let mut bits = 0u64;
        for (i, &winding) in chunk.iter().enumerate() {
            sum += winding;
            bits |= u64::from(is_inside::<NON_ZERO>(i64::from(sum))) << i;
        }
        // Bit `i` set where pixel `i` differs from the one before it.
        let mut changes = bits ^ (bits << 1 | u64::from(inside));
        if chunk.len() < 64 {
            changes &= (1 << chunk.len()) - 1;
        }
        while changes != 0 {
            let x = (word * 64) as i64 + i64::from(changes.trailing_zeros());
            if inside {
                // Columns in `0..=width`, an `i32`.
                emit(row, start as i32, x as i32, target, sink);
            } else {
                start = x;
            }
            inside = !inside;
            changes &= changes - 1;
        }
    }
    if inside {
        emit(row, start as i32, target.width, target, sink);
    }
}
