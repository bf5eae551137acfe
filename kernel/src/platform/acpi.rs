//! The firmware's ACPI tables under the RSDP the bootloader found, read
//! through the bootloader's map of all physical memory
//! (`paging::read_physical`) where the memory map allows
//! (`memory_map.rs`). What is read, and every check of it, is the
//! `firmware-tables` crate's, where the host tests it on tables of its own
//! making.

use firmware_tables::{PhysicalMemory, Tables};

use crate::platform::{memory_map, paging};

/// Physical memory as the kernel reads it.
struct Physical;

impl PhysicalMemory for Physical {
    fn read(&self, address: u64, into: &mut [u8]) -> Option<()> {
        paging::read_physical(address, into)
    }
}

/// The tables under the RSDP at `rsdp`. Call after `memory_map::init` and
/// `paging::init`.
pub fn tables(rsdp: u64) -> Tables<'static, impl PhysicalMemory> {
    Tables::new(rsdp, memory_map::map(), &Physical)
}
