//! Mode 13h by our own register writes, the DAC, and the read-back proof.
//!
//! The mode is data ([`MODE_13H`]); [`set_mode`] is the one function that
//! knows the order the registers must be written in, and [`verify`] reads
//! every one of them back, with the DAC against the palette the screen
//! loaded last. [`wait_for_retrace`] is the one timing signal the card
//! gives. The values are the standard mode-13h table (Chris Giese's
//! modes.c, SeaBIOS vgasrc/stdvgamodes.c and rust-osdev/vga agree on
//! them).
//!
//! The card is expected in a standard VGA mode, as the BIOS leaves it
//! (the image's boot stages never set a VBE mode), or as `card.rs` leaves
//! it after undoing a UEFI firmware's mode: these are the standard
//! registers only, and a card still in a vendor's extended mode could read
//! them all back as written and show garbage. [`verify`] proves the
//! writes, not the picture; the harness proves the picture with QEMU's
//! screendump.

use alloc::vec::Vec;

use protocol::{Mismatch, RegisterGroup};
use scenes::palette::{Palette, ENTRIES};
use volatile::VolatilePtr;

use crate::platform::port::{io_delay, vga, IoPort};
use crate::time::clock::Deadline;
use crate::wire::serial;

/// Bytes in the DAC: 256 entries of red, green, blue.
pub const DAC_LEN: usize = ENTRIES * 3;

/// A display mode as register values, each group indexed from 0.
struct Mode {
    misc: u8,
    sequencer: &'static [u8],
    crtc: &'static [u8],
    graphics: &'static [u8],
    attribute: &'static [u8],
}

/// 320x200, 256 colours, chain-4: one byte per pixel, linear at 0xA0000.
const MODE_13H: Mode = Mode {
    misc: 0x63,
    sequencer: &[0x03, 0x01, 0x0F, 0x00, 0x0E],
    crtc: &[
        0x5F, 0x4F, 0x50, 0x82, 0x54, 0x80, 0xBF, 0x1F, 0x00, 0x41, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, //
        0x9C, 0x0E, 0x8F, 0x28, 0x40, 0x96, 0xB9, 0xA3, 0xFF,
    ],
    graphics: &[0x00, 0x00, 0x00, 0x00, 0x00, 0x40, 0x05, 0x0F, 0xFF],
    attribute: &[
        0x00, 0x01, 0x02, 0x03, 0x04, 0x05, 0x06, 0x07, 0x08, 0x09, 0x0A, 0x0B, 0x0C, 0x0D, 0x0E, 0x0F, //
        0x41, 0x00, 0x0F, 0x00, 0x00,
    ],
};

/// Sequencer register 0 while the others change: synchronous reset
/// (bit 1 clear), so the sequencer does not run on a half-set clock.
const SEQUENCER_SYNC_RESET: u8 = 0x01;
/// CRTC register 0x11, whose bit 7 write-protects CRTC registers 0-7.
const CRTC_PROTECT_INDEX: u8 = 0x11;
const CRTC_PROTECT_BIT: u8 = 0x80;
/// Attribute index bit 5 (palette address source): while clear the
/// attribute registers are open to the CPU and the screen is blank; it must
/// be set again at the end or the screen stays blank.
const ATTRIBUTE_VIDEO_ON: u8 = 0x20;
/// Attribute registers 0x00 to 0x0F are the palette registers, which the
/// CPU may read only while the palette address source bit is clear.
const ATTRIBUTE_PALETTE_END: u8 = 0x10;
/// Input status 1 bit 3: the CRT is in vertical retrace.
const VERTICAL_RETRACE: u8 = 0x08;
/// Longest [`wait_for_retrace`]: two frames of mode 13h's 70 Hz. A card
/// reaches the start of a retrace within one frame; under QEMU the bit
/// flips on every read; a card whose bit never changes is waited for no
/// longer than this.
const RETRACE_TIMEOUT_MICROS: u64 = 2 * 1_000_000 / 70;
/// Graphics register 8, the bit mask: read and write on every VGA, and
/// left as the kernel found it by [`responds`].
const GRAPHICS_BIT_MASK: u8 = 0x08;
/// Sequencer register 4, memory mode, and its chain-4 bit: set, the CPU's
/// address picks the plane (mode 13h's linear bytes); clear, the map mask
/// does and every plane sees the same address.
const SEQUENCER_MEMORY_MODE: u8 = 0x04;
const CHAIN_4: u8 = 0x08;
/// Graphics register 5, graphics mode, and write mode 1 in its bits 0-1:
/// a CPU write stores the four latches (loaded by the last read) into the
/// planes, whatever the byte written.
const GRAPHICS_MODE: u8 = 0x05;
const WRITE_MODE_1: u8 = 0x01;
/// The granularity of QEMU's record of written video memory: its target
/// page, 4 KiB on x86.
const QEMU_DIRTY_PAGE: usize = 4096;

/// An index/data port pair: one register group.
#[derive(Clone, Copy)]
pub struct IndexedRegisters {
    index: IoPort<u8>,
    data: IoPort<u8>,
}

pub const SEQUENCER: IndexedRegisters = IndexedRegisters { index: vga::SEQUENCER_INDEX, data: vga::SEQUENCER_DATA };
pub const CRTC: IndexedRegisters = IndexedRegisters { index: vga::CRTC_INDEX, data: vga::CRTC_DATA };
const GRAPHICS: IndexedRegisters = IndexedRegisters { index: vga::GRAPHICS_INDEX, data: vga::GRAPHICS_DATA };

impl IndexedRegisters {
    pub fn write(self, index: u8, value: u8) {
        self.index.write(index);
        self.data.write(value);
    }

    fn read(self, index: u8) -> u8 {
        self.index.write(index);
        self.data.read()
    }

    fn write_all(self, values: &[u8]) {
        for (index, &value) in (0..).zip(values) {
            self.write(index, value);
        }
    }
}

/// Writes one attribute register. The flip-flop is reset first, so the
/// write to 0x3C0 is taken as the index and the next as the data. Every
/// access waits an I/O delay: the attribute controller of some ISA-era
/// cards loses writes that follow each other too closely (X.Org's VGA
/// code waits the same way between attribute accesses).
fn write_attribute(index: u8, value: u8) {
    vga::INPUT_STATUS_1.read();
    io_delay();
    vga::ATTRIBUTE_WRITE.write(index);
    io_delay();
    vga::ATTRIBUTE_WRITE.write(value);
    io_delay();
}

/// Reads one attribute register. A palette register (0x00 to 0x0F) is
/// read with the palette address source bit clear, as the VGA references
/// require (some cards return garbage, or block the read, with it set):
/// the screen goes blank for the few microseconds of the read and is
/// turned on again after it. The other registers are read with it set,
/// the screen left on. Each access waits an I/O delay, as writes do.
fn read_attribute(index: u8) -> u8 {
    let palette = index < ATTRIBUTE_PALETTE_END;
    vga::INPUT_STATUS_1.read();
    io_delay();
    vga::ATTRIBUTE_WRITE.write(if palette { index } else { index | ATTRIBUTE_VIDEO_ON });
    io_delay();
    let value = vga::ATTRIBUTE_READ.read();
    io_delay();
    if palette {
        video_on();
    }
    value
}

/// Gives the palette back to the display (palette address source set):
/// the screen shows again. The flip-flop is reset first, so the write is
/// taken as an index.
fn video_on() {
    vga::INPUT_STATUS_1.read();
    io_delay();
    vga::ATTRIBUTE_WRITE.write(ATTRIBUTE_VIDEO_ON);
    io_delay();
}

/// Every bit of a pixel's byte reaches the DAC: the pixel mask a BIOS's
/// mode set writes. A firmware may leave another, which masks the palette.
const PIXEL_MASK_ALL: u8 = 0xFF;

/// Puts the card in mode 13h, its DAC pixel mask open. The DAC is the
/// screen's to load (`video::Screen`).
pub fn set_mode_13h() {
    set_mode(&MODE_13H);
    // A DAC index write first: on a Cirrus card the fifth access to 0x3C6
    // after four reads of it in a row reaches its hidden DAC register
    // instead, and any other DAC port resets that count.
    vga::DAC_WRITE_INDEX.write(0);
    vga::DAC_PIXEL_MASK.write(PIXEL_MASK_ALL);
}

/// Whether a VGA answers at the standard ports: the graphics bit-mask
/// register keeps two patterns written to it (an absent card reads 0xFF),
/// and is then given its value back. No wait, no timing.
pub fn responds() -> bool {
    let old = GRAPHICS.read(GRAPHICS_BIT_MASK);
    let answers = [0x5A, 0xA5].into_iter().all(|pattern| {
        GRAPHICS.write(GRAPHICS_BIT_MASK, pattern);
        GRAPHICS.read(GRAPHICS_BIT_MASK) == pattern
    });
    GRAPHICS.write(GRAPHICS_BIT_MASK, old);
    answers
}

/// Programs `mode` in the order the registers depend on: the sequencer
/// held in a synchronous reset while Misc (whose clock select changes the
/// dot clock under it) and the other sequencer registers change; CRTC
/// after Misc bit 0 has put it at the colour addresses and after unlocking
/// registers 0-7; graphics; the attribute controller; finally the video
/// back on.
fn set_mode(mode: &Mode) {
    SEQUENCER.write(0, SEQUENCER_SYNC_RESET);
    vga::MISC_WRITE.write(mode.misc);
    for (index, &value) in (0..).zip(mode.sequencer).skip(1) {
        SEQUENCER.write(index, value);
    }
    if let Some(&reset) = mode.sequencer.first() {
        SEQUENCER.write(0, reset);
    }

    let protect = CRTC.read(CRTC_PROTECT_INDEX);
    CRTC.write(CRTC_PROTECT_INDEX, protect & !CRTC_PROTECT_BIT);
    CRTC.write_all(mode.crtc);

    GRAPHICS.write_all(mode.graphics);

    for (index, &value) in (0..).zip(mode.attribute) {
        write_attribute(index, value);
    }
    video_on();
}

/// Rewrites one doubleword in every 4 KiB of `window` (the mode-13h
/// window, as mapped) with itself, through the latches: chain 4 off, write
/// mode 1, a read (which loads the four latches) and a write (which stores
/// them back, the byte written being ignored) at offsets 0, 4096, ...,
/// then mode 13h's memory mode and graphics mode back. Video memory is
/// left as it was on any VGA; the point is the write itself.
///
/// QEMU's Cirrus card since QEMU 9.0 records a chain-4 write in mode 13h
/// (doubleword addressing) at a quarter of its address, so only the rows
/// in the first 16 KiB are ever drawn again and the rest of the screen
/// keeps the last picture; a write through the latches is recorded where
/// it lands. Called after each change of the picture on that card, it
/// marks every 4 KiB of the frame as written;
/// docs/emulators.md#cirrus-since-qemu-90 has the details and the QEMU commit.
pub fn rewrite_through_latches(window: VolatilePtr<'_, [u8]>) {
    let memory_mode = MODE_13H.sequencer[usize::from(SEQUENCER_MEMORY_MODE)];
    let graphics_mode = MODE_13H.graphics[usize::from(GRAPHICS_MODE)];
    SEQUENCER.write(SEQUENCER_MEMORY_MODE, memory_mode & !CHAIN_4);
    GRAPHICS.write(GRAPHICS_MODE, graphics_mode | WRITE_MODE_1);
    for offset in (0..window.len()).step_by(QEMU_DIRTY_PAGE) {
        let byte = window.index(offset);
        byte.write(byte.read());
    }
    GRAPHICS.write(GRAPHICS_MODE, graphics_mode);
    SEQUENCER.write(SEQUENCER_MEMORY_MODE, memory_mode);
}

/// Loads the DAC: 6-bit red, green, blue per entry from entry 0 on. A
/// register-level mode set leaves the DAC as the text mode had it, so mode
/// 13h's palette is loaded by hand. Each write waits an I/O delay: the
/// RAMDACs of ISA-era cards need time between accesses (X.Org's VGA code
/// waits between DAC accesses too); 769 delays, under a millisecond.
pub fn load_dac(palette: &Palette) {
    vga::DAC_WRITE_INDEX.write(0);
    io_delay();
    for &level in palette.as_flattened() {
        vga::DAC_DATA.write(level);
        io_delay();
    }
}

/// The DAC read back, entry 0 first, red, green, blue each.
pub fn read_dac() -> [u8; DAC_LEN] {
    vga::DAC_READ_INDEX.write(0);
    let mut dac = [0; DAC_LEN];
    dac.fill_with(|| vga::DAC_DATA.read());
    dac
}

/// Waits for the start of a vertical retrace, the moment to change the
/// picture without tearing: while the retrace bit is set (one already
/// under way), then until it is set. Gives up after
/// [`RETRACE_TIMEOUT_MICROS`] by the clock, so it ends on any machine.
/// COM1 is polled meanwhile (`serial::poll`).
pub fn wait_for_retrace() {
    let in_retrace = || {
        serial::poll();
        vga::INPUT_STATUS_1.read() & VERTICAL_RETRACE != 0
    };
    let give_up = Deadline::after_micros(RETRACE_TIMEOUT_MICROS);
    while in_retrace() && !give_up.passed() {}
    while !in_retrace() && !give_up.passed() {}
}

/// Reads back every register of [`MODE_13H`] and the whole DAC and returns
/// whatever differs from what [`set_mode`] wrote and from `palette`, the
/// palette [`load_dac`] loaded last. (Not the DAC's pixel mask: QEMU's VGA
/// does not keep it and reads 0x00 there whatever was written.) Empty means the card is in mode 13h
/// as we set it.
pub fn verify(palette: &Palette) -> Vec<Mismatch> {
    let mode = &MODE_13H;
    let mut mismatches = Vec::new();
    let mut check = |group, index, expected, actual| {
        if expected != actual {
            mismatches.push(Mismatch { group, index, expected, actual });
        }
    };
    check(RegisterGroup::Misc, 0, mode.misc, vga::MISC_READ.read());
    let groups = [
        (RegisterGroup::Sequencer, SEQUENCER, mode.sequencer),
        (RegisterGroup::Crtc, CRTC, mode.crtc),
        (RegisterGroup::Graphics, GRAPHICS, mode.graphics),
    ];
    for (group, registers, values) in groups {
        for (index, &value) in (0..).zip(values) {
            check(group, usize::from(index), value, registers.read(index));
        }
    }
    for (index, &value) in (0..).zip(mode.attribute) {
        check(RegisterGroup::Attribute, usize::from(index), value, read_attribute(index));
    }
    for (index, (&expected, actual)) in palette.as_flattened().iter().zip(read_dac()).enumerate() {
        check(RegisterGroup::Dac, index, expected, actual);
    }
    mismatches
}
