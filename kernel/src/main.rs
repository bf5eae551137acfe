//! The bare-metal side of the polygon lab: boots from the `bootloader`
//! crate's BIOS stages (stage 2 patched to leave the card in text mode,
//! see boot/image/src/bootloader.rs), puts the VGA in mode 13h with its own
//! register writes, runs the demo (the show), and serves the host's
//! commands over COM1 as soon as one arrives.
//!
//! Hardware access lives in small modules with `// SAFETY:` notes
//! (`port`, `video`, `heap`, `gdt`, `interrupts`, `fault`, and `bench`'s
//! one RDTSC); everything above them is safe code.
#![no_std]
#![no_main]
#![feature(abi_x86_interrupt)]
#![deny(unsafe_op_in_unsafe_fn)]

extern crate alloc;

mod bench;
mod console;
mod demo;
mod exit;
mod fatal;
mod fault;
mod gdt;
mod heap;
mod interrupts;
mod keyboard;
mod pci;
mod pit;
mod player;
mod port;
mod serial;
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
    serial::init();
    gdt::init();
    interrupts::init();
    heap::init();
    vga::init();
    let Some(mut screen) = video::Screen::new(boot_info) else {
        panic!("the bootloader did not map physical memory, so 0xA0000 is out of reach");
    };
    // The text mode the BIOS left had other bytes in video memory.
    screen.clear(0);
    serial::enable_receive_interrupt();
    interrupts::enable();
    console::announce(&screen);
    // The show's memory, allocated once for the demo and `SHOW`.
    let mut stage = scenes::show::Stage::new();
    let first_byte = demo::run(&mut screen, &mut stage, demo::Start::default());
    console::serve(&mut screen, &mut stage, first_byte)
}
