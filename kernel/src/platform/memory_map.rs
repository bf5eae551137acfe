//! The firmware's memory map as the bootloader hands it over, kept to check
//! the addresses a firmware table gives before anything reads or maps
//! them: an ACPI table must lie in the firmware's own memory (`acpi.rs`),
//! and an HPET's registers must not lie in RAM (`timers.rs`). A wrong table
//! could otherwise have the kernel read device registers as a table, or
//! mark a RAM page uncacheable and write to it.
//!
//! The bootloader passes each region of the firmware's map on with its
//! type: usable RAM, what the bootloader itself took (the kernel, its page
//! tables, the boot info), and every other type as the firmware named it
//! (`UnknownBios` with the E820 type, `UnknownUefi` with the UEFI memory
//! type). Addresses in no region (the PCI and APIC windows, on most
//! machines) are not RAM.

use alloc::vec::Vec;

use bootloader_api::info::MemoryRegionKind;
use bootloader_api::BootInfo;
use protocol::{HpetRefusal, IoApicRefusal};
use spin::Once;

/// The E820 types of the firmware's own memory: reserved, ACPI tables
/// (reclaimable), ACPI non-volatile storage.
const E820_FIRMWARE: [u32; 3] = [2, 3, 4];
/// The UEFI memory types of the same: reserved, ACPI reclaimable, ACPI
/// NVS.
const UEFI_FIRMWARE: [u32; 3] = [0, 9, 10];

/// Each region's start, end (exclusive) and kind.
static REGIONS: Once<Vec<(u64, u64, MemoryRegionKind)>> = Once::new();

/// Keeps the regions of `boot_info`'s memory map. Call once, after
/// `heap::init`.
pub fn init(boot_info: &BootInfo) {
    REGIONS
        .call_once(|| boot_info.memory_regions.iter().map(|region| (region.start, region.end, region.kind)).collect());
}

fn regions() -> &'static [(u64, u64, MemoryRegionKind)] {
    REGIONS.get().map_or(&[], Vec::as_slice)
}

/// Whether every byte of the `len` bytes from `start` lies in the
/// firmware's own memory (reserved, ACPI, ACPI NVS), where its tables are.
pub fn holds_firmware_tables(start: u64, len: u64) -> bool {
    let Some(end) = start.checked_add(len.max(1)) else { return false };
    let is_firmware = |kind: MemoryRegionKind| match kind {
        MemoryRegionKind::UnknownBios(kind) => E820_FIRMWARE.contains(&kind),
        MemoryRegionKind::UnknownUefi(kind) => UEFI_FIRMWARE.contains(&kind),
        _ => false,
    };
    // The map's regions do not overlap; walk the covered stretch up.
    let mut covered = start;
    while covered < end {
        let next = regions().iter().find(|&&(from, to, kind)| from <= covered && covered < to && is_firmware(kind));
        match next {
            Some(&(_, to, _)) => covered = to,
            None => return false,
        }
    }
    true
}

/// What is wrong with where the firmware places a device's registers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Misplaced {
    /// Off the boundary the device's registers start on.
    Misaligned,
    /// In RAM the map gives the kernel or its loader.
    InRam,
}

impl From<Misplaced> for HpetRefusal {
    fn from(misplaced: Misplaced) -> Self {
        match misplaced {
            Misplaced::Misaligned => HpetRefusal::Misaligned,
            Misplaced::InRam => HpetRefusal::InRam,
        }
    }
}

impl From<Misplaced> for IoApicRefusal {
    fn from(misplaced: Misplaced) -> Self {
        match misplaced {
            Misplaced::Misaligned => IoApicRefusal::Misaligned,
            Misplaced::InRam => IoApicRefusal::InRam,
        }
    }
}

/// Checks an address the firmware hands over for a device's `len` bytes
/// of registers, which start on a `boundary` (a power of two), before
/// anything is mapped or written there: the one check every such address
/// gets (the HPET's, each I/O APIC's), so that a wrong or hostile table
/// cannot have the kernel make a RAM page uncacheable or write into it.
pub fn device_registers(address: u64, len: u64, boundary: u64) -> Result<(), Misplaced> {
    if !address.is_multiple_of(boundary) {
        return Err(Misplaced::Misaligned);
    }
    if overlaps_ram(address, len) {
        return Err(Misplaced::InRam);
    }
    Ok(())
}

/// Whether any of the `len` bytes from `start` lies in RAM the map gives
/// the kernel or its loader (usable, or the bootloader's own).
fn overlaps_ram(start: u64, len: u64) -> bool {
    let end = start.saturating_add(len.max(1));
    regions().iter().any(|&(from, to, kind)| {
        matches!(kind, MemoryRegionKind::Usable | MemoryRegionKind::Bootloader) && from < end && start < to
    })
}
