//! The I/O ports this kernel touches, and the only place it does port I/O.
//!
//! Port I/O is `unsafe` in `x86_64` because a port can reach memory behind
//! the compiler's back (a DMA controller, a disk, a PCI device's address
//! decoders). [`IoPort`] can only be made here, for the registers listed
//! below: VGA, COM1, the PIT, the PS/2 controller, the interrupt
//! controllers, PCI configuration reads and QEMU's debug-exit device. None
//! of them moves memory, so reading or writing them from safe code cannot
//! break memory safety; the worst they do is change the picture, the timer
//! or the serial line, raise an interrupt (whose vector the IDT handles,
//! or reports as a fault) or end the machine.

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
/// and the BIOS's colour text mode have it).
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

/// COM1, a 16550 UART (`serial.rs`). With the divisor latch bit of
/// [`com1::LINE_CONTROL`] set, the first two ports are the baud divisor.
pub mod com1 {
    use super::IoPort;

    /// Receive buffer when read, transmit holding register when written;
    /// divisor low byte while the divisor latch is open.
    pub const DATA: IoPort<u8> = IoPort::new(0x3F8);
    /// Which events raise the UART's interrupt; divisor high byte while
    /// the divisor latch is open.
    pub const INTERRUPT_ENABLE: IoPort<u8> = IoPort::new(0x3F9);
    pub const FIFO_CONTROL: IoPort<u8> = IoPort::new(0x3FA);
    pub const LINE_CONTROL: IoPort<u8> = IoPort::new(0x3FB);
    pub const MODEM_CONTROL: IoPort<u8> = IoPort::new(0x3FC);
    /// Reading it clears its error bits (overrun among them).
    pub const LINE_STATUS: IoPort<u8> = IoPort::new(0x3FD);
}

/// The two 8259 interrupt controllers of the PC, master and slave.
pub mod pic {
    use super::IoPort;

    pub const MASTER_COMMAND: IoPort<u8> = IoPort::new(0x20);
    pub const MASTER_DATA: IoPort<u8> = IoPort::new(0x21);
    pub const SLAVE_COMMAND: IoPort<u8> = IoPort::new(0xA0);
    pub const SLAVE_DATA: IoPort<u8> = IoPort::new(0xA1);
}

/// PCI configuration mechanism 1: a write to 0xCF8 selects a dword of one
/// function's configuration space, which 0xCFC then reads. Only reads are
/// offered here, through [`pci::read_config`]: a write to 0xCFC could move
/// a device's address windows or let it master the bus, and reach memory.
pub mod pci {
    use super::IoPort;

    const ADDRESS: IoPort<u32> = IoPort::new(0xCF8);
    const DATA: IoPort<u32> = IoPort::new(0xCFC);
    /// Bit 31 of the address: the cycle is a configuration access.
    const ENABLE: u32 = 1 << 31;

    /// The dword at `offset` (rounded down to a multiple of 4) of the
    /// configuration space of `bus`:`device`.`function` (device below 32,
    /// function below 8; higher bits are dropped). An absent function
    /// reads 0xFFFF_FFFF. Reads of the standard header have no side
    /// effects.
    pub fn read_config(bus: u8, device: u8, function: u8, offset: u8) -> u32 {
        let address = ENABLE
            | u32::from(bus) << 16
            | u32::from(device & 0x1F) << 11
            | u32::from(function & 0x07) << 8
            | u32::from(offset & 0xFC);
        ADDRESS.write(address);
        DATA.read()
    }
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
