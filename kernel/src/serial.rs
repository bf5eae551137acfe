//! COM1, the protocol channel (kernel/protocol): frames out, command bytes
//! in. Sending polls the UART; receiving is by interrupt (IRQ 4, see
//! `interrupts.rs`) into a ring buffer, so bytes arriving while the demo
//! draws a frame or the console answers a command are kept: the UART's
//! own FIFO holds only 16, about 1.4 ms at 115200 baud.
//!
//! What is lost anyway is counted ([`losses`]): overrun errors the UART
//! reports in its line status (a byte arrived with its FIFO full) and
//! bytes that found the ring full. Every read of the line status goes
//! through [`line_status`], since reading it clears the overrun bit.
//!
//! A PC may have no COM1 at all. Then nothing is set up: frames go nowhere
//! and no byte ever arrives, so the demo runs on. Reading an absent UART
//! would return 0xFF, "data ready", and stop the demo for nothing.

use core::fmt::{self, Write};
use core::sync::atomic::{AtomicBool, AtomicU32, AtomicU8, AtomicUsize, Ordering};

use protocol::{FrameHeader, FrameKind, LineLosses};
use spin::Mutex;
use x86_64::instructions::interrupts;

use crate::port::com1;

/// Line control: 8 data bits, no parity, 1 stop bit.
const EIGHT_N_ONE: u8 = 0x03;
/// Line control bit 7: the first two ports are the baud divisor.
const DIVISOR_LATCH: u8 = 0x80;
/// 115200 baud: the UART's 1.8432 MHz clock / 16 / 1.
const DIVISOR_115200: u8 = 1;
/// FIFO control: enable and clear both FIFOs, interrupt once 8 bytes wait
/// (bits 7-6 = 10), leaving 8 bytes of room for the handler to get there.
const FIFOS_ON_TRIGGER_8: u8 = 0x87;
/// Modem control: DTR and RTS (a host may wait for them), OUT2, which on a
/// PC connects the UART's interrupt line to the PIC.
const DTR_RTS_OUT2: u8 = 0x0B;
/// Modem control bit 4: loopback, what is sent comes back in.
const LOOPBACK: u8 = 0x10;
/// Interrupt enable bit 0: received data available (and, with the FIFO on,
/// a character timeout when fewer bytes than the trigger wait).
const RECEIVED_DATA_INTERRUPT: u8 = 0x01;
/// Line status bits: a byte waits; an overrun error since the last read;
/// the transmit holding register is empty.
const DATA_READY: u8 = 0x01;
const OVERRUN_ERROR: u8 = 0x02;
const TRANSMIT_EMPTY: u8 = 0x20;
/// Sent and expected back in loopback to tell a UART from an empty port.
const LOOPBACK_PROBE: u8 = 0xAE;
/// Most line-status reads spent waiting for the probe to come back: it
/// takes one character time, 87 us at 115200 baud, and a port read at
/// least about 0.3 us.
const PROBE_MAX_READS: u32 = 4096;

/// Bytes the ring holds: a whole command line of `protocol::MAX_LINE` and
/// the commands a host sends behind it while a long answer (a 64 KB dump)
/// goes out.
const RING_LEN: usize = 16 * 1024;

/// Whether COM1 answered the loopback probe and is set up.
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

/// Sets COM1 to 115200 baud 8-N-1 with FIFOs, if there is a COM1, its
/// interrupt still off ([`enable_receive_interrupt`] turns it on once the
/// IDT and the PIC are ready for it). The bootloader's own serial logging
/// is off (boot/src/main.rs), so the line is ours alone. QEMU ignores the
/// speed; on a real PC the host's terminal must match it.
pub fn init() {
    com1::INTERRUPT_ENABLE.write(0);
    com1::LINE_CONTROL.write(DIVISOR_LATCH);
    com1::DATA.write(DIVISOR_115200);
    com1::INTERRUPT_ENABLE.write(0);
    com1::LINE_CONTROL.write(EIGHT_N_ONE);
    com1::FIFO_CONTROL.write(FIFOS_ON_TRIGGER_8);
    com1::MODEM_CONTROL.write(DTR_RTS_OUT2 | LOOPBACK);
    com1::DATA.write(LOOPBACK_PROBE);
    let arrived = (0..PROBE_MAX_READS).any(|_| line_status() & DATA_READY != 0);
    let echoed = arrived && com1::DATA.read() == LOOPBACK_PROBE;
    com1::MODEM_CONTROL.write(DTR_RTS_OUT2);
    // The probe may have left the overrun bit or a stray byte behind:
    // losses count from here.
    com1::FIFO_CONTROL.write(FIFOS_ON_TRIGGER_8);
    line_status();
    OVERRUNS.store(0, Ordering::Relaxed);
    PRESENT.store(echoed, Ordering::Release);
}

/// Lets COM1 raise IRQ 4 when bytes arrive (if there is a COM1).
pub fn enable_receive_interrupt() {
    if PRESENT.load(Ordering::Acquire) {
        com1::INTERRUPT_ENABLE.write(RECEIVED_DATA_INTERRUPT);
    }
}

/// Reads the line status, counting an overrun it reports: the one way
/// this kernel reads it, since the read clears the bit.
fn line_status() -> u8 {
    let status = com1::LINE_STATUS.read();
    if status & OVERRUN_ERROR != 0 {
        OVERRUNS.fetch_add(1, Ordering::Relaxed);
    }
    status
}

/// The IRQ 4 handler's work: moves every waiting byte from the UART into
/// the ring (counting those that find it full). Runs with interrupts off.
pub fn receive_waiting_bytes() {
    while line_status() & DATA_READY != 0 {
        let byte = com1::DATA.read();
        let tail = RING_TAIL.load(Ordering::Relaxed);
        if tail.wrapping_sub(RING_HEAD.load(Ordering::Acquire)) == RING_LEN {
            DROPPED.fetch_add(1, Ordering::Relaxed);
            continue;
        }
        RING[tail % RING_LEN].store(byte, Ordering::Relaxed);
        RING_TAIL.store(tail.wrapping_add(1), Ordering::Release);
    }
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
/// one. Never returns where there is no COM1.
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
    LineLosses { overruns: OVERRUNS.load(Ordering::Relaxed), dropped: DROPPED.load(Ordering::Relaxed) }
}

/// Sends one frame: header line, payload, `\n` (kernel/protocol/src/lib.rs).
pub fn send_frame(kind: FrameKind, payload: &[u8]) {
    if PRESENT.load(Ordering::Acquire) {
        let _sending = SENDING.lock();
        write_frame(kind, payload);
    }
}

/// Sends a `FATAL` frame from a fault or panic handler. Interrupts are off
/// and there is one CPU, so if a frame is being sent, its sender is the
/// code this fault interrupted, which never runs again: the frame goes out
/// without waiting for it (it may then land inside a half-sent one; the
/// host resynchronises on the next header).
pub fn send_fatal(payload: &[u8]) {
    if PRESENT.load(Ordering::Acquire) {
        write_frame(FrameKind::Fatal, payload);
    }
}

fn write_frame(kind: FrameKind, payload: &[u8]) {
    let header = FrameHeader::for_payload(kind, payload);
    // `Wire` never fails.
    let _ = writeln!(Wire, "{header}");
    send_bytes(payload);
    send_bytes(b"\n");
}

/// Sends `bytes` as they are, waiting for room before each.
fn send_bytes(bytes: &[u8]) {
    for &byte in bytes {
        while line_status() & TRANSMIT_EMPTY == 0 {
            core::hint::spin_loop();
        }
        com1::DATA.write(byte);
    }
}

/// `fmt::Write` straight to the UART, byte for byte: no `\n` to `\r\n`
/// translation, which would break the frame lengths.
struct Wire;

impl Write for Wire {
    fn write_str(&mut self, text: &str) -> fmt::Result {
        send_bytes(text.as_bytes());
        Ok(())
    }
}
