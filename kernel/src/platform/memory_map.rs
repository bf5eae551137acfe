//! The firmware's memory map as the bootloader hands it over, kept to check
//! the addresses a firmware table gives before anything reads or maps
//! them: an ACPI table must lie in the firmware's own memory (`acpi.rs`),
//! and an HPET's or an I/O APIC's registers in no RAM (`time/timers.rs`,
//! `interrupts/ioapic.rs`). A wrong table could otherwise have the kernel read device
//! registers as a table, or mark a RAM page uncacheable and write to it.
//!
//! The bootloader passes each region of the firmware's map on with its
//! type: usable RAM, what the bootloader itself took (the kernel, its page
//! tables, the boot info), and every other type as the firmware named it
//! (`UnknownBios` with the E820 type, `UnknownUefi` with the UEFI memory
//! type). Each becomes a `firmware_tables::Class`, and the checks are that
//! crate's.

use alloc::vec::Vec;

use bootloader_api::info::MemoryRegionKind;
use bootloader_api::BootInfo;
use firmware_tables::{Class, MemoryMap, Misplaced, Region};
use spin::Once;

/// The map's regions.
static REGIONS: Once<Vec<Region>> = Once::new();

/// Keeps the regions of `boot_info`'s memory map. Call once, after
/// `heap::init`.
pub fn init(boot_info: &BootInfo) {
    REGIONS.call_once(|| {
        let class = |kind| match kind {
            MemoryRegionKind::UnknownBios(kind) => Class::of_e820(kind),
            MemoryRegionKind::UnknownUefi(kind) => Class::of_uefi(kind),
            _ => Class::Memory,
        };
        let regions = boot_info.memory_regions.iter();
        regions.map(|region| Region { start: region.start, end: region.end, class: class(region.kind) }).collect()
    });
}

/// The memory map (empty before `init`).
pub fn map() -> MemoryMap<'static> {
    MemoryMap::new(REGIONS.get().map_or(&[], Vec::as_slice))
}

/// Checks an address the firmware hands over for a device's `len` bytes
/// of registers, which start on a `boundary`, before anything is mapped or
/// written there (`MemoryMap::device_registers`).
pub fn device_registers(address: u64, len: u64, boundary: u64) -> Result<(), Misplaced> {
    map().device_registers(address, len, boundary)
}
