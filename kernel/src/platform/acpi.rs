//! The ACPI tables, read only as far as the kernel needs them: where the
//! power management timer's port is (the FADT), where the HPET's
//! registers are (the HPET table), and where the I/O APICs are and which
//! of their pins an ISA IRQ reaches (the MADT).
//!
//! The bootloader hands over the RSDP's physical address: under UEFI from
//! the firmware's configuration table, under a BIOS found in the BIOS
//! area. From there the XSDT (or, before ACPI 2.0, the RSDT) lists every
//! other table by physical address. Each structure is checked (signature,
//! length, checksum) before anything in it is used, and only addresses a
//! checked table names are read, through the bootloader's map of physical
//! memory (`paging::read_physical`): a corrupt table is refused, not
//! followed; and a table is read only where the memory map says the
//! firmware keeps its own memory (reserved, ACPI, ACPI NVS:
//! `memory_map.rs`), never at an address a root table names in RAM or in
//! a device's registers, which reading can disturb. The layouts are the
//! ACPI specification's (6.5: "Root System
//! Description Pointer", "Fixed ACPI Description Table"; the IA-PC HPET
//! specification for the HPET table).

use alloc::vec;
use alloc::vec::Vec;

use crate::platform::{memory_map, paging};

/// The RSDP: its signature, the bytes its first checksum covers (ACPI
/// 1.0's structure), and the revision, RSDT, length and XSDT fields.
const RSDP_SIGNATURE: &[u8; 8] = b"RSD PTR ";
const RSDP_V1_LEN: usize = 20;
const RSDP_REVISION: usize = 15;
const RSDP_RSDT: usize = 16;
const RSDP_LENGTH: usize = 20;
const RSDP_XSDT: usize = 24;
const RSDP_V2_LEN: usize = 36;
/// Every table starts with a 36-byte header: signature, length, ... .
const HEADER_LEN: usize = 36;
const HEADER_LENGTH: usize = 4;
/// The longest table read: far more than a FADT (276 bytes), an HPET
/// table (56) or an XSDT with a few hundred entries.
const MAX_TABLE_LEN: usize = 64 * 1024;

/// FADT fields: PM_TMR_BLK (the timer's port, 32 bits), PM_TMR_LEN (4
/// where there is a timer), the flags (bit 8 TMR_VAL_EXT: the counter has
/// 32 bits, else 24; bit 20 HW_REDUCED_ACPI: no fixed hardware, no PM
/// timer), and X_PM_TMR_BLK, a generic address of 12 bytes.
const FADT_PM_TIMER_BLOCK: usize = 76;
const FADT_PM_TIMER_LEN: usize = 91;
const FADT_FLAGS: usize = 112;
const TIMER_VALUE_EXTENDED: u32 = 1 << 8;
const HARDWARE_REDUCED: u32 = 1 << 20;
const FADT_X_PM_TIMER_BLOCK: usize = 208;
/// The HPET table's event timer block address, a generic address.
const HPET_BASE: usize = 40;
/// A generic address structure: address space (0 memory, 1 system I/O),
/// then at byte 4 the 64-bit address.
const GAS_LEN: usize = 12;
const GAS_SYSTEM_MEMORY: u8 = 0;
const GAS_SYSTEM_IO: u8 = 1;
const GAS_ADDRESS: usize = 4;

/// The ACPI PM timer as the FADT describes it.
#[derive(Clone, Copy)]
pub struct PmTimerBlock {
    pub port: u16,
    /// Whether its counter has 32 bits (else 24).
    pub wide: bool,
}

/// The PM timer, if the FADT under `rsdp` describes one in I/O space.
pub fn pm_timer(rsdp: u64) -> Option<PmTimerBlock> {
    let fadt = table(rsdp, b"FACP")?;
    let flags = u32_at(&fadt, FADT_FLAGS)?;
    if flags & HARDWARE_REDUCED != 0 {
        return None;
    }
    let wide = flags & TIMER_VALUE_EXTENDED != 0;
    let extended = fadt.get(FADT_X_PM_TIMER_BLOCK..FADT_X_PM_TIMER_BLOCK + GAS_LEN);
    let port = match extended.map(|gas| (gas[0], u64_at(gas, GAS_ADDRESS))) {
        Some((GAS_SYSTEM_IO, Some(address))) if address != 0 => address,
        _ if fadt.get(FADT_PM_TIMER_LEN) == Some(&4) => u64::from(u32_at(&fadt, FADT_PM_TIMER_BLOCK)?),
        _ => return None,
    };
    Some(PmTimerBlock { port: u16::try_from(port).ok().filter(|&port| port != 0)?, wide })
}

/// The physical address of the HPET's registers, if the HPET table under
/// `rsdp` places them in memory.
pub fn hpet(rsdp: u64) -> Option<u64> {
    let table = table(rsdp, b"HPET")?;
    let gas = table.get(HPET_BASE..HPET_BASE + GAS_LEN)?;
    let address = u64_at(gas, GAS_ADDRESS)?;
    (gas[0] == GAS_SYSTEM_MEMORY && address != 0).then_some(address)
}

/// The MADT: after the header, the local APIC's address and flags (8
/// bytes), then entries of a type byte and a length byte each: type 1 an
/// I/O APIC (its address at byte 4, the first global system interrupt it
/// takes at byte 8), type 2 an interrupt source override (the ISA IRQ at
/// byte 3, the global system interrupt it reaches at byte 4).
const MADT_ENTRIES: usize = HEADER_LEN + 8;
const MADT_IO_APIC: u8 = 1;
const MADT_OVERRIDE: u8 = 2;

/// An I/O APIC as the MADT describes it.
#[derive(Clone, Copy)]
pub struct IoApicEntry {
    /// Its registers' physical address.
    pub address: u64,
    /// The global system interrupt its pin 0 takes.
    pub first_interrupt: u32,
}

/// The I/O APICs every MADT under `rsdp` lists, and the global system
/// interrupt ISA IRQ `irq` reaches (the IRQ's own number unless an
/// override says otherwise; the first MADT's override counts). A firmware
/// gives one MADT; each one there is is read all the same, so that every
/// I/O APIC address the tables hand over is checked (`ioapic::init`), one
/// added by QEMU's `-acpitable` (the tests' hostile table) among them.
pub fn io_apics(rsdp: u64, irq: u8) -> Option<(Vec<IoApicEntry>, u32)> {
    let madts = tables(rsdp, b"APIC")?;
    let mut io_apics = Vec::new();
    let mut interrupt = None;
    for madt in &madts {
        let mut at = MADT_ENTRIES;
        while let [kind, len, ..] = *madt.get(at..).unwrap_or_default() {
            let Some(entry) = madt.get(at..at + usize::from(len).max(2)) else { break };
            match (kind, u32_at(entry, 4)) {
                (MADT_IO_APIC, Some(address)) => {
                    if let Some(first_interrupt) = u32_at(entry, 8) {
                        io_apics.push(IoApicEntry { address: u64::from(address), first_interrupt });
                    }
                }
                (MADT_OVERRIDE, Some(to)) if entry.get(3) == Some(&irq) => {
                    interrupt.get_or_insert(to);
                }
                _ => {}
            }
            at += entry.len();
        }
    }
    (!madts.is_empty()).then(|| (io_apics, interrupt.unwrap_or(u32::from(irq))))
}

/// The first table with `signature` the root table under `rsdp` lists,
/// checked.
fn table(rsdp: u64, signature: &[u8; 4]) -> Option<Vec<u8>> {
    tables(rsdp, signature)?.into_iter().next()
}

/// Every table with `signature` the root table under `rsdp` lists that
/// checks, in its order; `None` without a root table.
fn tables(rsdp: u64, signature: &[u8; 4]) -> Option<Vec<Vec<u8>>> {
    let (root, entry_len) = root_table(rsdp)?;
    let entries = root.get(HEADER_LEN..)?.chunks_exact(entry_len).filter_map(entry_address);
    let is_it = |&address: &u64| {
        let mut found = [0; 4];
        memory_map::holds_firmware_tables(address, HEADER_LEN as u64)
            && paging::read_physical(address, &mut found).is_some()
            && found == *signature
    };
    Some(entries.filter(is_it).filter_map(read_table).collect())
}

/// The XSDT (8-byte entries) or, where there is none, the RSDT (4-byte
/// entries) the RSDP at `rsdp` points to, checked.
fn root_table(rsdp: u64) -> Option<(Vec<u8>, usize)> {
    let mut pointer = [0; RSDP_V2_LEN];
    paging::read_physical(rsdp, &mut pointer[..RSDP_V1_LEN])?;
    if !pointer.starts_with(RSDP_SIGNATURE) || !sums_to_zero(&pointer[..RSDP_V1_LEN]) {
        return None;
    }
    if pointer[RSDP_REVISION] >= 2 && paging::read_physical(rsdp, &mut pointer).is_some() {
        let length = u32_at(&pointer, RSDP_LENGTH)? as usize;
        let xsdt = u64_at(&pointer, RSDP_XSDT)?;
        if length >= RSDP_V2_LEN && sums_to_zero(&pointer) && xsdt != 0 {
            if let Some(table) = read_table(xsdt).filter(|table| table.starts_with(b"XSDT")) {
                return Some((table, 8));
            }
        }
    }
    let rsdt = read_table(u64::from(u32_at(&pointer, RSDP_RSDT)?)).filter(|table| table.starts_with(b"RSDT"))?;
    Some((rsdt, 4))
}

/// The table at physical address `address`, whole, if it lies in the
/// firmware's memory, its header's length is sane and its bytes sum to
/// zero.
fn read_table(address: u64) -> Option<Vec<u8>> {
    if !memory_map::holds_firmware_tables(address, HEADER_LEN as u64) {
        return None;
    }
    let mut header = [0; HEADER_LEN];
    paging::read_physical(address, &mut header)?;
    let length = u32_at(&header, HEADER_LENGTH)? as usize;
    if !(HEADER_LEN..=MAX_TABLE_LEN).contains(&length) || !memory_map::holds_firmware_tables(address, length as u64) {
        return None;
    }
    let mut table = vec![0; length];
    paging::read_physical(address, &mut table)?;
    sums_to_zero(&table).then_some(table)
}

/// A root table entry: a 4- or 8-byte little-endian address.
fn entry_address(entry: &[u8]) -> Option<u64> {
    match entry.len() {
        4 => u32_at(entry, 0).map(u64::from),
        _ => u64_at(entry, 0),
    }
}

fn sums_to_zero(bytes: &[u8]) -> bool {
    bytes.iter().fold(0u8, |sum, &byte| sum.wrapping_add(byte)) == 0
}

fn u32_at(bytes: &[u8], at: usize) -> Option<u32> {
    Some(u32::from_le_bytes(bytes.get(at..at + 4)?.try_into().ok()?))
}

fn u64_at(bytes: &[u8], at: usize) -> Option<u64> {
    Some(u64::from_le_bytes(bytes.get(at..at + 8)?.try_into().ok()?))
}
