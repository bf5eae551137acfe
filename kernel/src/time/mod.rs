//! Time: the clock every wait in the kernel ends by (`clock`: the
//! time-stamp counter, its rate measured at boot against the timers of
//! `timers` and `pit`), and the real-time clock's periodic interrupt
//! (`rtc`) that the test-only `FAULT` commands raise.
//!
//! Uses `platform` alone.

pub mod clock;
mod pit;
pub mod rtc;
mod timers;
