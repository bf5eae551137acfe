//! The bare-metal side of the polygon lab: boots from the `bootloader`
//! crate's BIOS stages (stage 2 patched to leave the card in text mode,
//! see boot/image/src/bootloader.rs) or its UEFI loader, puts the VGA in
//! mode 13h with its own register writes (after undoing a UEFI firmware's
//! mode on the cards it knows, `card`) or else presents its 320x200 frame
//! in the firmware's framebuffer (`presenter`), runs the demo (the
//! show), and serves the host's commands over COM1 as soon as one arrives
//! (`server`).
//!
//! `unsafe` code lives in these modules alone, each block with a
//! `// SAFETY:` note: hardware access in `port`, `video`, `paging`, `pat`,
//! `apic`, `ioapic`, `timers`, `heap`, `gdt`, `interrupts` and `fault`;
//! `clock`'s one RDTSC; and `serial`'s one forced unlock of COM1's driver,
//! when a fatal error interrupted the code that held it.
//! Everything above them is safe code.
#![no_std]
#![no_main]
#![feature(abi_x86_interrupt)]
#![deny(unsafe_op_in_unsafe_fn)]

extern crate alloc;

mod acpi;
mod apic;
mod bench;
mod card;
mod clock;
mod demo;
mod exit;
mod fatal;
mod fault;
mod firmware;
mod gdt;
mod heap;
mod interrupts;
mod ioapic;
mod keyboard;
mod line;
mod machine;
mod memory_map;
mod paging;
mod pat;
mod pci;
mod pic;
mod pit;
mod player;
mod port;
mod presenter;
mod rtc;
mod serial;
mod server;
mod storm;
mod timers;
mod vga;
mod video;

use bootloader_api::config::{BootloaderConfig, Mapping};
use bootloader_api::{entry_point, BootInfo};

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
    interrupts::init();
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
    interrupts::enable();
    pic::check_timer();
    server::announce(&screen, firmware, &identity);
    // The show's memory, allocated once for the demo and `SHOW`.
    let mut stage = scenes::show::Stage::new();
    let mut pending = line::PendingLine::new();
    let first = demo::run(&mut screen, &mut stage, demo::Start::default(), &mut pending);
    server::serve(&mut screen, &mut stage, pending, first)
}
