//! The end of the road for panics and CPU exceptions: one `FATAL` frame
//! saying what happened, then QEMU exits with [`protocol::EXIT_FAILURE`]
//! (a real PC halts, `exit.rs`), so a kernel bug is reported, never silent
//! (`docs/hardware.md#failures`).

use core::fmt::{self, Write};
use core::panic::PanicInfo;
use core::sync::atomic::{AtomicBool, Ordering};

use protocol::FatalReport;

use crate::platform::exit;
use crate::wire::serial;

/// Longest `FATAL` text; the rest is cut. A stack buffer, not the heap:
/// the heap may be what failed.
const MESSAGE_CAPACITY: usize = 512;

/// Set by the first fatal error, so that a fault while reporting one exits
/// at once instead of looping through the handlers.
static REPORTING: AtomicBool = AtomicBool::new(false);

/// Reports `report` in a `FATAL` frame and exits QEMU with the failure
/// code.
pub fn fatal(report: FatalReport<'_>) -> ! {
    // Nothing runs after this: no interrupt handler either.
    x86_64::instructions::interrupts::disable();
    if !REPORTING.swap(true, Ordering::SeqCst) {
        let mut message = Message::new();
        // `Message` never fails; it cuts what does not fit.
        let _ = write!(message, "{report}");
        serial::send_fatal(message.as_str().as_bytes());
    }
    exit::stop(protocol::EXIT_FAILURE)
}

#[panic_handler]
fn panic(info: &PanicInfo<'_>) -> ! {
    let mut message = Message::new();
    let _ = write!(message, "{info}");
    fatal(FatalReport::Panic(message.as_str()))
}

/// A fixed buffer that keeps the first `MESSAGE_CAPACITY` bytes written.
struct Message {
    bytes: [u8; MESSAGE_CAPACITY],
    len: usize,
}

impl Message {
    fn new() -> Self {
        Self { bytes: [0; MESSAGE_CAPACITY], len: 0 }
    }

    /// What was kept: whole characters only.
    fn as_str(&self) -> &str {
        let kept = &self.bytes[..self.len];
        core::str::from_utf8(kept).unwrap_or_else(|error| {
            // The cut fell inside a character: up to it is valid UTF-8.
            core::str::from_utf8(&kept[..error.valid_up_to()]).unwrap_or_default()
        })
    }
}

impl Write for Message {
    fn write_str(&mut self, text: &str) -> fmt::Result {
        let room = MESSAGE_CAPACITY - self.len;
        let take = text.len().min(room);
        self.bytes[self.len..self.len + take].copy_from_slice(&text.as_bytes()[..take]);
        self.len += take;
        Ok(())
    }
}
