//! The fill rule, applied to a row's crossings in order: which of them
//! open and close the runs of pixels inside.

use super::tables::{Active, Run};

/// Works out the inside runs of `active`, in order, into `runs`, and
/// returns how many: each crossing's winding sum (of the crossings before
/// it and up to it) under the rule says whether it opens a run, closes one
/// or neither. A pixel's inside test sums every crossing at or left of
/// it; where several share a column, the states between them cover no
/// pixel, so any order of theirs gives the same pixels. A run still open
/// after the last crossing reaches the right border (edges right of the
/// target are not in the table, so the sum need not come back to zero).
/// `runs` has a place per active edge and one more.
pub(super) fn plan<const NON_ZERO: bool, E>(active: &[Active<E>], runs: &mut [Run]) -> usize {
    // Each crossing adds +1 or -1: no `i64` overflow for any edge count.
    // Without a branch per crossing (which way each goes is anyone's
    // guess): every crossing writes a run, which only a closing one keeps.
    let (mut winding, mut open, mut count) = (0i64, 0, 0);
    for (i, edge) in active.iter().enumerate() {
        let was_inside = is_inside::<NON_ZERO>(winding);
        winding += i64::from(edge.winding);
        let inside = is_inside::<NON_ZERO>(winding);
        open = if inside && !was_inside { i as u32 } else { open };
        runs[count] = Run { open, close: i as u32 };
        count += usize::from(was_inside && !inside);
    }
    runs[count] = Run { open, close: active.len() as u32 };
    count + usize::from(is_inside::<NON_ZERO>(winding))
}

/// Whether a winding sum (signed crossings left of a centre) means inside.
/// Every crossing is +1 or -1, so the sum's parity is the crossing count's.
#[inline(always)]
pub(super) fn is_inside<const NON_ZERO: bool>(winding: i64) -> bool {
    if NON_ZERO {
        winding != 0
    } else {
        winding & 1 != 0
    }
}
