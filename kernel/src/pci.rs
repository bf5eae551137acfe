//! The PCI bus, read only: which display adapter the machine has. `READY`
//! names it, so a log of a run says which card drew the screen (and the
//! harness can check that QEMU emulated the card it asked for).

use protocol::PciId;

use crate::port::pci::read_config;

/// Configuration-space offsets: vendor and device IDs; class code (bits
/// 31-24), subclass and interface; header type (bits 23-16).
const ID_OFFSET: u8 = 0x00;
const CLASS_OFFSET: u8 = 0x08;
const HEADER_OFFSET: u8 = 0x0C;
/// The vendor ID an absent function reads.
const NO_VENDOR: u16 = 0xFFFF;
/// Header type bit 7: the device has functions 1 to 7 as well.
const MULTI_FUNCTION: u32 = 0x80 << 16;
/// The base class of display controllers (VGA-compatible or not).
const DISPLAY_CLASS: u32 = 0x03;
const DEVICES_PER_BUS: u8 = 32;
const FUNCTIONS_PER_DEVICE: u8 = 8;

/// The IDs of the first display controller in bus, device, function
/// order; `None` if there is none. Reads the configuration space of every
/// possible device once (8,192 reads, and more for multi-function ones).
pub fn display_adapter() -> Option<PciId> {
    for bus in 0..=u8::MAX {
        for device in 0..DEVICES_PER_BUS {
            if vendor_and_device(bus, device, 0).is_none() {
                continue;
            }
            let multi_function = read_config(bus, device, 0, HEADER_OFFSET) & MULTI_FUNCTION != 0;
            let functions = if multi_function { FUNCTIONS_PER_DEVICE } else { 1 };
            for function in 0..functions {
                let Some(id) = vendor_and_device(bus, device, function) else { continue };
                if read_config(bus, device, function, CLASS_OFFSET) >> 24 == DISPLAY_CLASS {
                    return Some(id);
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
