//! The seeded generator of the unit tests that draw random operands (one
//! room of its own at the crate's top, so that tests in any folder may
//! use it without one folder importing another's tests).

/// A xorshift generator from a nonzero `seed`: the same numbers on every
/// run, so a failure names an input that fails again.
pub(crate) fn xorshift(mut seed: u64) -> impl FnMut() -> u64 {
    move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        seed
    }
}
