//! The I/O ports this kernel touches, and the only place it grants port
//! I/O.
//!
//! Port I/O is `unsafe` in `x86_64` because a port can reach memory behind
//! the compiler's back (a DMA controller, a disk, a PCI device's address
//! decoders). [`IoPort`] can only be made here, for the registers listed
//! below: VGA, the Bochs VBE interface, the PIT, system control port B
//! (the NMI's reason), the PS/2 controller, the interrupt controllers, PCI
//! configuration reads, the POST code port (for [`io_delay`]), QEMU's
//! debug-exit device (written only once the kernel has identified QEMU,
//! `machine.rs`), the RTC's CMOS registers, and the ACPI PM timer at the port the firmware's tables
//! name; [`com1`] hands COM1's eight
//! registers to the `uart_16550` driver, and [`vmware_svga`] writes one
//! register of that card. None of
//! them moves memory, so reading or writing them from safe code cannot
//! break memory safety; the worst they do is change the picture, the timer
//! or the serial line, raise an interrupt (whose vector the IDT handles,
//! or reports as a fault) or end the machine.

use core::marker::PhantomData;

use uart_16550::backend::PioBackend;
use uart_16550::Uart16550;
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
    /// The DAC's pixel mask: ANDed with every pixel's byte before the DAC
    /// looks it up.
    pub const DAC_PIXEL_MASK: IoPort<u8> = IoPort::new(0x3C6);
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

/// COM1's base port: its eight registers are 0x3F8 to 0x3FF.
const COM1_BASE: u16 = 0x3F8;

/// The `uart_16550` driver on COM1 (`serial.rs`), which does the port I/O
/// on those eight registers itself. It checks that a UART is there before
/// it sets anything up; where none is, the reads return 0xFF and the
/// writes go nowhere.
pub fn com1() -> Uart16550<PioBackend> {
    // SAFETY: 0x3F8..=0x3FF are COM1's registers on every PC, decoded by
    // a 16550-compatible UART or by nothing; none of them moves memory (a
    // UART has no DMA in the PC's wiring). `serial::init` makes the one
    // driver and keeps it for the whole run.
    unsafe { Uart16550::new_port(COM1_BASE) }.expect("COM1's registers fit below port 0xFFFF")
}

/// The Bochs "dispi" VBE interface of QEMU's std, qxl-vga and virtio-vga
/// cards (and Bochs's and VirtualBox's own): a 16-bit index port and its
/// data port. On other cards these ports may be vendor registers, so the
/// kernel writes them only after the card's PCI IDs and the interface's
/// own ID say it is there (`card.rs`).
pub mod bochs_vbe {
    use super::IoPort;

    pub const INDEX: IoPort<u16> = IoPort::new(0x1CE);
    pub const DATA: IoPort<u16> = IoPort::new(0x1CF);
}

/// The VMware SVGA II card (PCI 15ad:0405, also VirtualBox's VMSVGA),
/// whose registers sit behind an index and a value port at the I/O base
/// its BAR 0 names.
pub mod vmware_svga {
    use protocol::PciAddress;

    use super::{pci, IoPort};

    const VENDOR_DEVICE: u32 = 0x0405_15AD;
    /// Configuration-space offset of BAR 0.
    const BAR_0: u8 = 0x10;
    /// BAR bit 0: the BAR is an I/O port range (else memory).
    const BAR_IS_IO: u32 = 1;
    /// Bits 31-2 of an I/O BAR: the base port.
    const IO_BASE_MASK: u32 = !0b11;
    /// The value port follows the index port (32-bit ports, 1 apart).
    const VALUE_OFFSET: u16 = 1;
    /// SVGA_REG_ENABLE: while set, the card shows its own framebuffer
    /// and ignores the VGA core; 0 hands the screen back to the VGA.
    const REG_ENABLE: u32 = 1;

    /// Turns the SVGA mode of the card at `address` off
    /// (SVGA_REG_ENABLE = 0), if that function is a VMware SVGA II whose
    /// BAR 0 is an I/O range; returns whether it was. Anything else is
    /// left alone.
    pub fn disable(address: PciAddress) -> bool {
        let PciAddress { bus, device, function } = address;
        if pci::read_config(bus, device, function, 0) != VENDOR_DEVICE {
            return false;
        }
        let bar = pci::read_config(bus, device, function, BAR_0);
        let Ok(base) = u16::try_from(bar & IO_BASE_MASK) else { return false };
        if bar & BAR_IS_IO == 0 || base == 0 {
            return false;
        }
        // The card's own two ports, found through its own BAR: writing
        // its enable register changes the picture only.
        IoPort::<u32>::new(base).write(REG_ENABLE);
        IoPort::<u32>::new(base + VALUE_OFFSET).write(0);
        true
    }
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

/// System control port B: reading it says why an NMI came (bit 7 a PCI
/// system error, SERR#; bit 6 an I/O channel check, IOCHK#); writing bit
/// 2 or 3 clears that latch (and masks it while set). Bits 0 and 1 gate
/// PIT channel 2 and the speaker, which the kernel leaves as it finds
/// them (`interrupts/idt.rs`).
pub mod system_control {
    use super::IoPort;

    pub const PORT_B: IoPort<u8> = IoPort::new(0x61);
}

/// The real-time clock's registers in the CMOS: an index port (bit 7 of
/// what is written disables the NMI while set, so the kernel writes it
/// clear, as the firmware leaves it) and a data port (`rtc.rs`).
pub mod cmos {
    use super::IoPort;

    pub const INDEX: IoPort<u8> = IoPort::new(0x70);
    pub const DATA: IoPort<u8> = IoPort::new(0x71);
}

/// The ACPI power management timer's counter, at the port the firmware's
/// FADT names (`acpi.rs`): a 24- or 32-bit count at 3.579545 MHz, which
/// reading does not change. Only the port the FADT gives is ever made.
pub fn acpi_pm_timer(port: u16) -> IoPort<u32> {
    IoPort::new(port)
}

/// The 8042 PS/2 controller.
pub mod ps2 {
    use super::IoPort;

    pub const DATA: IoPort<u8> = IoPort::new(0x60);
    pub const STATUS: IoPort<u8> = IoPort::new(0x64);
}

/// QEMU's `isa-debug-exit` device (`-device isa-debug-exit,iobase=0xf4,
/// iosize=0x04`). On a PC the port is in the old x87 coprocessor's range
/// and nobody knows what answers there, so the kernel writes it only on a
/// machine it has identified as QEMU (`exit.rs`, `machine.rs`); QEMU
/// without the device ignores the write.
pub const DEBUG_EXIT: IoPort<u32> = IoPort::new(0xF4);

/// The POST code port: a BIOS writes its progress codes here for a
/// diagnostic card to show, and nothing reads it. A write to it takes one
/// ISA bus cycle, about a microsecond, whatever the CPU's speed.
const POST_CODE: IoPort<u8> = IoPort::new(0x80);

/// An I/O recovery delay: one write to the POST code port, as Linux's
/// `outb_p` and the `pic8259` crate do between accesses that old chips
/// (the 8259s, ISA-era VGA cards) need time to recover from.
pub fn io_delay() {
    POST_CODE.write(0);
}
