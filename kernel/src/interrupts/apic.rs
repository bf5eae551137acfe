//! The local APIC, only as far as an interrupt the kernel did not ask for
//! needs it: whether it has a vector in service (then it awaits an end of
//! interrupt, and blocks every vector of that priority class and below
//! until it gets one), the end of interrupt itself, an entry of its local
//! vector table masked when its vector storms, its ID (where an I/O APIC
//! sends to), and a self-IPI, how `FAULT strayinterrupt` raises a stray
//! vector the way a device would.
//!
//! The kernel programs nothing here. The firmware leaves the local APIC
//! enabled (IA32_APIC_BASE bit 11) with its LINT0 passing the 8259's
//! interrupts on, and may leave LVT entries live (thermal, CMCI, error,
//! performance counters) or the spurious vector (0xFF on most firmware)
//! raised: those are the stray interrupts `idt.rs` survives. Its
//! registers are memory-mapped at the base IA32_APIC_BASE names (xAPIC
//! mode), mapped uncacheable here, or MSRs from 0x800 where the firmware
//! switched it to x2APIC mode (bit 10).

use core::arch::x86_64::__cpuid;

use protocol::MemoryType;
use spin::Once;
use x86_64::registers::model_specific::Msr;
use x86_64::VirtAddr;

use crate::platform::paging;

/// CPUID leaf 1, EDX bit 9: the CPU has a local APIC.
const HAS_APIC: u32 = 1 << 9;
const IA32_APIC_BASE: u32 = 0x1B;
const GLOBAL_ENABLE: u64 = 1 << 11;
const X2APIC_MODE: u64 = 1 << 10;
/// Bits 12 to 51 of IA32_APIC_BASE: the registers' physical base.
const BASE_ADDRESS: u64 = 0x000F_FFFF_FFFF_F000;
/// The registers' page.
const REGISTERS_LEN: u64 = 0x1000;
/// x2APIC mode: register offset `o` is MSR `0x800 + o / 16`.
const X2APIC_MSRS: u32 = 0x800;

/// Register offsets (xAPIC): end of interrupt; spurious-interrupt vector
/// (bit 8: the APIC is software-enabled); the eight in-service registers,
/// 32 vectors each, 16 bytes apart; the interrupt command register, low
/// and high halves.
const EOI: u32 = 0xB0;
const SPURIOUS_VECTOR: u32 = 0xF0;
const SOFTWARE_ENABLE: u32 = 1 << 8;
const IN_SERVICE: u32 = 0x100;
const COMMAND_LOW: u32 = 0x300;
const COMMAND_HIGH: u32 = 0x310;
/// The local APIC's ID (bits 24-31 in xAPIC mode, the whole register in
/// x2APIC mode) and version (bits 16-23: the index of the last entry of
/// the local vector table).
const ID: u32 = 0x20;
const VERSION: u32 = 0x30;
/// The local vector table: timer, thermal sensor, performance counters,
/// LINT0, LINT1, error; and CMCI where the version counts a seventh entry.
/// Each entry: its vector (bits 0-7), its delivery mode (bits 8-10, 0 for
/// fixed, the only mode whose vector is the one delivered), masked (bit 16).
const LOCAL_VECTOR_TABLE: [u32; 6] = [0x320, 0x330, 0x340, 0x350, 0x360, 0x370];
const CMCI: u32 = 0x2F0;
const CMCI_ENTRY: u32 = 6;
const ENTRY_VECTOR: u32 = 0xFF;
const DELIVERY_MODE: u32 = 0b111 << 8;
const ENTRY_MASKED: u32 = 1 << 16;
/// Interrupt command: fixed delivery, edge, level asserted (bit 14, which
/// the manual asks for in every mode but INIT de-assert), to the sender
/// itself (the "self" destination shorthand, bits 18-19 = 01), the vector
/// in bits 0-7.
const SELF_FIXED: u32 = (1 << 18) | (1 << 14);

/// How the local APIC's registers are reached.
#[derive(Clone, Copy)]
enum Registers {
    /// xAPIC: the registers' page, mapped uncacheable.
    Memory(VirtAddr),
    /// x2APIC: MSRs.
    Msrs,
}

static REGISTERS: Once<Option<Registers>> = Once::new();

/// Finds the local APIC (none on a CPU without one or where the firmware
/// disabled it) and maps its registers uncacheable. Call once, after
/// `paging::init`.
pub fn init() {
    REGISTERS.call_once(|| {
        if __cpuid(1).edx & HAS_APIC == 0 {
            return None;
        }
        // SAFETY: reading IA32_APIC_BASE, present with the APIC, changes
        // nothing.
        let base = unsafe { Msr::new(IA32_APIC_BASE).read() };
        if base & GLOBAL_ENABLE == 0 {
            return None;
        }
        if base & X2APIC_MODE != 0 {
            return Some(Registers::Msrs);
        }
        let registers = paging::physical(base & BASE_ADDRESS)?;
        paging::set_memory_type(registers, REGISTERS_LEN, MemoryType::Uncacheable).ok()?;
        Some(Registers::Memory(registers))
    });
}

fn registers() -> Option<Registers> {
    REGISTERS.get().copied().flatten()
}

fn read(registers: Registers, offset: u32) -> u32 {
    match registers {
        // SAFETY: the local APIC's register page, mapped uncacheable by
        // `init`; reading these registers has no side effects.
        Registers::Memory(base) => unsafe { paging::register(base, u64::from(offset)).read() },
        // SAFETY: in x2APIC mode these MSRs are the same registers.
        Registers::Msrs => unsafe { Msr::new(X2APIC_MSRS + offset / 16).read() as u32 },
    }
}

fn write(registers: Registers, offset: u32, value: u32) {
    match registers {
        // SAFETY: as in `read`; the registers written (EOI, the command
        // register, an entry of the local vector table) end, send or mask
        // an interrupt, and touch no memory.
        Registers::Memory(base) => unsafe { paging::register(base, u64::from(offset)).write(value) },
        // SAFETY: as above, through the x2APIC MSRs.
        Registers::Msrs => unsafe { Msr::new(X2APIC_MSRS + offset / 16).write(u64::from(value)) },
    }
}

/// Ends `vector`'s interrupt if the local APIC has it in service, and
/// says whether it did. (An interrupt it delivered as ExtINT, from the
/// 8259, or as its spurious vector, is never in service there.)
pub fn end_if_in_service(vector: u8) -> bool {
    let Some(registers) = registers() else { return false };
    let in_service = read(registers, IN_SERVICE + 0x10 * u32::from(vector / 32)) & (1 << (vector % 32)) != 0;
    if in_service {
        write(registers, EOI, 0);
    }
    in_service
}

/// This CPU's local APIC ID as an I/O APIC's destination field takes it
/// (its low 8 bits); `None` with no enabled local APIC.
pub fn id() -> Option<u8> {
    let registers = registers()?;
    let id = read(registers, ID);
    Some(match registers {
        Registers::Memory(_) => (id >> 24) as u8,
        Registers::Msrs => id as u8,
    })
}

/// Masks every unmasked entry of the local vector table that delivers
/// `vector`; whether there was one. Called from an interrupt handler.
pub fn mask_vector(vector: u8) -> bool {
    let Some(registers) = registers() else { return false };
    let has_cmci = read(registers, VERSION) >> 16 & 0xFF >= CMCI_ENTRY;
    let entries = LOCAL_VECTOR_TABLE.into_iter().chain(has_cmci.then_some(CMCI));
    let mut masked = false;
    for entry in entries {
        let value = read(registers, entry);
        if value & ENTRY_VECTOR == u32::from(vector) && value & DELIVERY_MODE == 0 && value & ENTRY_MASKED == 0 {
            write(registers, entry, value | ENTRY_MASKED);
            masked = true;
        }
    }
    masked
}

/// Sends `vector` to this CPU through the local APIC, as a device's
/// interrupt arrives; `false` if there is no enabled local APIC to send it.
pub fn send_to_self(vector: u8) -> bool {
    let Some(registers) = registers() else { return false };
    if read(registers, SPURIOUS_VECTOR) & SOFTWARE_ENABLE == 0 {
        return false;
    }
    match registers {
        Registers::Memory(_) => {
            write(registers, COMMAND_HIGH, 0);
            write(registers, COMMAND_LOW, SELF_FIXED | u32::from(vector));
        }
        // SAFETY: in x2APIC mode the command register is one 64-bit MSR;
        // the write sends the interrupt and touches no memory.
        Registers::Msrs => unsafe {
            Msr::new(X2APIC_MSRS + COMMAND_LOW / 16).write(u64::from(SELF_FIXED | u32::from(vector)))
        },
    }
    true
}
