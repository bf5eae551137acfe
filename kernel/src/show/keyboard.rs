//! The demo's keys, from the PS/2 controller by polling: set-1 make codes
//! (the controller translates), decoded into what the viewer asks for.
//! With no keyboard, or no controller (status reads 0xFF, which looks like
//! mouse data), no key is ever pressed.

use raster::MethodId;

use crate::platform::port::ps2;

/// Status bit 0: a byte is waiting at the data port.
const OUTPUT_FULL: u8 = 0x01;
/// Status bit 5: that byte is from the auxiliary (mouse) port.
const FROM_AUX: u8 = 0x20;

/// Set-1 make codes of the keys the demo knows.
const ESCAPE: u8 = 0x01;
/// Keys 1 to 9 are 0x02 to 0x0A, in order.
const DIGIT_1: u8 = 0x02;
const DIGIT_9: u8 = 0x0A;
const DIGIT_0: u8 = 0x0B;
const ENTER: u8 = 0x1C;
const SPACE: u8 = 0x39;

/// What a key asks the demo for.
#[derive(Clone, Copy)]
pub enum Key {
    /// Space or Enter: the next entry.
    Next,
    /// A digit d from 1: every entry drawn with `MethodId::ALL[d - 1]`.
    Method(MethodId),
    /// 0: every entry with its own method again.
    OwnMethods,
    /// Escape: the first entry from frame 0, with its own method.
    Restart,
}

/// The last key pressed since the last call that means something to the
/// demo. Reads (and so drops) every waiting byte: releases, prefixes and
/// other keys are ignored.
pub fn poll() -> Option<Key> {
    let mut key = None;
    // The controller holds one byte at a time; a bounded loop still ends
    // if a broken one reports "full" forever.
    for _ in 0..16 {
        let status = ps2::STATUS.read();
        if status & OUTPUT_FULL == 0 {
            break;
        }
        let code = ps2::DATA.read();
        if status & FROM_AUX == 0 {
            key = decode(code).or(key);
        }
    }
    key
}

/// The key a set-1 make code stands for. Break codes (bit 7 set), 0x00
/// (an error) and digits past the last method mean nothing.
fn decode(code: u8) -> Option<Key> {
    match code {
        SPACE | ENTER => Some(Key::Next),
        DIGIT_1..=DIGIT_9 => MethodId::ALL.get(usize::from(code - DIGIT_1)).map(|&method| Key::Method(method)),
        DIGIT_0 => Some(Key::OwnMethods),
        ESCAPE => Some(Key::Restart),
        _ => None,
    }
}
