//! The real-time clock's periodic interrupt, IRQ 8, only as the test-only
//! `FAULT strayirq` and `FAULT interruptstorm` raise it (`fault.rs`): a
//! device's interrupt the kernel can start and stop at will, and whose line
//! stays high until the kernel reads register C, as a level-triggered
//! source's does until its driver serves it.
//!
//! The registers (the MC146818's, which every PC's chipset keeps): A sets
//! the periodic rate (bits 0-3, 6 = 1024 Hz; bits 4-6 the divider, left
//! as they are), B enables the periodic interrupt (bit 6), C says which
//! interrupt fired and, read, clears them all and lowers IRQ 8.

use x86_64::instructions::interrupts;

use crate::platform::port::cmos;

const REGISTER_A: u8 = 0x0A;
const REGISTER_B: u8 = 0x0B;
const REGISTER_C: u8 = 0x0C;
const RATE_BITS: u8 = 0x0F;
/// Rate 6: 32768 >> (6 - 1) = 1024 interrupts a second.
const RATE_1024_HZ: u8 = 6;
const PERIODIC_INTERRUPT_ENABLE: u8 = 1 << 6;

/// Reads a CMOS register. The index and the data access go together, so
/// no interrupt may come between them.
fn read(register: u8) -> u8 {
    interrupts::without_interrupts(|| {
        cmos::INDEX.write(register);
        cmos::DATA.read()
    })
}

fn write(register: u8, value: u8) {
    interrupts::without_interrupts(|| {
        cmos::INDEX.write(register);
        cmos::DATA.write(value);
    });
}

/// Starts (`true`) or stops the periodic interrupt, at 1024 Hz.
pub fn periodic(on: bool) {
    if on {
        write(REGISTER_A, read(REGISTER_A) & !RATE_BITS | RATE_1024_HZ);
    }
    let b = read(REGISTER_B);
    write(REGISTER_B, if on { b | PERIODIC_INTERRUPT_ENABLE } else { b & !PERIODIC_INTERRUPT_ENABLE });
}

/// Reads register C: what fired is cleared, and IRQ 8 goes low.
pub fn acknowledge() {
    read(REGISTER_C);
}
