//! Interrupts and CPU exceptions: the GDT with the double fault's stack
//! (`gdt`), the IDT and its handlers (`idt`), the interrupt controllers
//! (`pic`, `apic`, `ioapic`), a vector that storms, masked at its source
//! (`storm`), the `FATAL` end of every exception and panic (`fatal`), and
//! the test-only `FAULT` command that provokes them (`fault`).
//!
//! Uses `platform`, `time` and `wire`.

pub mod apic;
mod fatal;
pub mod fault;
pub mod gdt;
pub mod idt;
pub mod ioapic;
pub mod pic;
mod storm;
