//! Elapsed time from the 8253/8254 PIT, by polling (its interrupt stays
//! masked): the reference `clock` measures the TSC's rate against at boot.
//! Where there is no PIT its count never moves, which `clock` notices.
//!
//! Channel 0 is reprogrammed to mode 2 (rate generator) with reload 0,
//! i.e. 65,536: it counts down by one per tick at 1.193182 MHz and wraps
//! every 55 ms. Each reading latches the count and adds what went by since
//! the last one, so the stopwatch stays right as long as it is read more
//! often than every 55 ms. (The BIOS leaves mode 3, which counts by twos.)

use crate::platform::port::pit;

/// PIT input clock in ticks per second.
pub const TICKS_PER_SECOND: u64 = 1_193_182;

/// Command: channel 0 (bits 7-6 = 00), low byte then high byte
/// (bits 5-4 = 11), mode 2 (bits 3-1 = 010), binary (bit 0 = 0).
const CHANNEL_0_MODE_2: u8 = 0x34;
/// Command: channel 0, latch the count (bits 5-4 = 00).
const CHANNEL_0_LATCH: u8 = 0x00;

/// Counts PIT ticks since it was started.
pub struct Stopwatch {
    last_count: u16,
    elapsed: u64,
}

impl Stopwatch {
    /// Reprograms channel 0 and starts counting from zero.
    pub fn start() -> Self {
        pit::COMMAND.write(CHANNEL_0_MODE_2);
        pit::CHANNEL_0.write(0);
        pit::CHANNEL_0.write(0);
        Self { last_count: read_count(), elapsed: 0 }
    }

    /// Ticks since `start`.
    pub fn elapsed_ticks(&mut self) -> u64 {
        let count = read_count();
        // The counter runs down and wraps at 65,536, which u16 arithmetic
        // does by itself.
        self.elapsed += u64::from(self.last_count.wrapping_sub(count));
        self.last_count = count;
        self.elapsed
    }
}

fn read_count() -> u16 {
    pit::COMMAND.write(CHANNEL_0_LATCH);
    let low = pit::CHANNEL_0.read();
    let high = pit::CHANNEL_0.read();
    u16::from_le_bytes([low, high])
}
