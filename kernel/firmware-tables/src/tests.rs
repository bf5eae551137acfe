//! Every decision on a machine of the tests' own: tables placed where a
//! firmware would, and where a wrong or hostile one might, with every read
//! recorded, so that a test sees not only what is refused but that
//! nothing was read where it must not be.

use alloc::vec;
use alloc::vec::Vec;
use core::cell::RefCell;

use crate::{Class, IoApicEntry, MemoryMap, Misplaced, PhysicalMemory, PmTimerBlock, PmTimerRefusal, Region, Tables};

/// Where the tests' firmware keeps things: the RSDP in the BIOS area, the
/// tables in ACPI memory, more in a reserved region, runtime services' data
/// after them, a PCI configuration window, the chipset's TPM window, and
/// the I/O APIC's registers as memory-mapped I/O.
const RSDP: u64 = 0xE_0000;
const ACPI: (u64, u64) = (0x7F0_0000, 0x7F1_0000);
const RESERVED: (u64, u64) = (0x7F1_0000, 0x7F2_0000);
const RUNTIME_DATA: (u64, u64) = (0x7F2_0000, 0x7F3_0000);
const PCI_WINDOW: (u64, u64) = (0xB000_0000, 0xC000_0000);
const TPM: (u64, u64) = (0xFED4_0000, 0xFED4_5000);
const IO_APIC: (u64, u64) = (0xFEC0_0000, 0xFEC0_1000);
/// Where the XSDT goes, and the MCFG naming `PCI_WINDOW`.
const XSDT_AT: u64 = ACPI.0;
const MCFG_AT: u64 = ACPI.0 + 0x100;

fn regions() -> Vec<Region> {
    let region = |(start, end): (u64, u64), class| Region { start, end, class };
    vec![
        region((0, 0x9_F000), Class::of_e820(1)),
        region((0xE_0000, 0x10_0000), Class::of_e820(2)),
        region((0x10_0000, ACPI.0), Class::Memory),
        region(ACPI, Class::of_uefi(9)),
        region(RESERVED, Class::of_uefi(0)),
        region(RUNTIME_DATA, Class::of_uefi(6)),
        region(PCI_WINDOW, Class::of_e820(2)),
        region(TPM, Class::of_e820(2)),
        region(IO_APIC, Class::of_uefi(11)),
    ]
}

/// Physical memory of placed blobs (zero elsewhere), and every read made.
#[derive(Default)]
struct Machine {
    blobs: Vec<(u64, Vec<u8>)>,
    reads: RefCell<Vec<(u64, u64)>>,
}

impl PhysicalMemory for Machine {
    fn read(&self, address: u64, into: &mut [u8]) -> Option<()> {
        self.reads.borrow_mut().push((address, address + into.len() as u64));
        into.fill(0);
        for (at, blob) in &self.blobs {
            for (offset, byte) in into.iter_mut().enumerate() {
                let Some(inside) = (address + offset as u64).checked_sub(*at) else { continue };
                if let Some(&value) = blob.get(inside as usize) {
                    *byte = value;
                }
            }
        }
        Some(())
    }
}

impl Machine {
    /// A machine whose XSDT lists `tables`, each placed at its address,
    /// with the MCFG first.
    fn with(tables: &[(u64, Vec<u8>)]) -> Self {
        let mut mcfg_body = vec![0; 8];
        mcfg_body.extend(PCI_WINDOW.0.to_le_bytes());
        mcfg_body.extend([0, 0, 0, 0xFF, 0, 0, 0, 0]);
        let mut listed = vec![(MCFG_AT, table(b"MCFG", &mcfg_body))];
        listed.extend_from_slice(tables);
        let entries: Vec<u8> = listed.iter().flat_map(|(at, _)| at.to_le_bytes()).collect();
        let mut machine = Machine { blobs: listed, ..Machine::default() };
        machine.blobs.push((XSDT_AT, table(b"XSDT", &entries)));
        machine.blobs.push((RSDP, rsdp(XSDT_AT)));
        machine
    }

    /// Whether any read reached into `from..to`.
    fn read_in(&self, (from, to): (u64, u64)) -> bool {
        self.reads.borrow().iter().any(|&(start, end)| start < to && from < end)
    }
}

fn fix_checksum(bytes: &mut [u8], at: usize) {
    bytes[at] = 0;
    let sum = bytes.iter().fold(0u8, |sum, &byte| sum.wrapping_add(byte));
    bytes[at] = sum.wrapping_neg();
}

/// A table: the 36-byte header (signature, length, revision, checksum,
/// the rest zero), then `body`.
fn table(signature: &[u8; 4], body: &[u8]) -> Vec<u8> {
    let mut table = vec![0; 36];
    table[..4].copy_from_slice(signature);
    table[4..8].copy_from_slice(&((36 + body.len()) as u32).to_le_bytes());
    table[8] = 1;
    table.extend_from_slice(body);
    fix_checksum(&mut table, 9);
    table
}

/// An ACPI 2.0 RSDP pointing to the XSDT at `xsdt`.
fn rsdp(xsdt: u64) -> Vec<u8> {
    let mut pointer = vec![0; 36];
    pointer[..8].copy_from_slice(b"RSD PTR ");
    pointer[15] = 2;
    pointer[20..24].copy_from_slice(&36u32.to_le_bytes());
    pointer[24..32].copy_from_slice(&xsdt.to_le_bytes());
    fix_checksum(&mut pointer[..20], 8);
    fix_checksum(&mut pointer, 32);
    pointer
}

/// A FADT of 276 bytes giving the PM timer at `port`, through PM_TMR_BLK
/// or, with `extended`, through X_PM_TMR_BLK.
fn fadt(port: u16, extended: bool) -> Vec<u8> {
    let mut body = vec![0; 276 - 36];
    let at = |offset: usize| offset - 36;
    if extended {
        body[at(208)] = 1;
        body[at(212)..at(220)].copy_from_slice(&u64::from(port).to_le_bytes());
    } else {
        body[at(76)..at(80)].copy_from_slice(&u32::from(port).to_le_bytes());
        body[at(91)] = 4;
    }
    body[at(112)..at(116)].copy_from_slice(&(1u32 << 8).to_le_bytes());
    table(b"FACP", &body)
}

/// An HPET table placing its registers at `address`.
fn hpet(address: u64) -> Vec<u8> {
    let mut body = vec![0; 56 - 36];
    body[8..16].copy_from_slice(&address.to_le_bytes());
    table(b"HPET", &body)
}

/// A MADT listing an I/O APIC at `address` taking interrupts from
/// `first_interrupt` on, and, if given, ISA IRQ 8 overridden to another.
fn madt(address: u32, first_interrupt: u32, irq_8_to: Option<u32>) -> Vec<u8> {
    let mut body = vec![0; 8];
    body.extend([1, 12, 0, 0]);
    body.extend(address.to_le_bytes());
    body.extend(first_interrupt.to_le_bytes());
    if let Some(to) = irq_8_to {
        body.extend([2, 10, 0, 8]);
        body.extend(to.to_le_bytes());
        body.extend([0, 0]);
    }
    table(b"APIC", &body)
}

fn tables<'a>(machine: &'a Machine, regions: &'a [Region]) -> Tables<'a, Machine> {
    Tables::new(RSDP, MemoryMap::new(regions), machine)
}

#[test]
fn a_pm_timer_on_a_fixed_devices_ports_is_refused_and_one_elsewhere_is_used() {
    let regions = regions();
    for extended in [false, true] {
        for (port, expected) in [
            (0x608, Ok(PmTimerBlock { port: 0x608, wide: true })),
            (0xB008, Ok(PmTimerBlock { port: 0xB008, wide: true })),
            (0x3F8, Err(PmTimerRefusal { port: 0x3F8 })),
            (0x3F6, Err(PmTimerRefusal { port: 0x3F6 })),
            (0x3DC, Err(PmTimerRefusal { port: 0x3DC })),
            (0x60, Err(PmTimerRefusal { port: 0x60 })),
            (0xCFC, Err(PmTimerRefusal { port: 0xCFC })),
            (0xFFFE, Err(PmTimerRefusal { port: 0xFFFE })),
        ] {
            let machine = Machine::with(&[(ACPI.0 + 0x400, fadt(port, extended))]);
            assert_eq!(tables(&machine, &regions).pm_timer(), Some(expected), "port {port:#x}, extended {extended}");
        }
    }
}

#[test]
fn device_registers_in_ram_of_any_kind_are_refused_and_in_reserved_or_device_memory_or_none_accepted() {
    let regions = regions();
    let map = MemoryMap::new(&regions);
    for (address, expected) in [
        (0x20_0000, Err(Misplaced::InRam)),
        (ACPI.0 + 0x1000, Err(Misplaced::InRam)),
        (RUNTIME_DATA.0, Err(Misplaced::InRam)),
        // The last 16 bytes of RAM's page: the registers' 1 KiB reaches in.
        (RUNTIME_DATA.0 - 0x400 + 0x10, Err(Misplaced::Misaligned)),
        (RUNTIME_DATA.0 - 0x200, Err(Misplaced::InRam)),
        (IO_APIC.0, Ok(())),
        (TPM.0, Ok(())),
        (0xFED0_0000, Ok(())),
        (0xFED0_0004, Err(Misplaced::Misaligned)),
    ] {
        assert_eq!(map.device_registers(address, 0x400, 0x200), expected, "at {address:#x}");
    }
    for (kind, class) in
        [(3, Class::Acpi), (4, Class::Acpi), (5, Class::Memory), (7, Class::Memory), (99, Class::Memory)]
    {
        assert_eq!(Class::of_e820(kind), class, "E820 type {kind}");
    }
    for (kind, class) in
        [(5, Class::Memory), (6, Class::Memory), (10, Class::Acpi), (12, Class::Device), (14, Class::Memory)]
    {
        assert_eq!(Class::of_uefi(kind), class, "UEFI type {kind}");
    }
}

#[test]
fn a_table_in_ram_in_a_device_window_or_in_no_region_is_never_read() {
    let regions = regions();
    for (at, where_) in [
        (0x20_0000, "in RAM"),
        (RUNTIME_DATA.0 + 0x100, "in runtime services' data"),
        (PCI_WINDOW.0 + 0x8000, "in the MCFG's PCI configuration window, a reserved region"),
        (TPM.0, "in the TPM's window, a reserved region"),
        (0xD000_0000, "in no region"),
    ] {
        let machine = Machine::with(&[(at, hpet(0xFED0_0000))]);
        assert_eq!(tables(&machine, &regions).hpet(), None, "an HPET table {where_}");
        // Before the MCFG is read, its windows are not known: the search
        // for it reads each listed table's signature there, and no more.
        let probed = if (PCI_WINDOW.0..PCI_WINDOW.1).contains(&at) { at + 4 } else { at };
        assert!(!machine.read_in((probed, at + 36)), "an HPET table {where_} was read");
    }
    for at in [ACPI.0 + 0x400, RESERVED.0 + 0x400] {
        let machine = Machine::with(&[(at, hpet(0xFED0_0000))]);
        assert_eq!(tables(&machine, &regions).hpet(), Some(0xFED0_0000), "an HPET table at {at:#x}");
    }
}

#[test]
fn a_table_running_out_of_the_firmwares_memory_into_ram_is_refused_before_its_body_is_read() {
    let regions = regions();
    // The header ends 4 bytes short of runtime services' data; the table
    // runs 20 bytes into it.
    let at = RUNTIME_DATA.0 - 40;
    let machine = Machine::with(&[(at, hpet(0xFED0_0000))]);
    assert_eq!(tables(&machine, &regions).hpet(), None);
    assert!(!machine.read_in(RUNTIME_DATA), "the table's body was read in RAM");
}

#[test]
fn every_madts_io_apics_are_listed_and_the_first_override_counts() {
    let regions = regions();
    let machine = Machine::with(&[
        (ACPI.0 + 0x400, madt(0xFEC0_0000, 0, Some(18))),
        (ACPI.0 + 0x800, madt(0x0100_0000, 24, Some(20))),
    ]);
    let (io_apics, rtc) = tables(&machine, &regions).io_apics(8).expect("two MADTs");
    let expected = [
        IoApicEntry { address: 0xFEC0_0000, first_interrupt: 0 },
        IoApicEntry { address: 0x0100_0000, first_interrupt: 24 },
    ];
    assert_eq!((io_apics.as_slice(), rtc), (&expected[..], 18));
    let machine = Machine::with(&[(ACPI.0 + 0x400, madt(0xFEC0_0000, 0, None))]);
    assert_eq!(tables(&machine, &regions).io_apics(8).map(|(_, rtc)| rtc), Some(8));
}
