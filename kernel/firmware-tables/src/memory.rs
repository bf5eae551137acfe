//! The firmware's memory map, reduced to what the kernel must know of each
//! region: may device registers be there, and may firmware tables.
//!
//! The firmware types its regions (E820 types under a BIOS, UEFI memory
//! types under UEFI); the bootloader passes usable RAM and its own on as
//! such and every other region with the firmware's type. Most types are
//! RAM of some kind (runtime services' code and data, ACPI tables, bad or
//! persistent memory): no device's registers may lie there, whatever a
//! table says. Reserved regions hold firmware data (the tables, under
//! SeaBIOS) and also device windows (the chipset's, a PCI configuration
//! window); memory-mapped I/O regions hold only devices. Addresses in no
//! region (the PCI and APIC windows, on most machines) are not RAM.

/// What a region of the memory map is, as far as the checks go.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Class {
    /// RAM of any kind: usable, the bootloader's, runtime services',
    /// unusable, persistent, or a type this code does not know.
    Memory,
    /// Where the ACPI tables live: ACPI reclaimable memory and ACPI
    /// non-volatile storage (RAM, so no device's registers either).
    Acpi,
    /// Reserved: firmware data, and device windows too.
    Reserved,
    /// Memory-mapped I/O the firmware declares: devices only.
    Device,
}

impl Class {
    /// The class of an E820 type: 1 usable, 2 reserved, 3 ACPI
    /// reclaimable, 4 ACPI NVS, 5 unusable, 7 persistent memory.
    pub fn of_e820(kind: u32) -> Self {
        match kind {
            2 => Class::Reserved,
            3 | 4 => Class::Acpi,
            _ => Class::Memory,
        }
    }

    /// The class of a UEFI memory type: 0 reserved, 1-4 the loader's and
    /// boot services' code and data, 5-6 runtime services' code and data,
    /// 7 conventional, 8 unusable, 9 ACPI reclaimable, 10 ACPI NVS, 11
    /// memory-mapped I/O, 12 memory-mapped I/O port space, 13 PAL code,
    /// 14 persistent memory.
    pub fn of_uefi(kind: u32) -> Self {
        match kind {
            0 => Class::Reserved,
            9 | 10 => Class::Acpi,
            11 | 12 => Class::Device,
            _ => Class::Memory,
        }
    }
}

/// One region of the map: its start, its end (exclusive), its class.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Region {
    pub start: u64,
    pub end: u64,
    pub class: Class,
}

/// What is wrong with where the firmware places a device's registers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Misplaced {
    /// Off the boundary the device's registers start on.
    Misaligned,
    /// In RAM of any kind the map names ([`Class::Memory`] or
    /// [`Class::Acpi`]).
    InRam,
}

/// The fixed device windows of a PC, which a reserved region may cover and
/// no firmware table lies in: the legacy VGA window, and the chipset's
/// range below 4 GiB (the I/O APICs at 0xFEC00000, the HPET at 0xFED00000,
/// the TPM at 0xFED40000, the local APIC at 0xFEE00000, the firmware's
/// flash above).
const DEVICE_WINDOWS: [(u64, u64); 2] = [(0xA_0000, 0xC_0000), (0xFEC0_0000, 0x1_0000_0000)];

/// The firmware's memory map, regions that do not overlap.
#[derive(Clone, Copy)]
pub struct MemoryMap<'a> {
    regions: &'a [Region],
}

impl<'a> MemoryMap<'a> {
    pub fn new(regions: &'a [Region]) -> Self {
        Self { regions }
    }

    /// Checks an address the firmware hands over for a device's `len`
    /// bytes of registers, which start on a `boundary` (a power of two),
    /// before anything is mapped or written there: the one check every such
    /// address gets (the HPET's, each I/O APIC's), so that a wrong or
    /// hostile table cannot have the kernel make RAM uncacheable or write
    /// into it. Reserved and device regions pass, and addresses in none.
    pub fn device_registers(self, address: u64, len: u64, boundary: u64) -> Result<(), Misplaced> {
        if !address.is_multiple_of(boundary) {
            return Err(Misplaced::Misaligned);
        }
        let end = address.saturating_add(len.max(1));
        let in_ram = self.regions.iter().any(|region| {
            matches!(region.class, Class::Memory | Class::Acpi) && region.start < end && address < region.end
        });
        if in_ram {
            return Err(Misplaced::InRam);
        }
        Ok(())
    }

    /// Whether every byte of the `len` bytes from `start` lies in the
    /// firmware's own memory (ACPI, or reserved), where its tables are, and
    /// none in a device window: a PC's fixed ones, or one of `windows` (the
    /// PCI configuration windows the MCFG names), where reading could
    /// disturb a device.
    pub fn holds_firmware_tables(self, start: u64, len: u64, windows: &[(u64, u64)]) -> bool {
        let Some(end) = start.checked_add(len.max(1)) else { return false };
        let in_a_window = DEVICE_WINDOWS.iter().chain(windows).any(|&(from, to)| from < end && start < to);
        if in_a_window {
            return false;
        }
        // The regions do not overlap; walk the covered stretch up.
        let mut covered = start;
        while covered < end {
            let holding = self.regions.iter().find(|region| {
                region.start <= covered && covered < region.end && matches!(region.class, Class::Acpi | Class::Reserved)
            });
            match holding {
                Some(region) => covered = region.end,
                None => return false,
            }
        }
        true
    }
}
