//! Leaving QEMU with a status the host can assert on.
//!
//! QEMU's `isa-debug-exit` device (`docs/hardware.md#isa-debug-exit`) ends the
//! process with status `(value << 1) | 1`, so no value written here can
//! look like QEMU's own success (0). On a PC without the device the write
//! does nothing and the CPU halts for good.

use crate::port::DEBUG_EXIT;

/// Exits QEMU with `code`, or halts forever where there is no QEMU.
pub fn exit_qemu(code: u8) -> ! {
    x86_64::instructions::interrupts::disable();
    DEBUG_EXIT.write(u32::from(code));
    loop {
        // Interrupts are off, so only an NMI ends a `hlt`; halt again.
        x86_64::instructions::hlt();
    }
}
