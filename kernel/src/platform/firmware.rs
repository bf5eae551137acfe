//! Which firmware started the boot, read from the memory map the
//! bootloader hands over: its UEFI loader passes on the UEFI memory map,
//! marking every region that is not conventional memory with its UEFI type
//! (`UnknownUefi`), its BIOS stages the BIOS's E820 map, marking every
//! region that is not usable RAM with its E820 type (`UnknownBios`). Both
//! maps always hold such regions (the loader's own code and data, the
//! firmware's, ACPI tables; the BIOS area below 1 MiB).

use bootloader_api::info::MemoryRegionKind;
use bootloader_api::BootInfo;
use protocol::Firmware;

/// The firmware that booted the kernel: UEFI if the memory map came from
/// UEFI, else a BIOS (or a UEFI firmware's CSM, which is one to us).
pub fn of(boot_info: &BootInfo) -> Firmware {
    let from_uefi =
        boot_info.memory_regions.iter().any(|region| matches!(region.kind, MemoryRegionKind::UnknownUefi(_)));
    if from_uefi {
        Firmware::Uefi
    } else {
        Firmware::Bios
    }
}
