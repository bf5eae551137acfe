//! The bare-metal side of the polygon lab: boots from the `bootloader`
//! crate's BIOS stages (stage 2 patched to leave the card in text mode,
//! see boot/image/src/bootloader.rs) or its UEFI loader, puts the VGA in
//! mode 13h with its own register writes (after undoing a UEFI firmware's
//! mode on the cards it knows, `video::card`) or else presents its 320x200
//! frame in the firmware's framebuffer (`video::presenter`), runs the demo
//! (the show), and serves the host's commands over COM1 as soon as one
//! arrives (`server`).
//!
//! Each subsystem is a folder whose `mod.rs` says what it owns and is its
//! one face to the others, and each uses only those above it in this
//! list (tests/tests/import_circles.rs finds any circle):
//! - `platform`: the machine, the firmware's tables and memory map, I/O
//!   ports, PCI, the page tables and memory types, the heap, the exit;
//! - `time`: the clock every wait ends by, and the timers it is measured
//!   against;
//! - `wire`: COM1 and the command line its bytes make;
//! - `interrupts`: the GDT, the IDT and its handlers, the interrupt
//!   controllers, and the `FATAL` end of exceptions and panics;
//! - `video`: the screen, on the VGA or in a firmware's framebuffer;
//! - `show`: the demo and the player of its frames;
//! - `server`: the protocol server's commands.
//!
//! `unsafe` code lives in these modules alone, each block with a
//! `// SAFETY:` note: hardware access in `platform::port`,
//! `platform::paging`, `platform::pat`, `platform::heap`, `time::timers`,
//! `interrupts::gdt`, `interrupts::idt`, `interrupts::apic`,
//! `interrupts::ioapic`, `interrupts::fault`, `video::screen` and
//! `video::canvas`; `time::clock`'s one RDTSC; and `wire::serial`'s one
//! forced unlock of COM1's driver, when a fatal error interrupted the code
//! that held it.
//! Everything above them is safe code.
#![no_std]
#![no_main]
#![feature(abi_x86_interrupt)]
#![deny(unsafe_op_in_unsafe_fn)]

extern crate alloc;

mod interrupts;
mod platform;
mod server;
mod show;
mod time;
mod video;
mod wire;

use bootloader_api::config::{BootloaderConfig, Mapping};
use bootloader_api::{entry_point, BootInfo};

use interrupts::{apic, gdt, idt, ioapic, pic};
use platform::{firmware, heap, machine, memory_map, paging, pci};
use show::demo;
use time::clock;
use wire::{line, serial};

/// All physical memory mapped at an offset the bootloader chooses: how the
/// kernel reaches 0xA0000, which is not mapped otherwise.
static CONFIG: BootloaderConfig = {
    let mut config = BootloaderConfig::new_default();
    config.mappings.physical_memory = Some(Mapping::Dynamic);
    config
};

entry_point!(kernel_main, config = &CONFIG);

fn kernel_main(boot_info: &'static mut BootInfo) -> ! {
    // First, so that a fatal error from here on knows whether it may
    // leave QEMU through its exit port.
    let identity = machine::identify();
    gdt::init();
    idt::init();
    heap::init();
    paging::init(boot_info);
    memory_map::init(boot_info);
    // After the page tables, through which it reaches the ACPI tables and
    // the HPET; before anything that waits.
    clock::init(boot_info.rsdp_addr.into_option());
    serial::init();
    apic::init();
    ioapic::init(boot_info.rsdp_addr.into_option());
    let firmware = firmware::of(boot_info);
    let displays = pci::Displays::scan();
    let mut screen = video::Screen::open(boot_info, firmware, &displays);
    serial::enable_interrupt();
    idt::enable();
    pic::check_timer();
    server::announce(&screen, firmware, &identity);
    // The show's memory, allocated once for the demo and `SHOW`.
    let mut stage = scenes::show::Stage::new();
    let mut pending = line::PendingLine::new();
    let first = demo::run(&mut screen, &mut stage, demo::Start::default(), &mut pending);
    server::serve(&mut screen, &mut stage, pending, first)
}
