//! Leaving QEMU with a status the host can assert on.
//!
//! QEMU's `isa-debug-exit` device (DESIGN.md "Hardware facts") ends the
//! process with status `(value << 1) | 1`, so no value written here can
//! look like QEMU's own success (0). On a PC without the device the write
//! does nothing and the CPU halts for good.

use crate::port::DEBUG_EXIT;

/// The codes the harness knows: `Success` gives process status 33,
/// `Failed` 35.
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum QemuExitCode {
    /// What the host sends as `EXIT 16` to end a run cleanly; the kernel
    /// never exits successfully on its own.
    #[expect(dead_code, reason = "the host sends this code with EXIT; kept to document the pair")]
    Success = 0x10,
    /// A panic or CPU exception.
    Failed = 0x11,
}

/// Exits QEMU with `code`, or halts forever where there is no QEMU.
pub fn exit_qemu(code: u8) -> ! {
    DEBUG_EXIT.write(u32::from(code));
    loop {
        // Interrupts are off, so only an NMI ends a `hlt`; halt again.
        x86_64::instructions::hlt();
    }
}
