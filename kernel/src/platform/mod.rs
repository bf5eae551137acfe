//! The machine under the kernel, and its memory: which machine and which
//! firmware it is (`machine`, `firmware`), the I/O ports the kernel
//! touches (`port`, the one place port I/O is granted), the PCI bus
//! (`pci`), the ACPI tables (`acpi`) and the firmware's memory map their
//! addresses are checked against (`memory_map`), the page tables and the
//! memory types a page can have (`paging`, `pat`), the heap (`heap`), and
//! the way out (`exit`).
//!
//! Every other subsystem stands on this one; it uses none of them.

pub mod acpi;
pub mod exit;
pub mod firmware;
pub mod heap;
pub mod machine;
pub mod memory_map;
pub mod paging;
pub mod pat;
pub mod pci;
pub mod port;
