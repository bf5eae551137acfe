//! The I/O APICs, only as far as a storm of interrupts needs them: a
//! redirection entry that sends a vector, masked when that vector storms
//! (`idt.rs`), and, for the test-only `FAULT interruptstorm`
//! (`fault.rs`), one entry routed level-triggered and put back after.
//!
//! The kernel programs no I/O APIC otherwise: the firmware leaves their
//! entries masked, or, on some machines, one unmasked that a device then
//! raises, level-triggered, again after every end of interrupt until its
//! driver serves it. Each I/O APIC's registers are reached through an index
//! (IOREGSEL, offset 0x00) and a window (IOWIN, offset 0x10) in its page,
//! which the MADT places (`platform/acpi.rs`) and which is mapped uncacheable here;
//! register 1 gives the number of entries (bits 16-23, the last one's
//! index), and entry N is registers 0x10 + 2N (low half) and 0x11 + 2N
//! (high half) (Intel's 82093AA datasheet).

use alloc::vec::Vec;

use firmware_tables::IoApicEntry;
use protocol::{IoApicRefusal, MemoryType};
use spin::Once;
use x86_64::instructions::interrupts;
use x86_64::VirtAddr;

use crate::platform::{acpi, memory_map, paging};

const SELECT: u64 = 0x00;
const WINDOW: u64 = 0x10;
const VERSION: u32 = 0x01;
const FIRST_ENTRY: u32 = 0x10;
const REGISTERS_LEN: u64 = 0x20;
/// The boundary the registers start on: IOREGSEL and IOWIN are 16 bytes
/// apart, each on its own 16-byte boundary.
const REGISTERS_BOUNDARY: u64 = 0x10;
/// An entry's low half: its vector (bits 0-7), level-triggered (bit 15),
/// masked (bit 16); the high half's top byte is the destination APIC ID.
const VECTOR: u32 = 0xFF;
const LEVEL_TRIGGERED: u32 = 1 << 15;
const MASKED: u32 = 1 << 16;
const DESTINATION_SHIFT: u32 = 24;
/// The ISA IRQ the storm is raised on: the RTC's.
pub const RTC_IRQ: u8 = 8;

/// An I/O APIC: its mapped registers, the global system interrupt of its
/// pin 0, and how many pins it has.
struct IoApic {
    registers: VirtAddr,
    first_interrupt: u32,
    pins: u32,
}

impl IoApic {
    /// Reads register `index`. The index and the window go together: call
    /// with interrupts off (an interrupt handler that masks an entry uses
    /// the same pair).
    fn read(&self, index: u32) -> u32 {
        // SAFETY: `registers` is this I/O APIC's page, mapped uncacheable by
        // `init`; IOREGSEL and IOWIN are its 32-bit registers, and selecting
        // and reading a register changes nothing else.
        unsafe {
            paging::register(self.registers, SELECT).write(index);
            paging::register(self.registers, WINDOW).read()
        }
    }

    fn write(&self, index: u32, value: u32) {
        // SAFETY: as in `read`; writing a redirection entry routes or masks
        // an interrupt, and touches no memory.
        unsafe {
            paging::register(self.registers, SELECT).write(index);
            paging::register(self.registers, WINDOW).write(value);
        }
    }
}

static IO_APICS: Once<Vec<IoApic>> = Once::new();
/// The I/O APICs the MADTs named that were not used, and why.
static REFUSED: Once<Vec<(u64, IoApicRefusal)>> = Once::new();
/// The global system interrupt the RTC's IRQ reaches.
static RTC_INTERRUPT: Once<u32> = Once::new();

/// Finds the I/O APICs the ACPI tables under `rsdp` list and maps their
/// registers uncacheable. Each address is checked before anything is
/// mapped (`memory_map::device_registers`: on a 16-byte boundary, in no
/// RAM of the memory map), and what answers there before anything is
/// written (IOREGSEL must not read all ones) and before it is used (its
/// version register must give a version other than 0 and 0xFF); a
/// refused one is kept for [`refused`] to tell. Call once, after
/// `paging::init`.
pub fn init(rsdp: Option<u64>) {
    let found = rsdp.and_then(|rsdp| acpi::tables(rsdp).io_apics(RTC_IRQ));
    let (entries, rtc) = found.unwrap_or_default();
    RTC_INTERRUPT.call_once(|| rtc);
    let mut refused = Vec::new();
    let mut io_apics = Vec::new();
    for entry in entries {
        match IoApic::at(entry) {
            Ok(Some(io_apic)) => io_apics.push(io_apic),
            Ok(None) => {}
            Err(why) => refused.push((entry.address, why)),
        }
    }
    IO_APICS.call_once(|| io_apics);
    REFUSED.call_once(|| refused);
}

/// The I/O APICs the MADTs named that the kernel did not use, and why:
/// for a `LOG` frame each at boot.
pub fn refused() -> &'static [(u64, IoApicRefusal)] {
    REFUSED.get().map_or(&[], Vec::as_slice)
}

impl IoApic {
    /// The I/O APIC `entry` names, its registers mapped uncacheable; a
    /// refusal where the address or what answers there is wrong; `None`
    /// where the map does not reach the address or its page cannot be
    /// made uncacheable (nothing was written).
    fn at(entry: IoApicEntry) -> Result<Option<Self>, IoApicRefusal> {
        memory_map::device_registers(entry.address, REGISTERS_LEN, REGISTERS_BOUNDARY)?;
        // Not RAM, as the check above found: an uncacheable mapping of it
        // makes no Rust object or page table uncacheable.
        let Some(registers) = paging::physical(entry.address) else { return Ok(None) };
        if paging::set_memory_type(registers, REGISTERS_LEN, MemoryType::Uncacheable).is_err() {
            return Ok(None);
        }
        // SAFETY: `registers` is the block the MADT names, device memory
        // (or nothing) outside RAM, mapped uncacheable just above; IOREGSEL
        // is its 32-bit register at offset 0, and reading it changes
        // nothing. All ones is what a read where nothing answers gives.
        let select = unsafe { paging::register(registers, SELECT) }.read();
        if select == u32::MAX {
            return Err(IoApicRefusal::NothingThere);
        }
        let mut io_apic = IoApic { registers, first_interrupt: entry.first_interrupt, pins: 0 };
        let version = interrupts::without_interrupts(|| io_apic.read(VERSION));
        if matches!(version & 0xFF, 0 | 0xFF) {
            return Err(IoApicRefusal::NotAnIoApic { version });
        }
        io_apic.pins = (version >> 16 & 0xFF) + 1;
        Ok(Some(io_apic))
    }
}

/// Masks every unmasked entry that sends `vector`; the global system
/// interrupt of the first, if there was one. Safe to call from an
/// interrupt handler: the main flow touches the registers only with
/// interrupts off.
pub fn mask_vector(vector: u8) -> Option<u32> {
    let mut masked = None;
    for io_apic in IO_APICS.get()? {
        for pin in 0..io_apic.pins {
            let low = io_apic.read(FIRST_ENTRY + 2 * pin);
            if low & VECTOR == u32::from(vector) && low & MASKED == 0 {
                io_apic.write(FIRST_ENTRY + 2 * pin, low | MASKED);
                masked = masked.or(Some(io_apic.first_interrupt + pin));
            }
        }
    }
    masked
}

/// An entry as it was before [`route_rtc_level`] changed it.
pub struct Saved {
    io_apic: usize,
    pin: u32,
    low: u32,
    high: u32,
}

/// Routes the RTC's IRQ to `vector` on `apic_id`, level-triggered, active
/// high, unmasked: while its line is high, it comes again after every end
/// of interrupt. `None` where no I/O APIC takes that interrupt.
pub fn route_rtc_level(vector: u8, apic_id: u8) -> Option<Saved> {
    let interrupt = *RTC_INTERRUPT.get()?;
    let (index, io_apic) =
        IO_APICS.get()?.iter().enumerate().find(|(_, io_apic)| {
            (io_apic.first_interrupt..io_apic.first_interrupt + io_apic.pins).contains(&interrupt)
        })?;
    let pin = interrupt - io_apic.first_interrupt;
    interrupts::without_interrupts(|| {
        let saved = Saved {
            io_apic: index,
            pin,
            low: io_apic.read(FIRST_ENTRY + 2 * pin),
            high: io_apic.read(FIRST_ENTRY + 2 * pin + 1),
        };
        io_apic.write(FIRST_ENTRY + 2 * pin, MASKED);
        io_apic.write(FIRST_ENTRY + 2 * pin + 1, u32::from(apic_id) << DESTINATION_SHIFT);
        io_apic.write(FIRST_ENTRY + 2 * pin, u32::from(vector) | LEVEL_TRIGGERED);
        Some(saved)
    })
}

/// Puts back the entry [`route_rtc_level`] changed, as it was.
pub fn restore(saved: Saved) {
    let Some(io_apic) = IO_APICS.get().and_then(|io_apics| io_apics.get(saved.io_apic)) else { return };
    interrupts::without_interrupts(|| {
        io_apic.write(FIRST_ENTRY + 2 * saved.pin, saved.low | MASKED);
        io_apic.write(FIRST_ENTRY + 2 * saved.pin + 1, saved.high);
        io_apic.write(FIRST_ENTRY + 2 * saved.pin, saved.low);
    });
}
