//! Key presses from the PS/2 controller, by polling. Only "a key went
//! down" matters (the demo's `getch`, ABRASH_FACTS.md §1), so any make
//! code counts and nothing is decoded. With no keyboard, or no controller
//! (status reads 0xFF, which looks like mouse data), nothing is pressed.

use crate::port::ps2;

/// Status bit 0: a byte is waiting at the data port.
const OUTPUT_FULL: u8 = 0x01;
/// Status bit 5: that byte is from the auxiliary (mouse) port.
const FROM_AUX: u8 = 0x20;
/// Scan code bit 7: a release (break code), or a prefix or reply byte.
const BREAK: u8 = 0x80;

/// Whether a key was pressed since the last call. Reads (and so drops)
/// every waiting byte.
pub fn key_pressed() -> bool {
    let mut pressed = false;
    // The controller holds one byte at a time; a bounded loop still ends
    // if a broken one reports "full" forever.
    for _ in 0..16 {
        let status = ps2::STATUS.read();
        if status & OUTPUT_FULL == 0 {
            break;
        }
        let byte = ps2::DATA.read();
        // Set-1 make codes (the controller translates); 0x00 is an error.
        pressed |= status & FROM_AUX == 0 && byte & BREAK == 0 && byte != 0;
    }
    pressed
}
