//! Keeping the walk's crossings in order, left to right by visible column:
//! the order the inside test needs, as the crossings at or left of a
//! visible pixel are then a prefix of it. The active chains come sorted
//! but for chains that just joined or crossed, so insertion does most
//! rows; a wholesale sort is the fallback.

use super::super::clip::visible_column;
use super::super::edge::Crossing;
use super::tables::{start_index, Active, Wide};

/// Insertion sorts may move edges past each other four times this often
/// however few they are.
const SHORT: usize = 16;

/// Sorts `active` by visible column and sets `columns` to them: by
/// insertion when the list is short or out of order in a few places, else
/// in `wide` when there is one, else by the library's in-place sort.
pub(super) fn sort<E: Crossing>(
    active: &mut [Active<E>],
    columns: &mut [i32],
    width: i32,
    wide: Option<&mut Wide<'_, E>>,
) {
    let column = |edge: &Active<E>| visible_column(edge.stepper.column(), width);
    for (slot, edge) in columns.iter_mut().zip(active.iter()) {
        *slot = column(edge);
    }
    if !insertion_sort(active, columns) {
        match wide {
            Some(wide) => sort_wide(wide, active, width),
            None => active.sort_unstable_by_key(column),
        }
        for (slot, edge) in columns.iter_mut().zip(active.iter()) {
            *slot = column(edge);
        }
    }
}

/// Sorts `active` by `columns` (moving both), then by position
/// ([`Crossing::position_in`]), by insertion, unless that takes moving
/// edges past each other more often than four times per edge (quadratic
/// is near when many cross): then it stops, with both in some order, and
/// returns `false`.
#[inline(always)]
pub(super) fn insertion_sort<E: Crossing>(active: &mut [Active<E>], columns: &mut [i32]) -> bool {
    // Crossings in one column go by position where the stepper has one, so
    // that the order is the positions' (`walk.rs`, `rows_in_pairs`).
    let key = |chain: &Active<E>, column: i32| (column, chain.stepper.position_in(0));
    let mut budget = 4 * active.len().max(SHORT);
    for i in 1..active.len().min(columns.len()) {
        let mut j = i;
        while j > 0 && key(&active[j - 1], columns[j - 1]) > key(&active[j], columns[j]) {
            if budget == 0 {
                return false;
            }
            columns.swap(j - 1, j);
            active.swap(j - 1, j);
            (j, budget) = (j - 1, budget - 1);
        }
    }
    true
}

/// Sorts `active` by visible column, in `O(n + width)` by counting where
/// the target is narrow next to the edge count, else in `O(n log n)` by
/// 64-bit keys (visible column above index), then moved into that order
/// once: cheaper than sorting the edges themselves, which are larger.
fn sort_wide<E: Crossing>(wide: &mut Wide<'_, E>, active: &mut [Active<E>], width: i32) {
    let column = |edge: &Active<E>| visible_column(edge.stepper.column(), width) as usize;
    let spare = &mut wide.spare[..active.len()];
    if !wide.counts.is_empty() {
        wide.counts.fill(0);
        for edge in active.iter() {
            wide.counts[column(edge)] += 1;
        }
        let mut next = 0;
        for count in wide.counts.iter_mut() {
            (*count, next) = (next, next + *count);
        }
        for edge in active.iter() {
            let slot = &mut wide.counts[column(edge)];
            spare[*slot as usize] = *edge;
            *slot += 1;
        }
    } else {
        // Visible columns are below 2^31 and indices below 2^32.
        let keys = &mut wide.keys[..active.len()];
        for (i, (key, edge)) in keys.iter_mut().zip(active.iter()).enumerate() {
            *key = (column(edge) as u64) << 32 | i as u64;
        }
        keys.sort_unstable();
        for (edge, &key) in spare.iter_mut().zip(keys.iter()) {
            *edge = active[start_index(key)];
        }
    }
    active.copy_from_slice(spare);
}
