//! The demo that runs when no host talks: the built-in scenes
//! (`raster::scenes::NAMES`: Listings 38.3 and 40.4, the WGT triangle) in
//! turn, each with the method of its source, each for about 3 seconds or until a key is pressed (the book's
//! `getch`), round and round. It works with no keyboard and no serial
//! line: the timer alone turns the pages.
//!
//! The first byte from the host stops it for good, so that what the host
//! draws is all that is on the screen when it asks for a dump.

use core::hint::spin_loop;

use raster::scenes;

use crate::pit::{Stopwatch, TICKS_PER_SECOND};
use crate::video::Screen;
use crate::{keyboard, serial};

/// How long a page stays up without a key press.
const PAGE_TICKS: u64 = 3 * TICKS_PER_SECOND;

/// Runs the demo until the host sends a byte, and returns that byte.
pub fn run(screen: &mut Screen) -> u8 {
    let mut stopwatch = Stopwatch::start();
    let mut pages = scenes::NAMES.iter().cycle();
    loop {
        if let Some(scene) = pages.next().and_then(|name| scenes::by_name(name)) {
            screen.draw(&scene, scene.method());
        }
        stopwatch.restart();
        while stopwatch.elapsed_ticks() < PAGE_TICKS && !keyboard::key_pressed() {
            if let Some(byte) = serial::try_read_byte() {
                return byte;
            }
            spin_loop();
        }
    }
}
