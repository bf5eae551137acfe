//! Time: the CPU's time-stamp counter, its rate measured once at boot.
//! Every wait in the kernel ends by this clock ([`Deadline`]), never after
//! a count of port reads: what a port read costs differs from machine to
//! machine by orders of magnitude (a few nanoseconds of virtual time under
//! an emulator such as Bochs, about a microsecond on a real ISA bus).
//!
//! The rate comes from the first source that has it:
//! 1. the PIT (channel 0 counted for 10 ms), found on every PC and
//!    emulator this was tried on, and the clock QEMU's and Bochs's virtual
//!    time runs the TSC against;
//! 2. CPUID leaf 0x15 (TSC to crystal ratio and the crystal frequency) or
//!    0x16 (base frequency), on the newer Intel CPUs whose platforms may
//!    gate the PIT off;
//! 3. else [`ASSUMED_HZ`]: the show then runs at the wrong pace, but every
//!    wait still ends.
//!
//! Under QEMU the TSC follows QEMU's virtual clock: host time, or one tick
//! per emulated instruction with `-icount shift=0`; the PIT follows the
//! same clock, so the rate measured is the one the guest sees either way.

use core::sync::atomic::{AtomicU64, AtomicU8, Ordering};

use protocol::{ClockSource, TscRate};

use crate::pit::{self, Stopwatch};

/// PIT ticks the calibration spans: 10 ms.
const CALIBRATION_PIT_TICKS: u64 = pit::TICKS_PER_SECOND / 100;
/// TSC cycles to wait for a PIT that does not count: the PIT ticks every
/// 0.84 us, so any TSC below 80 GHz sees it move in this many cycles.
const PIT_SILENCE_CYCLES: u64 = 1 << 16;
/// TSC cycles the whole calibration may take if the PIT stops counting
/// half way: 2^34 cycles are 10 s at 1.7 GHz.
const CALIBRATION_MAX_CYCLES: u64 = 1 << 34;
/// The rate taken when nothing measures it.
const ASSUMED_HZ: u64 = 1_000_000_000;

/// TSC cycles per second, once [`init`] has measured it.
static CYCLES_PER_SECOND: AtomicU64 = AtomicU64::new(ASSUMED_HZ);
/// Where that rate came from, as an index into `ClockSource::ALL`.
static SOURCE: AtomicU8 = AtomicU8::new(ClockSource::Assumed as u8);

/// Measures the TSC's rate. Takes about 10 ms with a PIT.
pub fn init() {
    let (rate, source) = match rate_from_pit() {
        Some(rate) => (rate, ClockSource::Pit),
        None => match rate_from_cpuid() {
            Some(rate) => (rate, ClockSource::Cpuid),
            None => (ASSUMED_HZ, ClockSource::Assumed),
        },
    };
    CYCLES_PER_SECOND.store(rate, Ordering::Relaxed);
    SOURCE.store(source as u8, Ordering::Relaxed);
}

/// The TSC's rate and how it was found, as `CLOCK` reports it.
pub fn rate() -> TscRate {
    let source = ClockSource::ALL[usize::from(SOURCE.load(Ordering::Relaxed))];
    TscRate { hz: cycles_per_second(), source, readings: protocol::ClockReadings::default() }
}

/// The time-stamp counter.
pub fn cycles() -> u64 {
    // SAFETY: RDTSC only reads the counter into registers; it touches no
    // memory. Every x86_64 CPU has it, and the kernel runs in ring 0, where
    // CR4.TSD cannot make it fault.
    unsafe { core::arch::x86_64::_rdtsc() }
}

/// TSC cycles per second.
pub fn cycles_per_second() -> u64 {
    CYCLES_PER_SECOND.load(Ordering::Relaxed)
}

/// TSC cycles in `micros` microseconds.
pub fn cycles_in_micros(micros: u64) -> u64 {
    // 2^64 / 10^6 cycles a second would be 18 THz: no overflow in u128.
    (u128::from(cycles_per_second()) * u128::from(micros) / 1_000_000) as u64
}

/// A moment after which a wait gives up.
#[derive(Clone, Copy)]
pub struct Deadline {
    at: u64,
}

impl Deadline {
    /// `micros` microseconds from now.
    pub fn after_micros(micros: u64) -> Self {
        Self::after_cycles(cycles_in_micros(micros))
    }

    /// `cycles` TSC cycles from now.
    pub fn after_cycles(cycles: u64) -> Self {
        Self { at: self::cycles().saturating_add(cycles) }
    }

    pub fn passed(self) -> bool {
        cycles() >= self.at
    }
}

/// Counts the TSC over [`CALIBRATION_PIT_TICKS`] of the PIT. `None` if the
/// PIT's count does not move (no PIT) or stops.
fn rate_from_pit() -> Option<u64> {
    let mut stopwatch = Stopwatch::start();
    let silence = Deadline::after_cycles(PIT_SILENCE_CYCLES);
    while stopwatch.elapsed_ticks() == 0 {
        if silence.passed() {
            return None;
        }
    }
    // Count from a tick edge, so the 10 ms are whole ticks on both clocks.
    let (ticks_at_start, cycles_at_start) = (stopwatch.elapsed_ticks(), cycles());
    let give_up = Deadline::after_cycles(CALIBRATION_MAX_CYCLES);
    loop {
        let ticks = stopwatch.elapsed_ticks() - ticks_at_start;
        if ticks >= CALIBRATION_PIT_TICKS {
            let spent = u128::from(cycles() - cycles_at_start);
            return u64::try_from(spent * u128::from(pit::TICKS_PER_SECOND) / u128::from(ticks)).ok();
        }
        if give_up.passed() {
            return None;
        }
    }
}

/// The TSC's rate as the CPU states it: leaf 0x15 (crystal frequency times
/// the TSC/crystal ratio), else leaf 0x16's base frequency, which these
/// CPUs run the TSC at.
fn rate_from_cpuid() -> Option<u64> {
    use core::arch::x86_64::__cpuid;
    let highest_leaf = __cpuid(0).eax;
    if highest_leaf >= 0x15 {
        let leaf = __cpuid(0x15);
        let (denominator, numerator, crystal_hz) = (leaf.eax, leaf.ebx, leaf.ecx);
        if denominator != 0 && numerator != 0 && crystal_hz != 0 {
            return Some(u64::from(crystal_hz) * u64::from(numerator) / u64::from(denominator));
        }
    }
    if highest_leaf >= 0x16 {
        let base_mhz = __cpuid(0x16).eax & 0xFFFF;
        if base_mhz != 0 {
            return Some(u64::from(base_mhz) * 1_000_000);
        }
    }
    None
}
