//! The PCI bus, read only: which display controller the machine has.
//! `READY` names it, so a log of a run says which card drew the screen
//! (and the harness can check that QEMU emulated the card it asked for),
//! and `card.rs` decides from it what the firmware's mode takes to undo.

use protocol::PciId;

use crate::port::pci::read_config;

/// Configuration-space offsets: vendor and device IDs; class code (bits
/// 31-24), subclass (23-16) and programming interface (15-8); header type
/// (bits 23-16).
const ID_OFFSET: u8 = 0x00;
const CLASS_OFFSET: u8 = 0x08;
const HEADER_OFFSET: u8 = 0x0C;
/// The vendor ID an absent function reads.
const NO_VENDOR: u16 = 0xFFFF;
/// Header type bit 7: the device has functions 1 to 7 as well.
const MULTI_FUNCTION: u32 = 0x80 << 16;
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
    pub bus: u8,
    pub device: u8,
    pub function: u8,
    /// Class, subclass, programming interface.
    class: [u8; 3],
}

impl DisplayController {
    /// Whether it is a VGA-compatible controller (class 03/00/00).
    pub fn is_vga_compatible(&self) -> bool {
        self.class == VGA_COMPATIBLE
    }
}

/// The first display controller in bus, device, function order; `None` if
/// there is none. Reads the configuration space of every possible device
/// once (8,192 reads, and more for multi-function ones).
pub fn display_controller() -> Option<DisplayController> {
    for bus in 0..=u8::MAX {
        for device in 0..DEVICES_PER_BUS {
            if vendor_and_device(bus, device, 0).is_none() {
                continue;
            }
            let multi_function = read_config(bus, device, 0, HEADER_OFFSET) & MULTI_FUNCTION != 0;
            let functions = if multi_function { FUNCTIONS_PER_DEVICE } else { 1 };
            for function in 0..functions {
                let Some(id) = vendor_and_device(bus, device, function) else { continue };
                let [_, interface, subclass, class] = read_config(bus, device, function, CLASS_OFFSET).to_le_bytes();
                if class == DISPLAY_CLASS {
                    return Some(DisplayController { id, bus, device, function, class: [class, subclass, interface] });
                }
            }
        }
    }
    None
}

/// The IDs of `bus`:`device`.`function`, if it exists.
fn vendor_and_device(bus: u8, device: u8, function: u8) -> Option<PciId> {
    let ids = read_config(bus, device, function, ID_OFFSET);
    let [vendor_low, vendor_high, device_low, device_high] = ids.to_le_bytes();
    let vendor = u16::from_le_bytes([vendor_low, vendor_high]);
    (vendor != NO_VENDOR).then(|| PciId { vendor, device: u16::from_le_bytes([device_low, device_high]) })
}
