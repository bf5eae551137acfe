//! Stopping for good: on request (`EXIT`) and after a fatal error.
//!
//! On QEMU the stop leaves QEMU with a status the host can assert on: its
//! `isa-debug-exit` device (`docs/emulators.md#isa-debug-exit`) ends the
//! process with status `(value << 1) | 1`, so no value written there can
//! look like QEMU's own success (0). The kernel writes that port only on a
//! machine it has identified as QEMU (`machine.rs`): on a PC it is a port
//! nobody identified. Elsewhere, and on a QEMU without the device, the CPU
//! halts for good. A non-maskable interrupt, the one thing that ends a
//! halt with interrupts off (a chipset reporting a parity error, say),
//! is counted and returned from like any other (`idt.rs`), and
//! the CPU halts again.

use protocol::Machine;

use crate::platform::machine;
use crate::platform::port::DEBUG_EXIT;

/// Stops: exits QEMU with `code` on a machine identified as QEMU, and
/// halts.
pub fn stop(code: u8) -> ! {
    x86_64::instructions::interrupts::disable();
    if machine::current() == Machine::Qemu {
        DEBUG_EXIT.write(u32::from(code));
    }
    loop {
        // Interrupts are off, so only an NMI ends a `hlt`; halt again.
        x86_64::instructions::hlt();
    }
}
