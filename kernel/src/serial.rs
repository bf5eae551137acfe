//! COM1, the protocol channel (kernel/protocol): frames out, command bytes
//! in, through the `uart_16550` crate's driver. Sending polls the UART;
//! receiving is by interrupt (IRQ 4, see `interrupts.rs`) into a ring
//! buffer, so bytes arriving while the demo draws a frame or the console
//! answers a command are kept: the UART's own FIFO holds only 16, about
//! 1.4 ms at 115200 baud.
//!
//! What is lost anyway is counted ([`losses`]): overrun errors the UART
//! reports in its line status (a byte arrived with its FIFO full) and
//! bytes that found the ring full. Reading the line status clears the
//! overrun bit; the driver keeps the error bits of its own reads and
//! hands them out with the next `lsr()`, which is where they are counted.
//!
//! A PC may have no COM1 at all. The driver's presence check (the scratch
//! register holds what is written to it; an absent port reads 0xFF) needs
//! no timing, so it answers the same on a PC and under any emulator. With
//! no COM1 nothing is set up: frames go nowhere and no byte ever arrives,
//! so the demo runs on. Every wait for the transmitter ends by the clock.

use core::fmt::{self, Write};
use core::hint::spin_loop;
use core::sync::atomic::{AtomicBool, AtomicU32, AtomicU8, AtomicUsize, Ordering};

use protocol::{FrameHeader, FrameKind, LineLosses};
use spin::Mutex;
use uart_16550::backend::PioBackend;
use uart_16550::spec::registers::{FifoTriggerLevel, IER, LSR};
use uart_16550::{BaudRate, Config, Uart16550};
use x86_64::instructions::interrupts;

use crate::clock::Deadline;
use crate::port;

/// Longest wait for room in the transmitter before the rest of a frame is
/// given up: 16 bytes take 1.4 ms at 115200 baud, but under QEMU the
/// transmitter waits for the host to read its end of the line, which a
/// loaded host may not do for a while. A host that resynchronises on the
/// next frame header loses one frame, never the kernel.
const SEND_TIMEOUT_MICROS: u64 = 2_000_000;

/// Bytes the ring holds: a whole command line of `protocol::MAX_LINE` and
/// the commands a host sends behind it while a long answer (a 64 KB dump)
/// goes out.
const RING_LEN: usize = 16 * 1024;

/// COM1's driver, once [`init`] found a UART there. Taken by the
/// interrupt handler, and by the main flow only with interrupts off, so
/// neither ever waits for the other.
static COM1: Mutex<Option<Uart16550<PioBackend>>> = Mutex::new(None);
/// Whether COM1 is set up, without taking the lock.
static PRESENT: AtomicBool = AtomicBool::new(false);
/// Serialises senders: a frame goes out whole.
static SENDING: Mutex<()> = Mutex::new(());
static OVERRUNS: AtomicU32 = AtomicU32::new(0);
static DROPPED: AtomicU32 = AtomicU32::new(0);

/// Received bytes, written by the interrupt handler alone and read by the
/// kernel's main flow alone: `RING_HEAD` (bytes taken) only ever chases
/// `RING_TAIL` (bytes put), both counting up and wrapping, and each side
/// publishes its count with release after touching the slots.
static RING: [AtomicU8; RING_LEN] = [const { AtomicU8::new(0) }; RING_LEN];
static RING_HEAD: AtomicUsize = AtomicUsize::new(0);
static RING_TAIL: AtomicUsize = AtomicUsize::new(0);

/// Sets COM1 to 115200 baud 8-N-1 with FIFOs (receive interrupt after 8
/// bytes, leaving 8 bytes of room for the handler to get there), if there
/// is a COM1, its interrupt still off ([`enable_receive_interrupt`] turns
/// it on once the IDT and the PIC are ready for it). The bootloader's own
/// serial logging is off (boot/src/main.rs), so the line is ours alone.
/// QEMU ignores the speed; on a real PC the host's terminal must match it.
pub fn init() {
    let mut uart = port::com1();
    let config = Config {
        baud_rate: BaudRate::Baud115200,
        fifo_trigger_level: Some(FifoTriggerLevel::Eight),
        ..Config::DEFAULT
    };
    // Fails only where the presence check finds no UART.
    if uart.init(config).is_ok() {
        *COM1.lock() = Some(uart);
        PRESENT.store(true, Ordering::Release);
    }
}

/// Lets COM1 raise IRQ 4 when bytes arrive (if there is a COM1).
pub fn enable_receive_interrupt() {
    with_com1(|uart| uart.enable_interrupts(IER::DATA_READY));
}

/// Runs `work` on COM1's driver with interrupts off; nothing where there
/// is no COM1.
fn with_com1<R: Default>(work: impl FnOnce(&mut Uart16550<PioBackend>) -> R) -> R {
    interrupts::without_interrupts(|| COM1.lock().as_mut().map(work).unwrap_or_default())
}

/// Counts an overrun in `lsr`, the line status with the error bits the
/// driver saved since the last `lsr()`.
fn count_overrun(lsr: LSR) {
    if lsr.contains(LSR::OVERRUN_ERROR) {
        OVERRUNS.fetch_add(1, Ordering::Relaxed);
    }
}

/// The IRQ 4 handler's work: moves every waiting byte from the UART into
/// the ring (counting those that find it full). Runs with interrupts off.
pub fn receive_waiting_bytes() {
    let mut com1 = COM1.lock();
    let Some(uart) = com1.as_mut() else { return };
    while let Ok(byte) = uart.try_receive_byte() {
        let tail = RING_TAIL.load(Ordering::Relaxed);
        if tail.wrapping_sub(RING_HEAD.load(Ordering::Acquire)) == RING_LEN {
            DROPPED.fetch_add(1, Ordering::Relaxed);
            continue;
        }
        RING[tail % RING_LEN].store(byte, Ordering::Relaxed);
        RING_TAIL.store(tail.wrapping_add(1), Ordering::Release);
    }
    count_overrun(uart.lsr());
}

/// The next byte from the host, if one has arrived.
pub fn try_read_byte() -> Option<u8> {
    let head = RING_HEAD.load(Ordering::Relaxed);
    if head == RING_TAIL.load(Ordering::Acquire) {
        return None;
    }
    let byte = RING[head % RING_LEN].load(Ordering::Relaxed);
    RING_HEAD.store(head.wrapping_add(1), Ordering::Release);
    Some(byte)
}

/// The next byte from the host, halting the CPU until an interrupt brings
/// one. Called only once a byte has come (the console serves a host that
/// is talking), so it waits for that host, not for a device.
pub fn read_byte() -> u8 {
    loop {
        // With interrupts off between the look and the `hlt` (`sti; hlt`
        // opens them only as the CPU halts), a byte cannot slip in
        // unnoticed in between.
        interrupts::disable();
        if let Some(byte) = try_read_byte() {
            interrupts::enable();
            return byte;
        }
        interrupts::enable_and_hlt();
    }
}

/// What the line has lost on the way in since boot.
pub fn losses() -> LineLosses {
    with_com1(|uart| count_overrun(uart.lsr()));
    LineLosses { overruns: OVERRUNS.load(Ordering::Relaxed), dropped: DROPPED.load(Ordering::Relaxed) }
}

/// Sends one frame: header line, payload, `\n` (kernel/protocol/src/lib.rs).
pub fn send_frame(kind: FrameKind, payload: &[u8]) {
    send_reply(kind, None, payload);
}

/// Sends the frame answering a command line, its header echoing the
/// line's sequence number if the line was sealed (`protocol::Sealed`).
pub fn send_reply(kind: FrameKind, seq: Option<u32>, payload: &[u8]) {
    if PRESENT.load(Ordering::Acquire) {
        let _sending = SENDING.lock();
        write_frame(FrameHeader::for_reply(kind, payload, seq), payload);
    }
}

/// Sends a `FATAL` frame from a fault or panic handler. Interrupts are off
/// and there is one CPU, so if a frame is being sent, its sender is the
/// code this fault interrupted, which never runs again: the frame goes out
/// without waiting for it (it may then land inside a half-sent one; the
/// host resynchronises on the next header). If the fault struck inside the
/// driver itself (its lock is held), nothing can be sent; the exit status
/// still says the run failed.
pub fn send_fatal(payload: &[u8]) {
    if PRESENT.load(Ordering::Acquire) && !COM1.is_locked() {
        write_frame(FrameHeader::for_payload(FrameKind::Fatal, payload), payload);
    }
}

fn write_frame(header: FrameHeader, payload: &[u8]) {
    let mut wire = Wire;
    if writeln!(wire, "{header}").is_ok() && send_bytes(payload).is_ok() {
        // A frame cut short is ended by nothing: the host's next header
        // search skips what came of it.
        let _ = send_bytes(b"\n");
    }
}

/// The transmitter had no room for [`SEND_TIMEOUT_MICROS`].
struct Stalled;

/// Sends `bytes` as they are, as many at a time as the transmitter FIFO
/// takes, waiting (a bounded time) for room before each batch.
fn send_bytes(mut bytes: &[u8]) -> Result<(), Stalled> {
    while !bytes.is_empty() {
        let give_up = Deadline::after_micros(SEND_TIMEOUT_MICROS);
        loop {
            let sent = with_com1(|uart| uart.send_bytes(bytes));
            if sent > 0 {
                bytes = &bytes[sent..];
                break;
            }
            if give_up.passed() {
                return Err(Stalled);
            }
            spin_loop();
        }
    }
    Ok(())
}

/// `fmt::Write` straight to the UART, byte for byte: no `\n` to `\r\n`
/// translation, which would break the frame lengths.
struct Wire;

impl Write for Wire {
    fn write_str(&mut self, text: &str) -> fmt::Result {
        send_bytes(text.as_bytes()).map_err(|Stalled| fmt::Error)
    }
}
