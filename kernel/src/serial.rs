//! COM1, the protocol channel (kernel/protocol): frames out, command bytes
//! in, polled (interrupts stay off in this kernel).
//!
//! A PC may have no COM1 at all. Then the port stays `None`: frames go
//! nowhere and no byte ever arrives, so the demo runs on. Reading an absent
//! UART would return 0xFF, "data ready", and stop the demo for nothing.

use core::fmt::{self, Write};

use protocol::{FrameHeader, FrameKind};
use spin::Mutex;
use uart_16550::backend::PioBackend;
use uart_16550::{BaudRate, Config, Uart16550};

type Uart = Uart16550<PioBackend>;

/// The standard COM1 base port.
const COM1_BASE: u16 = 0x3F8;

static COM1: Mutex<Option<Uart>> = Mutex::new(None);

/// Initialises COM1 at 115200 baud 8-N-1 with FIFOs. The bootloader's own
/// serial logging is off (boot/src/main.rs), so the line is ours alone.
/// QEMU ignores the speed; on a real PC the host's terminal must match it.
pub fn init() {
    // SAFETY: 0x3F8..0x3FF are COM1's registers on every PC, and nothing
    // else in this kernel drives them: the `Uart` lives only in `COM1`.
    let Ok(mut uart) = (unsafe { Uart::new_port(COM1_BASE) }) else { return };
    let config = Config { baud_rate: BaudRate::Baud115200, ..Config::DEFAULT };
    if uart.init(config).is_ok() {
        *COM1.lock() = Some(uart);
    }
}

/// The next byte from the host, if one has arrived.
pub fn try_read_byte() -> Option<u8> {
    COM1.lock().as_mut()?.try_receive_byte().ok()
}

/// Sends one frame: header line, payload, `\n` (kernel/protocol/src/lib.rs).
pub fn send_frame(kind: FrameKind, payload: &[u8]) {
    if let Some(uart) = COM1.lock().as_mut() {
        write_frame(uart, kind, payload);
    }
}

/// Sends a `FATAL` frame from a fault or panic handler. Interrupts are off
/// and there is one CPU, so if the port is locked, its holder is the code
/// this fault interrupted, which never runs again: the lock is taken over
/// rather than waited for forever (the frame may then land inside a
/// half-sent one; the host resynchronises on the next header).
pub fn send_fatal(payload: &[u8]) {
    if COM1.is_locked() {
        // SAFETY: see above: the holder never resumes, so no two parties
        // use the UART at once.
        unsafe { COM1.force_unlock() };
    }
    send_frame(FrameKind::Fatal, payload);
}

fn write_frame(uart: &mut Uart, kind: FrameKind, payload: &[u8]) {
    let header = FrameHeader::for_payload(kind, payload);
    // `Wire` never fails.
    let _ = writeln!(Wire(uart), "{header}");
    uart.send_bytes_exact(payload);
    uart.send_bytes_exact(b"\n");
}

/// `fmt::Write` straight to the UART, byte for byte: no `\n` to `\r\n`
/// translation, which would break the frame lengths.
struct Wire<'a>(&'a mut Uart);

impl Write for Wire<'_> {
    fn write_str(&mut self, text: &str) -> fmt::Result {
        self.0.send_bytes_exact(text.as_bytes());
        Ok(())
    }
}
