//! The timers `clock` measures the TSC's rate against, each counting at a
//! rate it states: the PIT (`pit.rs`), the ACPI power management timer,
//! and the HPET's main counter. Each reads as a count of its ticks since
//! it was started, which stays right as long as it is read more often
//! than its counter wraps (the PIT every 55 ms, the PM timer's 24 bits
//! every 4.7 s, the HPET's low 32 bits every 7 minutes at 10 MHz).

use firmware_tables::{PmTimerBlock, PmTimerRefusal};
use protocol::{HpetRefusal, MemoryType};
use volatile::VolatilePtr;

use crate::platform::port::{self, IoPort};
use crate::platform::{acpi, memory_map, paging};
use crate::time::pit::{self, Stopwatch};

/// A timer that counts at a known rate.
pub trait Timer {
    /// Its ticks per second.
    fn hz(&self) -> u64;
    /// Its ticks since it was started.
    fn ticks(&mut self) -> u64;
}

impl Timer for Stopwatch {
    fn hz(&self) -> u64 {
        pit::TICKS_PER_SECOND
    }

    fn ticks(&mut self) -> u64 {
        self.elapsed_ticks()
    }
}

/// The ACPI PM timer: 3,579,545 ticks a second (the specification's
/// figure: the NTSC colour burst's 3.579545 MHz), counting up, 24 or 32
/// bits wide.
pub struct PmTimer {
    port: IoPort<u32>,
    mask: u32,
    last: u32,
    elapsed: u64,
}

const PM_TIMER_HZ: u64 = 3_579_545;

impl PmTimer {
    /// The PM timer the ACPI tables under `rsdp` describe, started;
    /// `None` with none, the port refused (and nothing read there) where
    /// it is a fixed device's (`firmware_tables::Tables::pm_timer`).
    pub fn find(rsdp: u64) -> Option<Result<Self, PmTimerRefusal>> {
        Some(acpi::tables(rsdp).pm_timer()?.map(|PmTimerBlock { port, wide }| {
            let port = port::acpi_pm_timer(port);
            let mask = if wide { u32::MAX } else { 0x00FF_FFFF };
            Self { port, mask, last: port.read() & mask, elapsed: 0 }
        }))
    }
}

impl Timer for PmTimer {
    fn hz(&self) -> u64 {
        PM_TIMER_HZ
    }

    fn ticks(&mut self) -> u64 {
        let count = self.port.read() & self.mask;
        self.elapsed += u64::from(count.wrapping_sub(self.last) & self.mask);
        self.last = count;
        self.elapsed
    }
}

/// The HPET's main counter, counting up at the rate its capabilities
/// register states (a period in femtoseconds), read by its low 32 bits.
pub struct Hpet {
    counter: VolatilePtr<'static, u32>,
    hz: u64,
    last: u32,
    elapsed: u64,
}

/// Register offsets (IA-PC HPET specification): the capabilities' lower
/// half (bits 0-7 the revision, never 0), their upper half (the counter's
/// period in femtoseconds), the general configuration (bit 0: the main
/// counter runs), the main counter.
const HPET_CAPABILITIES: u64 = 0x00;
const HPET_REVISION: u32 = 0xFF;
const HPET_PERIOD: u64 = 0x04;
const HPET_CONFIGURATION: u64 = 0x10;
const HPET_ENABLE: u32 = 1;
const HPET_COUNTER: u64 = 0xF0;
/// The registers' extent, and the boundary the block starts on: 1 KiB.
const HPET_REGISTERS_LEN: u64 = 0x400;
/// The specification's longest period, 100 ns (10 MHz, the slowest), and
/// the shortest Linux takes, 100 ps (10 GHz).
const HPET_MAX_PERIOD_FS: u32 = 100_000_000;
const HPET_MIN_PERIOD_FS: u32 = 100_000;
const FEMTOSECONDS_PER_SECOND: u64 = 1_000_000_000_000_000;

impl Hpet {
    /// The HPET the ACPI tables under `rsdp` describe, its registers mapped
    /// uncacheable and its main counter running (started here if the
    /// firmware left it stopped; no timer of it is armed, so nothing
    /// interrupts); `None` with no HPET table. A table's address is checked
    /// before anything is mapped (on a 1 KiB boundary, in no RAM of the
    /// memory map: a wrong one could have a RAM page made uncacheable and
    /// written), and what answers there before anything is written (a
    /// revision, a period of 100 ps to 100 ns); a refusal says why.
    pub fn find(rsdp: u64) -> Option<Result<Self, (u64, HpetRefusal)>> {
        let address = acpi::tables(rsdp).hpet()?;
        Some(Self::at(address).map_err(|why| (address, why)))
    }

    fn at(address: u64) -> Result<Self, HpetRefusal> {
        memory_map::device_registers(address, HPET_REGISTERS_LEN, HPET_REGISTERS_LEN)?;
        // Not RAM, as the checks above found: an uncacheable mapping of it
        // makes no Rust object or page table uncacheable. (Where the map
        // does not reach it, there is nothing to use.)
        let not_there = HpetRefusal::NotAnHpet { capabilities: u32::MAX };
        let registers = paging::physical(address).ok_or(not_there)?;
        paging::set_memory_type(registers, HPET_REGISTERS_LEN, MemoryType::Uncacheable).map_err(|_| not_there)?;
        // SAFETY (of each `paging::register`): `registers` is the block the
        // table names, device memory (or nothing) outside RAM, mapped
        // uncacheable just above; the offsets are 32-bit registers inside
        // its 1 KiB, and reading these two changes nothing.
        let capabilities = unsafe { paging::register(registers, HPET_CAPABILITIES) }.read();
        if capabilities & HPET_REVISION == 0 || capabilities == u32::MAX {
            return Err(HpetRefusal::NotAnHpet { capabilities });
        }
        let period = unsafe { paging::register(registers, HPET_PERIOD) }.read();
        if !(HPET_MIN_PERIOD_FS..=HPET_MAX_PERIOD_FS).contains(&period) {
            return Err(HpetRefusal::Period { femtoseconds: period });
        }
        let period = u64::from(period);
        // SAFETY: as above; an HPET answered, so this is its configuration
        // register, whose bit 0 starts its counter.
        let configuration = unsafe { paging::register(registers, HPET_CONFIGURATION) };
        let config = configuration.read();
        if config & HPET_ENABLE == 0 {
            configuration.write(config | HPET_ENABLE);
        }
        // SAFETY: as above, its main counter.
        let counter = unsafe { paging::register(registers, HPET_COUNTER) };
        Ok(Self { counter, hz: FEMTOSECONDS_PER_SECOND / period, last: counter.read(), elapsed: 0 })
    }
}

impl Timer for Hpet {
    fn hz(&self) -> u64 {
        self.hz
    }

    fn ticks(&mut self) -> u64 {
        let count = self.counter.read();
        self.elapsed += u64::from(count.wrapping_sub(self.last));
        self.last = count;
        self.elapsed
    }
}
