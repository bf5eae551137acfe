//! The display cards whose firmware mode the kernel knows how to undo, so
//! that mode 13h can be programmed on them as under a BIOS.
//!
//! A BIOS's VGA BIOS leaves a card in text mode, a standard VGA mode, and
//! the image's boot stages set no other (boot/image/src/bootloader.rs). A
//! UEFI firmware instead leaves the card in the mode its graphics driver
//! set, a vendor's extended mode that the standard VGA registers do not
//! reach: they read back as written while the screen keeps showing the
//! firmware's framebuffer. Each card's way out is its own, so the kernel
//! touches a card only once its PCI IDs (and, for the Bochs interface, the
//! interface's own ID) say which card it is. docs/hardware.md#undoing-a-uefi-firmwares-mode
//! has the table, card by card.

use crate::platform::pci::DisplayController;
use crate::platform::port::{bochs_vbe, vmware_svga};
use crate::video::vga::{CRTC, SEQUENCER};

/// A card the kernel can return to standard VGA.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Card {
    /// QEMU's std VGA, qxl-vga and virtio-vga, Bochs's VGA and VirtualBox's
    /// VGA: the Bochs "dispi" VBE interface.
    BochsVbe,
    /// A Cirrus Logic GD5446 (QEMU's and Bochs's Cirrus card).
    Cirrus,
    /// The VMware SVGA II (also VirtualBox's VMSVGA). QEMU's model of it
    /// is built on its std VGA, so it carries the Bochs VBE interface too.
    VmwareSvga,
}

/// Cards with the Bochs VBE interface, by PCI vendor and device: QEMU's
/// std VGA (1234:1111; also bochs-display's IDs, which
/// `DisplayController::is_the_vga` tells apart), qxl-vga
/// (1b36:0100), virtio-vga (1af4:1050), VirtualBox's VGA (80ee:beef).
const BOCHS_VBE_IDS: [(u16, u16); 4] = [(0x1234, 0x1111), (0x1b36, 0x0100), (0x1af4, 0x1050), (0x80ee, 0xbeef)];
const CIRRUS_GD5446: (u16, u16) = (0x1013, 0x00b8);
const VMWARE_SVGA_II: (u16, u16) = (0x15ad, 0x0405);

/// Dispi register 0 (ID) and 4 (ENABLE). The interface answers its ID
/// register with 0xB0C0 plus its version; anything from 0xB0C0 to 0xB0CF
/// is taken for it.
const DISPI_ID: u16 = 0;
const DISPI_ENABLE: u16 = 4;
const DISPI_IDS: core::ops::RangeInclusive<u16> = 0xB0C0..=0xB0CF;

/// Cirrus sequencer register 6: writing 0x12 unlocks the extended
/// registers.
const CIRRUS_UNLOCK: (u8, u8) = (0x06, 0x12);
/// Cirrus sequencer register 7, extended sequencer mode: bit 0 selects the
/// extended (packed-pixel, linear) modes, in which the card ignores the
/// VGA's own memory mode. 0: standard VGA.
const CIRRUS_EXTENDED_MODE: (u8, u8) = (0x07, 0);
/// Cirrus CRTC register 0x1B, extended display controls: bit 4 is bit 8
/// of the row offset and bits 0, 2 and 3 are bits 16 to 18 of the display
/// start address, which the firmware's wide mode set and mode 13h's own
/// CRTC values cannot reach. 0: rows and start as the VGA registers say.
const CIRRUS_EXTENDED_DISPLAY: (u8, u8) = (0x1B, 0);

/// Which of the known cards `controller` is, if any. Only the VGA counts
/// (the VGA-compatible controller that decodes the legacy VGA ranges,
/// `DisplayController::is_the_vga`); for the Bochs VBE cards the interface
/// must also answer with its ID. Call only once the VGA has answered at
/// its standard ports: the Bochs interface's probe writes port 0x1CE.
pub fn identify(controller: &DisplayController) -> Option<Card> {
    if !controller.is_the_vga() {
        return None;
    }
    let id = (controller.id.vendor, controller.id.device);
    if BOCHS_VBE_IDS.contains(&id) {
        return has_dispi().then_some(Card::BochsVbe);
    }
    if is_cirrus(controller) {
        return Some(Card::Cirrus);
    }
    (id == VMWARE_SVGA_II).then_some(Card::VmwareSvga)
}

/// Whether `controller` is the VGA and a Cirrus Logic GD5446, by its PCI
/// IDs alone (no port is touched, so it may be asked under a BIOS too):
/// the card on which QEMU 9.0 and later redraw a changed mode-13h picture
/// only once it has been rewritten through the latches
/// (`vga::rewrite_through_latches`).
pub fn is_cirrus(controller: &DisplayController) -> bool {
    controller.is_the_vga() && (controller.id.vendor, controller.id.device) == CIRRUS_GD5446
}

impl Card {
    /// Takes the card out of the firmware's mode, back to standard VGA
    /// (the VGA registers then decide what the screen shows).
    pub fn undo_firmware_mode(self, controller: &DisplayController) {
        match self {
            Card::BochsVbe => disable_dispi(),
            Card::Cirrus => {
                SEQUENCER.write(CIRRUS_UNLOCK.0, CIRRUS_UNLOCK.1);
                SEQUENCER.write(CIRRUS_EXTENDED_MODE.0, CIRRUS_EXTENDED_MODE.1);
                CRTC.write(CIRRUS_EXTENDED_DISPLAY.0, CIRRUS_EXTENDED_DISPLAY.1);
            }
            Card::VmwareSvga => {
                // VMware's and VirtualBox's firmware set their mode through
                // the SVGA registers; OVMF sets QEMU's model's mode through
                // the Bochs interface, and leaves the SVGA mode off.
                vmware_svga::disable(controller.address);
                if has_dispi() {
                    disable_dispi();
                }
            }
        }
    }
}

/// Whether the Bochs VBE interface answers with its ID. Called only on a
/// card whose PCI IDs say it may have one.
fn has_dispi() -> bool {
    bochs_vbe::INDEX.write(DISPI_ID);
    DISPI_IDS.contains(&bochs_vbe::DATA.read())
}

/// ENABLE = 0: the VBE mode off, the VGA core drives the screen again.
fn disable_dispi() {
    bochs_vbe::INDEX.write(DISPI_ENABLE);
    bochs_vbe::DATA.write(0);
}
