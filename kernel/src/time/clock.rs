//! Time: the CPU's time-stamp counter, its rate measured at boot.
//! Every wait in the kernel ends by this clock ([`Deadline`]), never after
//! a count of port reads: what a port read costs differs from machine to
//! machine by orders of magnitude (a few nanoseconds of virtual time under
//! an emulator such as Bochs, about a microsecond on a real ISA bus).
//!
//! The rate is measured against every timer the machine has (`timers.rs`):
//! the PIT, the ACPI PM timer (its port from the FADT, through the RSDP the
//! bootloader hands over) and the HPET (from its ACPI table). The first of
//! them in that order that gives a rate is the clock's; the others, and
//! what CPUID leaf 0x15 or 0x16 states, are kept as cross-checks for
//! `CLOCK`. Only where no timer measures it is CPUID's figure taken, and
//! only where the CPU states none is [`ASSUMED_HZ`]: the show then runs at
//! the wrong pace, but every wait still ends. Many new PCs are
//! "legacy-free": the 8254 gated off, or reachable only through the HPET.
//!
//! Each measurement counts TSC cycles over [`WINDOW_MICROS`] of the
//! timer, from one reading of it to another; [`MEASUREMENTS`] are made and
//! the median kept, so one disturbed by a system management interrupt
//! (SMI: the firmware takes the CPU away, for tens of microseconds or
//! more, invisibly) does not decide the rate. Each reading is guarded
//! too: the TSC read just before and just after it must be at most
//! [`SMI_GUARD_CYCLES`] apart, else it is read again, so the moment it
//! stands for is known (Linux guards its calibration the same way).
//!
//! The test-only `CLOCK SOURCE [stalled]` ([`force`]) measures against one
//! timer alone and makes it the clock: the harness proves each source is
//! the one named and keeps the show's pace, and, with the kernel stalling
//! itself as an SMI would ([`Stalls`]), that the guard and the median each
//! hold.
//!
//! Under QEMU the TSC follows the host's (or, with `-icount shift=0`, one
//! tick per emulated instruction); the timers follow QEMU's virtual clock,
//! so the rate measured is the one the guest sees either way.

use core::arch::x86_64::__cpuid;
use core::sync::atomic::{compiler_fence, AtomicU64, AtomicU8, Ordering};

use firmware_tables::PmTimerRefusal;
use protocol::{ClockReadings, ClockSource, HpetRefusal, TscRate};
use spin::Once;

use crate::time::pit::Stopwatch;
use crate::time::timers::{Hpet, PmTimer, Timer};

/// Timer time each measurement spans: 10 ms.
const WINDOW_MICROS: u64 = 10_000;
/// Measurements per timer; the median is kept.
const MEASUREMENTS: usize = 5;
/// Longest gap between the TSC reads around one reading of a timer (a few
/// port or device accesses, well under 10 us on any PC): a longer one had
/// an SMI, or a host's scheduler under an emulator, inside it.
const SMI_GUARD_CYCLES: u64 = 50_000;
/// Readings tried before a measurement is given up.
const READ_TRIES: u32 = 16;
/// TSC cycles to wait for a timer that does not count: its ticks are at
/// most a microsecond apart (the PIT's, the slowest, 0.84 us), so any TSC
/// below 20 THz sees it move in 2^24 cycles, and an SMI is far shorter.
const SILENCE_CYCLES: u64 = 1 << 24;
/// TSC cycles one measurement may take if the timer stops counting half
/// way: 2^32 cycles are 1 s at 4 GHz.
const MEASUREMENT_MAX_CYCLES: u64 = 1 << 32;
/// The rate taken when nothing measures or states it.
const ASSUMED_HZ: u64 = 1_000_000_000;
/// `CLOCK SOURCE stalled`: how long the kernel stalls inside a reading (so
/// that a reading kept, its moment taken half way, moves its measurement
/// by a tenth of [`WINDOW_MICROS`]), and inside a window (longer than the
/// PIT's 55 ms wrap, which the stopwatch then misses); and how many
/// measurements, of the first attempts, stall in a reading (the rest of
/// [`MEASUREMENTS`] stall in their window).
const STALL_IN_READING_MICROS: u64 = 2_000;
const STALL_IN_WINDOW_MICROS: u64 = 60_000;
const STALLED_READINGS: usize = 3;

/// TSC cycles per second, once [`init`] has measured it.
static CYCLES_PER_SECOND: AtomicU64 = AtomicU64::new(ASSUMED_HZ);
/// Where that rate came from, as an index into `ClockSource::ALL`.
static SOURCE: AtomicU8 = AtomicU8::new(ClockSource::Assumed as u8);
/// What every source gave.
static READINGS: Once<ClockReadings> = Once::new();
/// The ACPI root pointer `init` was given, for [`force`].
static RSDP: Once<Option<u64>> = Once::new();
/// The HPET the ACPI tables named and the kernel did not use, and why.
static HPET_REFUSED: Once<(u64, HpetRefusal)> = Once::new();
/// The PM timer port the FADT named and the kernel did not use.
static PM_TIMER_REFUSED: Once<PmTimerRefusal> = Once::new();

/// Measures the TSC's rate against every timer there is, `rsdp` (the
/// bootloader's ACPI root pointer) leading to those the ACPI tables
/// describe. Takes about 50 ms per timer. Call once, after `paging::init`
/// (the HPET's registers and the tables are reached through it).
pub fn init(rsdp: Option<u64>) {
    RSDP.call_once(|| rsdp);
    let readings = ClockReadings {
        pit: rate_of(ClockSource::Pit, Stalls::None),
        pm_timer: rate_of(ClockSource::PmTimer, Stalls::None),
        hpet: rate_of(ClockSource::Hpet, Stalls::None),
        cpuid: rate_from_cpuid(),
    };
    let (rate, source) = [
        (readings.pit, ClockSource::Pit),
        (readings.pm_timer, ClockSource::PmTimer),
        (readings.hpet, ClockSource::Hpet),
        (readings.cpuid, ClockSource::Cpuid),
    ]
    .into_iter()
    .find_map(|(rate, source)| Some((rate?, source)))
    .unwrap_or((ASSUMED_HZ, ClockSource::Assumed));
    CYCLES_PER_SECOND.store(rate, Ordering::Relaxed);
    SOURCE.store(source as u8, Ordering::Relaxed);
    READINGS.call_once(|| readings);
}

/// The TSC's rate against `source` alone (a timer: the PIT, the PM timer
/// or the HPET), the median of [`MEASUREMENTS`]; `None` if the machine has
/// no such timer, or it does not count.
fn rate_of(source: ClockSource, stalls: Stalls) -> Option<u64> {
    let rsdp = RSDP.get().copied().flatten();
    match source {
        ClockSource::Pit => rate_against(Stopwatch::start(), stalls),
        ClockSource::PmTimer => rate_or_refusal(rsdp.and_then(PmTimer::find)?, &PM_TIMER_REFUSED, stalls),
        ClockSource::Hpet => rate_or_refusal(rsdp.and_then(Hpet::find)?, &HPET_REFUSED, stalls),
        ClockSource::Cpuid | ClockSource::Assumed => None,
    }
}

/// The TSC's rate against a timer the ACPI tables named, or, where the
/// kernel refused it, `None` with the first refusal kept in `refused`.
fn rate_or_refusal<T: Timer, R>(found: Result<T, R>, refused: &Once<R>, stalls: Stalls) -> Option<u64> {
    match found {
        Ok(timer) => rate_against(timer, stalls),
        Err(why) => {
            refused.call_once(|| why);
            None
        }
    }
}

/// Where the HPET the ACPI tables named is, and why the kernel did not
/// use it, if it did not: for a `LOG` frame at boot.
pub fn hpet_refused() -> Option<(u64, HpetRefusal)> {
    HPET_REFUSED.get().copied()
}

/// The port the FADT placed the PM timer at, if the kernel did not use it
/// there: for a `LOG` frame at boot.
pub fn pm_timer_refused() -> Option<u16> {
    PM_TIMER_REFUSED.get().map(|refused| refused.port)
}

/// Test only (`CLOCK SOURCE [stalled]`, on QEMU): measures the TSC against
/// `source` alone, with the kernel's own [`Stalls`] if `stalled`, and makes
/// that rate and source the clock's; what `CLOCK` then says, or `None` if
/// no such timer counts (the clock is left as it was).
pub fn force(source: ClockSource, stalled: bool) -> Option<TscRate> {
    let hz = rate_of(source, if stalled { Stalls::Planted } else { Stalls::None })?;
    CYCLES_PER_SECOND.store(hz, Ordering::Relaxed);
    SOURCE.store(source as u8, Ordering::Relaxed);
    Some(rate())
}

/// The TSC's rate, how it was found and what every source gave, as
/// `CLOCK` reports it.
pub fn rate() -> TscRate {
    let source = ClockSource::ALL[usize::from(SOURCE.load(Ordering::Relaxed))];
    TscRate { hz: cycles_per_second(), source, readings: READINGS.get().copied().unwrap_or_default() }
}

/// The time-stamp counter.
pub fn cycles() -> u64 {
    // SAFETY: RDTSC only reads the counter into registers; it touches no
    // memory. Every x86_64 CPU has it, and the kernel runs in ring 0, where
    // CR4.TSD cannot make it fault.
    unsafe { core::arch::x86_64::_rdtsc() }
}

/// Runs `work` and returns its result with the time-stamp counter cycles it
/// took (`BENCH` and `SHOW` both time their draws with it). RDTSC is not
/// serializing: the fences only keep the compiler from moving `work`
/// across the reads, which is enough for whole draws of thousands of
/// cycles. Always inlined, so that what is timed is compiled as part of
/// its caller wherever this helper lives: moved here from `bench.rs`
/// without it, the draws it times compiled differently and `cargo xtask
/// kbench` counted from 1.0% fewer to 1.25% more instructions.
#[inline(always)]
pub fn timed<R>(work: impl FnOnce() -> R) -> (R, u64) {
    let start = cycles();
    compiler_fence(Ordering::SeqCst);
    let result = work();
    compiler_fence(Ordering::SeqCst);
    (result, cycles().wrapping_sub(start))
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

/// Stalls a measurement makes in itself: none, or (`CLOCK SOURCE stalled`)
/// those an SMI would make, to show each defence holds: in the first
/// reading of the first [`STALLED_READINGS`] attempts (which the guard
/// must throw away), and inside the window of the attempts after them (a
/// stall longer than the PIT's wrap, which no guard sees: the median must
/// leave those measurements out).
#[derive(Clone, Copy)]
enum Stalls {
    None,
    Planted,
}

/// Where one attempt at a measurement stalls.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Stall {
    None,
    InFirstReading,
    InWindow,
}

impl Stalls {
    fn of_attempt(self, attempt: usize) -> Stall {
        match self {
            Stalls::None => Stall::None,
            Stalls::Planted if attempt < STALLED_READINGS => Stall::InFirstReading,
            Stalls::Planted if attempt < MEASUREMENTS => Stall::InWindow,
            Stalls::Planted => Stall::None,
        }
    }
}

/// Takes the CPU for `micros`, interrupts off, as an SMI does.
fn stall(micros: u64) {
    x86_64::instructions::interrupts::without_interrupts(|| {
        let end = Deadline::after_micros(micros);
        while !end.passed() {
            core::hint::spin_loop();
        }
    });
}

/// The median of up to [`MEASUREMENTS`] measurements of the TSC against
/// `timer`; `None` if the timer does not count (no such timer: an absent
/// PIT reads 0xFF for ever) or no measurement succeeds.
fn rate_against(mut timer: impl Timer, stalls: Stalls) -> Option<u64> {
    let start = timer.ticks();
    let silence = Deadline::after_cycles(SILENCE_CYCLES);
    while timer.ticks() == start {
        if silence.passed() {
            return None;
        }
    }
    let mut rates = [0; MEASUREMENTS];
    let mut measured = 0;
    for attempt in 0..2 * MEASUREMENTS {
        if measured == MEASUREMENTS {
            break;
        }
        if let Some(rate) = measure(&mut timer, stalls.of_attempt(attempt)) {
            rates[measured] = rate;
            measured += 1;
        }
    }
    let rates = &mut rates[..measured];
    rates.sort_unstable();
    rates.get(measured / 2).copied()
}

/// TSC cycles per second over [`WINDOW_MICROS`] of `timer`, from one
/// guarded reading to another, stalling where `stall` says.
fn measure(timer: &mut impl Timer, stall_at: Stall) -> Option<u64> {
    let window = timer.hz() * WINDOW_MICROS / 1_000_000;
    let (start_cycles, start_ticks) = guarded_reading(timer, stall_at == Stall::InFirstReading)?;
    if stall_at == Stall::InWindow {
        stall(STALL_IN_WINDOW_MICROS);
    }
    let give_up = Deadline::after_cycles(MEASUREMENT_MAX_CYCLES);
    while timer.ticks() - start_ticks < window {
        if give_up.passed() {
            return None;
        }
    }
    let (end_cycles, end_ticks) = guarded_reading(timer, false)?;
    let spent = u128::from(end_cycles.checked_sub(start_cycles)?);
    u64::try_from(spent * u128::from(timer.hz()) / u128::from(end_ticks - start_ticks)).ok()
}

/// The timer's ticks and the TSC at the moment it was read (the middle of
/// the two TSC reads around it), from the first of [`READ_TRIES`]
/// readings that took at most [`SMI_GUARD_CYCLES`]; `stalled`, the first
/// try stalls after the timer's read.
fn guarded_reading(timer: &mut impl Timer, stalled: bool) -> Option<(u64, u64)> {
    (0..READ_TRIES).find_map(|try_number| {
        let before = cycles();
        let ticks = timer.ticks();
        if stalled && try_number == 0 {
            stall(STALL_IN_READING_MICROS);
        }
        let after = cycles();
        let took = after.checked_sub(before)?;
        (took <= SMI_GUARD_CYCLES).then_some((before + took / 2, ticks))
    })
}

/// The TSC's rate as the CPU states it: leaf 0x15 (crystal frequency times
/// the TSC/crystal ratio), else leaf 0x16's base frequency, which these
/// CPUs run the TSC at. A statement, not a measurement: some CPUs leave
/// the crystal's frequency out, and the base frequency is the TSC's only
/// on the CPUs that say so; AMD's have neither leaf.
fn rate_from_cpuid() -> Option<u64> {
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
