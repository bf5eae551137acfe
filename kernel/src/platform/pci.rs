//! The PCI bus, read only: which display controller answers at the
//! legacy VGA addresses, and the subsystem IDs `machine.rs` reads. `READY`
//! names the display controller and where it sits, so a log of a run says
//! which card drew the screen (and the harness can check that QEMU
//! emulated the card it asked for), and `card.rs` decides from it what the
//! firmware's mode takes to undo.
//!
//! A PC with two display devices (an integrated and a discrete GPU, or two
//! in a virtual machine) has one of them decode the legacy VGA ranges
//! (ports 0x3B0 to 0x3DF, memory 0xA0000 to 0xBFFFF), which the kernel's
//! register writes and its frame reach: the device the path of those
//! addresses leads to. A device on a root bus decodes them if it is
//! VGA-compatible and its command register has I/O and memory decoding
//! on; one behind a PCI-to-PCI bridge only if that bridge, and every
//! bridge above it, forwards them (bit 3, VGA Enable, of its bridge
//! control register, with its own decoding on). That device is the one
//! [`display_controller`] names; only where none decodes them does it name
//! the first display controller in bus order, as the frame then goes
//! elsewhere (a firmware's framebuffer) or nowhere.
//!
//! Under UEFI the firmware's framebuffer lies in one device's memory,
//! which need not be that VGA's: the head the firmware showed its own
//! screen on. [`Displays::holding`] finds the display controller whose
//! memory BAR holds an address, from the BARs' bases alone (sizing a BAR
//! takes a configuration write, which this module never makes): BARs do
//! not overlap, so the BAR holding an address is the one with the
//! greatest base at or below it, of every BAR of every function; and a
//! BAR is aligned to its size, which bounds how far past its base an
//! address in it can lie.

use alloc::vec::Vec;

use protocol::{PciAddress, PciId};

use crate::platform::port::pci::read_config;

/// Configuration-space offsets: vendor and device IDs; command register
/// (bits 15-0); class code (bits 31-24), subclass (23-16) and programming
/// interface (15-8); header type (bits 23-16); a bridge's bus numbers
/// (primary 7-0, secondary 15-8); a bridge's control register (bits
/// 31-16); a device's subsystem vendor and subsystem IDs.
const ID_OFFSET: u8 = 0x00;
const COMMAND_OFFSET: u8 = 0x04;
const CLASS_OFFSET: u8 = 0x08;
const HEADER_OFFSET: u8 = 0x0C;
const BRIDGE_BUSES_OFFSET: u8 = 0x18;
const BRIDGE_CONTROL_OFFSET: u8 = 0x3C;
const SUBSYSTEM_OFFSET: u8 = 0x2C;
/// The base address registers: six in a device's header, two in a
/// bridge's.
const FIRST_BAR_OFFSET: u8 = 0x10;
const DEVICE_BARS: u8 = 6;
const BRIDGE_BARS: u8 = 2;
/// BAR bit 0: an I/O range (else memory); bits 2-1 of a memory BAR: 10
/// for a 64-bit BAR, whose upper half is the next BAR; bits 31-4 of a
/// memory BAR: its base.
const BAR_IO: u32 = 1;
const BAR_64_BIT: u32 = 0b100;
const BAR_MEMORY_BASE: u32 = !0xF;
/// The vendor ID an absent function reads.
const NO_VENDOR: u16 = 0xFFFF;
/// Header type bit 7: the device has functions 1 to 7 as well.
const MULTI_FUNCTION: u32 = 0x80 << 16;
/// Header type bits 6-0: 0 a device, 1 a PCI-to-PCI bridge.
const HEADER_TYPE: u32 = 0x7F << 16;
const DEVICE_HEADER: u32 = 0;
const BRIDGE_HEADER: u32 = 1 << 16;
/// Command register bits 0 and 1: the function decodes its I/O ports and
/// its memory.
const DECODES_IO_AND_MEMORY: u32 = 0b11;
/// Bridge control bit 3 (bit 19 of its dword): VGA Enable, the bridge
/// forwards the legacy VGA ranges to its secondary bus.
const BRIDGE_VGA_ENABLE: u32 = 1 << (16 + 3);
/// The base class of display controllers (VGA-compatible or not).
const DISPLAY_CLASS: u8 = 0x03;
/// Class 03, subclass 00, interface 00: a VGA-compatible controller,
/// which decodes the VGA's memory and ports. Other display controllers
/// (03/80, e.g. QEMU's bochs-display, which shares the std VGA's IDs) have
/// no VGA at all.
const VGA_COMPATIBLE: [u8; 3] = [DISPLAY_CLASS, 0x00, 0x00];
const DEVICES_PER_BUS: u8 = 32;
const FUNCTIONS_PER_DEVICE: u8 = 8;

/// A display controller on the PCI bus.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DisplayController {
    pub id: PciId,
    pub address: PciAddress,
    /// Class, subclass, programming interface.
    class: [u8; 3],
    /// Whether the legacy VGA ranges reach it (see the module docs).
    decodes_vga: bool,
}

impl DisplayController {
    /// Whether it is the VGA the kernel's register writes and its frame
    /// reach: a VGA-compatible controller (class 03/00/00) that the legacy
    /// VGA ranges are routed to.
    pub fn is_the_vga(&self) -> bool {
        self.class == VGA_COMPATIBLE && self.decodes_vga
    }
}

/// The display controllers on the bus, and the memory BARs of every
/// function, from one scan.
pub struct Displays {
    /// In bus, device, function order.
    displays: Vec<DisplayController>,
    /// Every memory BAR's base and the function it belongs to.
    bars: Vec<(u64, PciAddress)>,
}

impl Displays {
    /// Reads the configuration space of every possible device once (8,192
    /// reads, and more for multi-function ones).
    pub fn scan() -> Self {
        let mut bridges = Vec::new();
        let mut displays = Vec::new();
        let mut bars = Vec::new();
        for address in functions() {
            let decodes = read(address, COMMAND_OFFSET) & DECODES_IO_AND_MEMORY == DECODES_IO_AND_MEMORY;
            match read(address, HEADER_OFFSET) & HEADER_TYPE {
                BRIDGE_HEADER => {
                    bars.extend(memory_bars(address, BRIDGE_BARS).map(|base| (base, address)));
                    bridges.push(Bridge {
                        bus: address.bus,
                        secondary: read(address, BRIDGE_BUSES_OFFSET).to_le_bytes()[1],
                        forwards_vga: decodes && read(address, BRIDGE_CONTROL_OFFSET) & BRIDGE_VGA_ENABLE != 0,
                    });
                }
                DEVICE_HEADER => {
                    bars.extend(memory_bars(address, DEVICE_BARS).map(|base| (base, address)));
                    let [_, interface, subclass, class] = read(address, CLASS_OFFSET).to_le_bytes();
                    if let (DISPLAY_CLASS, Some(id)) = (class, vendor_and_device(address)) {
                        let class = [class, subclass, interface];
                        displays.push(DisplayController { id, address, class, decodes_vga: decodes });
                    }
                }
                _ => {}
            }
        }
        for display in &mut displays {
            display.decodes_vga &= vga_ranges_reach(display.address.bus, &bridges);
        }
        Self { displays, bars }
    }

    /// The display controller that decodes the legacy VGA ranges (the
    /// first, if a misconfigured machine has more than one), else the
    /// first display controller in bus, device, function order; `None` if
    /// there is none.
    pub fn vga(&self) -> Option<DisplayController> {
        self.displays.iter().find(|display| display.is_the_vga()).or(self.displays.first()).copied()
    }

    /// The display controller one of whose memory BARs holds physical
    /// address `address` (see the module docs); `None` if the BAR there
    /// is another function's, or none is (a framebuffer in RAM).
    pub fn holding(&self, address: u64) -> Option<DisplayController> {
        let &(base, function) = self.bars.iter().filter(|(base, _)| *base <= address).max_by_key(|(base, _)| *base)?;
        let within_alignment = address - base < 1u64.checked_shl(base.trailing_zeros()).unwrap_or(u64::MAX);
        within_alignment.then(|| self.displays.iter().find(|display| display.address == function).copied()).flatten()
    }
}

/// The bases of the memory BARs among the first `count` of the function
/// at `address` (64-bit ones whole); unassigned ones (base 0) left out.
fn memory_bars(address: PciAddress, count: u8) -> impl Iterator<Item = u64> {
    let mut index = 0;
    core::iter::from_fn(move || {
        while index < count {
            let low = read(address, FIRST_BAR_OFFSET + 4 * index);
            index += 1;
            if low & BAR_IO != 0 {
                continue;
            }
            let mut base = u64::from(low & BAR_MEMORY_BASE);
            if low & BAR_64_BIT != 0 && index < count {
                base |= u64::from(read(address, FIRST_BAR_OFFSET + 4 * index)) << 32;
                index += 1;
            }
            if base != 0 {
                return Some(base);
            }
        }
        None
    })
}

/// A PCI-to-PCI bridge: the bus it sits on, the bus behind it, and
/// whether it passes the legacy VGA ranges on to that bus.
struct Bridge {
    bus: u8,
    secondary: u8,
    forwards_vga: bool,
}

/// Whether the legacy VGA ranges reach `bus`: a root bus (behind no
/// bridge) gets them from the host bridge; a bus behind a bridge, only if
/// that bridge forwards them and they reach the bridge's own bus.
fn vga_ranges_reach(bus: u8, bridges: &[Bridge]) -> bool {
    let mut bus = bus;
    // A chain of bridges is at most 255 long; the bound keeps a
    // misconfigured loop of bus numbers from going round for ever.
    for _ in 0..=u8::MAX {
        match bridges.iter().find(|bridge| bridge.secondary == bus && bridge.secondary != bridge.bus) {
            None => return true,
            Some(bridge) if bridge.forwards_vga => bus = bridge.bus,
            Some(_) => return false,
        }
    }
    false
}

/// The subsystem vendor and subsystem IDs of the device at `address`, if a
/// device (not a bridge) is there.
pub fn subsystem(address: PciAddress) -> Option<PciId> {
    vendor_and_device(address)?;
    if read(address, HEADER_OFFSET) & HEADER_TYPE != DEVICE_HEADER {
        return None;
    }
    let [vendor_low, vendor_high, device_low, device_high] = read(address, SUBSYSTEM_OFFSET).to_le_bytes();
    Some(PciId {
        vendor: u16::from_le_bytes([vendor_low, vendor_high]),
        device: u16::from_le_bytes([device_low, device_high]),
    })
}

/// Every function present, in bus, device, function order.
fn functions() -> impl Iterator<Item = PciAddress> {
    (0..=u8::MAX).flat_map(|bus| {
        (0..DEVICES_PER_BUS).flat_map(move |device| {
            let first = PciAddress { bus, device, function: 0 };
            let functions = match vendor_and_device(first) {
                None => 0,
                Some(_) if read(first, HEADER_OFFSET) & MULTI_FUNCTION != 0 => FUNCTIONS_PER_DEVICE,
                Some(_) => 1,
            };
            (0..functions)
                .map(move |function| PciAddress { bus, device, function })
                .filter(|&address| vendor_and_device(address).is_some())
        })
    })
}

/// The IDs of the function at `address`, if it exists.
fn vendor_and_device(address: PciAddress) -> Option<PciId> {
    let ids = read(address, ID_OFFSET);
    let [vendor_low, vendor_high, device_low, device_high] = ids.to_le_bytes();
    let vendor = u16::from_le_bytes([vendor_low, vendor_high]);
    (vendor != NO_VENDOR).then(|| PciId { vendor, device: u16::from_le_bytes([device_low, device_high]) })
}

fn read(address: PciAddress, offset: u8) -> u32 {
    read_config(address.bus, address.device, address.function, offset)
}
