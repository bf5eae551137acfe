//! The firmware's memory map and ACPI tables, read as the kernel reads
//! them, with the checks every address they hand over gets before the
//! kernel reads, maps or writes there.
//!
//! The kernel gives this crate two things: the memory map's regions, each
//! with its [`Class`] (`kernel/src/platform/memory_map.rs` turns the bootloader's
//! region kinds into classes), and a way to read physical memory. Nothing
//! here touches hardware, so the host tests every decision on tables and
//! maps of its own making, hostile ones included, which QEMU cannot be
//! made to hand over: a FADT naming COM1's port as the PM timer's, a table
//! running out of the firmware's memory into RAM, a table inside a PCI
//! configuration window.
//!
//! - [`MemoryMap`] ([`Region`], [`Class`]): where device registers may be
//!   ([`MemoryMap::device_registers`], refused as [`Misplaced`]) and where
//!   firmware tables may be read ([`MemoryMap::holds_firmware_tables`]).
//! - [`Tables`]: the root table under the RSDP, and the few tables the
//!   kernel uses: the PM timer ([`PmTimerBlock`], refused as
//!   [`PmTimerRefusal`]), the HPET's address, the I/O APICs
//!   ([`IoApicEntry`]).
#![no_std]
#![forbid(unsafe_code)]

extern crate alloc;

mod acpi;
mod memory;
#[cfg(test)]
mod tests;

pub use acpi::{IoApicEntry, PhysicalMemory, PmTimerBlock, PmTimerRefusal, Tables};
pub use memory::{Class, MemoryMap, Misplaced, Region};
