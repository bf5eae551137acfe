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
//! interface's own ID) say which card it is. docs/hardware.md has the
//! table, card by card.

use crate::pci::DisplayController;
use crate::port::{bochs_vbe, vga, vmware_svga};
use crate::vga::{CRTC, GRAPHICS, SEQUENCER};

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
/// `DisplayController::is_vga_compatible` tells apart), qxl-vga
/// (1b36:0100), virtio-vga (1af4:1050), VirtualBox's VGA (80ee:beef).
const BOCHS_VBE_IDS: [(u16, u16); 4] = [(0x1234, 0x1111), (0x1b36, 0x0100), (0x1af4, 0x1050), (0x80ee, 0xbeef)];
const CIRRUS_GD5446: (u16, u16) = (0x1013, 0x00b8);
const VMWARE_SVGA_II: (u16, u16) = (0x15ad, 0x0405);

/// Dispi register 0 (ID) and 4 (ENABLE); the IDs the interface reports,
/// 0xB0C0 to 0xB0C5 in today's emulators, 0xB0C0 to 0xB0CF reserved.
const DISPI_ID: u16 = 0;
const DISPI_ENABLE: u16 = 4;
const DISPI_IDS: core::ops::RangeInclusive<u16> = 0xB0C0..=0xB0CF;

/// Cirrus sequencer register 6: writing 0x12 unlocks the extended
/// registers.
const CIRRUS_UNLOCK: (u8, u8) = (0x06, 0x12);
/// The Cirrus extended registers set back to their standard-VGA values,
/// each 0 (from the GD5446 register reference, and as QEMU's model reads
/// them): SR7, extended sequencer mode (bit 0: the packed-pixel extended
/// modes); CR1A, interlace and overlay; CR1B, extended display controls
/// (address wrap, extended start address, blanking); CR1D, overlay
/// extended control; GR9 and GRA, the two offset (bank) registers; GRB,
/// graphics controller mode extensions (the banking granularity). The
/// firmware's driver had set them; which of them the picture needs was
/// not narrowed down, all are cleared.
const CIRRUS_SEQUENCER: [(u8, u8); 1] = [(0x07, 0)];
const CIRRUS_CRTC: [(u8, u8); 3] = [(0x1A, 0), (0x1B, 0), (0x1D, 0)];
const CIRRUS_GRAPHICS: [(u8, u8); 3] = [(0x09, 0), (0x0A, 0), (0x0B, 0)];
/// Reads of the pixel mask in a row that open the hidden DAC register.
const HIDDEN_DAC_READS: usize = 4;
/// The hidden DAC register's standard value: 8-bit palette-indexed pixels.
const HIDDEN_DAC_STANDARD: u8 = 0;

/// Which of the known cards `controller` is, if any. Only VGA-compatible
/// controllers count; for the Bochs VBE cards the interface must also
/// answer with its ID.
pub fn identify(controller: &DisplayController) -> Option<Card> {
    if !controller.is_vga_compatible() {
        return None;
    }
    let id = (controller.id.vendor, controller.id.device);
    if BOCHS_VBE_IDS.contains(&id) {
        return has_dispi().then_some(Card::BochsVbe);
    }
    match id {
        CIRRUS_GD5446 => Some(Card::Cirrus),
        VMWARE_SVGA_II => Some(Card::VmwareSvga),
        _ => None,
    }
}

impl Card {
    /// Takes the card out of the firmware's mode, back to standard VGA
    /// (the VGA registers then decide what the screen shows).
    pub fn undo_firmware_mode(self, controller: &DisplayController) {
        match self {
            Card::BochsVbe => disable_dispi(),
            Card::Cirrus => {
                SEQUENCER.write(CIRRUS_UNLOCK.0, CIRRUS_UNLOCK.1);
                for (index, value) in CIRRUS_SEQUENCER {
                    SEQUENCER.write(index, value);
                }
                for (index, value) in CIRRUS_CRTC {
                    CRTC.write(index, value);
                }
                for (index, value) in CIRRUS_GRAPHICS {
                    GRAPHICS.write(index, value);
                }
                // Any DAC index access resets the count of pixel-mask reads.
                vga::DAC_WRITE_INDEX.read();
                for _ in 0..HIDDEN_DAC_READS {
                    vga::PEL_MASK.read();
                }
                vga::PEL_MASK.write(HIDDEN_DAC_STANDARD);
            }
            Card::VmwareSvga => {
                vmware_svga::disable(controller.bus, controller.device, controller.function);
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
