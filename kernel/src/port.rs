//! The I/O ports this kernel touches, and the only place it does port I/O
//! itself (COM1 goes through `uart_16550`).
//!
//! Port I/O is `unsafe` in `x86_64` because a port can reach memory behind
//! the compiler's back (a DMA controller, a disk, the interrupt
//! controllers). [`IoPort`] can only be made here, for the registers listed
//! below: VGA, the Bochs display interface, the PIT, the PS/2 controller
//! and QEMU's debug-exit device. None of them moves memory, so reading or
//! writing them from safe code cannot break memory safety; the worst they
//! do is change the picture, the timer or end the machine.

use core::marker::PhantomData;

use x86_64::instructions::port::{Port, PortRead, PortWrite};

/// One whitelisted I/O port, `T` wide (`u8`, `u16` or `u32`).
pub struct IoPort<T> {
    number: u16,
    width: PhantomData<T>,
}

impl<T> Clone for IoPort<T> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<T> Copy for IoPort<T> {}

impl<T> IoPort<T> {
    const fn new(number: u16) -> Self {
        Self { number, width: PhantomData }
    }
}

impl<T: PortRead> IoPort<T> {
    pub fn read(self) -> T {
        // SAFETY: `self` is one of the ports listed in this module, none of
        // which can touch memory (see the module docs).
        unsafe { Port::<T>::new(self.number).read() }
    }
}

impl<T: PortWrite> IoPort<T> {
    pub fn write(self, value: T) {
        // SAFETY: as in `read`: a listed port, which cannot touch memory.
        unsafe { Port::<T>::new(self.number).write(value) }
    }
}

/// VGA registers at their colour addresses (Misc bit 0 set, as mode 13h
/// has it); see DESIGN.md "Hardware facts".
pub mod vga {
    use super::IoPort;

    /// Attribute controller: index and data writes share this port, a
    /// flip-flop reset by reading [`INPUT_STATUS_1`] says which is next.
    pub const ATTRIBUTE_WRITE: IoPort<u8> = IoPort::new(0x3C0);
    pub const ATTRIBUTE_READ: IoPort<u8> = IoPort::new(0x3C1);
    pub const MISC_WRITE: IoPort<u8> = IoPort::new(0x3C2);
    pub const SEQUENCER_INDEX: IoPort<u8> = IoPort::new(0x3C4);
    pub const SEQUENCER_DATA: IoPort<u8> = IoPort::new(0x3C5);
    /// DAC read index: the entry that the next reads of [`DAC_DATA`] return.
    pub const DAC_READ_INDEX: IoPort<u8> = IoPort::new(0x3C7);
    /// DAC write index: the entry that the next writes of [`DAC_DATA`] set.
    pub const DAC_WRITE_INDEX: IoPort<u8> = IoPort::new(0x3C8);
    /// Red, green, blue in turn, 6 bits each; the index steps by itself.
    pub const DAC_DATA: IoPort<u8> = IoPort::new(0x3C9);
    pub const MISC_READ: IoPort<u8> = IoPort::new(0x3CC);
    pub const GRAPHICS_INDEX: IoPort<u8> = IoPort::new(0x3CE);
    pub const GRAPHICS_DATA: IoPort<u8> = IoPort::new(0x3CF);
    pub const CRTC_INDEX: IoPort<u8> = IoPort::new(0x3D4);
    pub const CRTC_DATA: IoPort<u8> = IoPort::new(0x3D5);
    /// Reading it resets the attribute controller's flip-flop; bit 3 says
    /// the CRT is in vertical retrace.
    pub const INPUT_STATUS_1: IoPort<u8> = IoPort::new(0x3DA);
}

/// The Bochs/QEMU "dispi" VBE interface. On real cards these ports may be
/// vendor registers: only `vga::disable_bochs_vbe` writes them, and only
/// after reading a Bochs ID back.
pub mod bochs {
    use super::IoPort;

    pub const INDEX: IoPort<u16> = IoPort::new(0x1CE);
    pub const DATA: IoPort<u16> = IoPort::new(0x1CF);
}

/// The 8253/8254 programmable interval timer, channel 0.
pub mod pit {
    use super::IoPort;

    pub const CHANNEL_0: IoPort<u8> = IoPort::new(0x40);
    pub const COMMAND: IoPort<u8> = IoPort::new(0x43);
}

/// The 8042 PS/2 controller.
pub mod ps2 {
    use super::IoPort;

    pub const DATA: IoPort<u8> = IoPort::new(0x60);
    pub const STATUS: IoPort<u8> = IoPort::new(0x64);
}

/// QEMU's `isa-debug-exit` device (`-device isa-debug-exit,iobase=0xf4,
/// iosize=0x04`); on a PC without it the write goes nowhere.
pub const DEBUG_EXIT: IoPort<u32> = IoPort::new(0xF4);
