//! The edge flags' grid: where a row's flags and counters lie on the
//! target, shared by the scatter that sets them and the scan that reads
//! them.

/// Where a row's flags lie on the target: bit 0 of a row is column
/// `left`; each row has `words` words of flags, and `columns` counters
/// (one per column from `left` to the box's last).
#[derive(Clone, Copy, Debug)]
pub(super) struct Grid {
    pub left: i32,
    pub words: usize,
    pub columns: usize,
}
