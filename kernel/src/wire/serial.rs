//! COM1, the protocol channel (kernel/protocol): frames out, command bytes
//! in, through the `uart_16550` crate's driver. Sending polls the UART.
//! Receiving moves every waiting byte into a ring buffer, so bytes
//! arriving while the demo draws a frame or the server answers a command
//! are kept (the UART's own FIFO holds only 16, about 1.4 ms at 115200
//! baud): from IRQ 4's handler (`idt.rs`), and by polling wherever
//! the kernel waits ([`poll`]: the demo's frame pacing, the retrace, the
//! transmitter, [`read_byte`]) or works for long (between a benchmark's
//! draws, while a framebuffer is filled). The interrupt is a speed-up: a
//! UEFI firmware need not route IRQ 4 to the CPU (the local APIC's LINT0,
//! a Super I/O set to another IRQ), and where it never arrives the kernel
//! still hears the host, by polling alone ([`interrupt_arrives`]).
//!
//! What is lost anyway is counted ([`losses`]): overrun errors the UART
//! reports in its line status (a byte arrived with its FIFO full), bytes
//! that found the ring full, and bytes received with a line error (a
//! break, a framing or a parity error: a cable plugged in, an adapter
//! powering up, a speed mismatch), which are dropped rather than taken
//! for command bytes. Reading the line status clears its error bits; the
//! driver keeps the error bits of its own reads and hands them out with
//! the next `lsr()`, which is where they are counted.
//!
//! A PC may have no COM1 at all. The driver's presence check (the scratch
//! register holds what is written to it; an absent port reads 0xFF) needs
//! no timing, so it answers the same on a PC and under any emulator. With
//! no COM1 nothing is set up: frames go nowhere and no byte ever arrives,
//! so the demo runs on. Every wait on the UART ends by the clock.

use alloc::string::ToString;
use core::fmt::{self, Write};
use core::hint::spin_loop;
use core::sync::atomic::{AtomicBool, AtomicU32, AtomicU8, AtomicUsize, Ordering};

use protocol::{FrameHeader, FrameKind, LineErrors, LineLosses, LogEvent};
use spin::Mutex;
use uart_16550::backend::PioBackend;
use uart_16550::spec::registers::{FifoTriggerLevel, IER, LSR};
use uart_16550::{BaudRate, Config, Uart16550};
use x86_64::instructions::interrupts;

use crate::platform::port;
use crate::time::clock::Deadline;

/// Longest wait for room in the transmitter before the rest of a frame is
/// given up: 16 bytes take 1.4 ms at 115200 baud, but under QEMU the
/// transmitter waits for the host to read its end of the line, which a
/// loaded host may not do for a while. A host that resynchronises on the
/// next frame header loses one frame, never the kernel.
const SEND_TIMEOUT_MICROS: u64 = 2_000_000;

/// Longest wait at boot for the transmitter to send what a previous owner
/// (a firmware's console) left in it: 16 characters take 133 ms at 1200
/// baud. A transmitter that never empties (a BMC's virtual UART, a
/// serial-over-LAN session that stalls) leaves COM1 unused.
const DRAIN_TIMEOUT_MICROS: u64 = 250_000;

/// Longest wait at boot for the interrupt the UART raises at once when
/// its transmitter-empty interrupt is enabled with the transmitter empty.
const INTERRUPT_TIMEOUT_MICROS: u64 = 10_000;

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
/// Whether COM1's interrupt has reached the CPU at least once.
static INTERRUPT_SEEN: AtomicBool = AtomicBool::new(false);
/// Serialises senders: a frame goes out whole.
static SENDING: Mutex<()> = Mutex::new(());
static OVERRUNS: AtomicU32 = AtomicU32::new(0);
static DROPPED: AtomicU32 = AtomicU32::new(0);
static FRAMING_ERRORS: AtomicU32 = AtomicU32::new(0);
static PARITY_ERRORS: AtomicU32 = AtomicU32::new(0);
static BREAKS: AtomicU32 = AtomicU32::new(0);

/// Received bytes, put by [`receive_into_ring`] and taken by
/// [`take_from_ring`]. Both sides run on the one CPU, the putting side
/// with interrupts off (in the interrupt handler, or polling with
/// interrupts off), so they never interleave within a side: `RING_HEAD`
/// (bytes taken) only ever chases `RING_TAIL` (bytes put), both counting
/// up and wrapping, and each side publishes its count with release after
/// touching the slots.
static RING: [AtomicU8; RING_LEN] = [const { AtomicU8::new(0) }; RING_LEN];
static RING_HEAD: AtomicUsize = AtomicUsize::new(0);
static RING_TAIL: AtomicUsize = AtomicUsize::new(0);

/// Sets COM1 to 115200 baud 8-N-1 with FIFOs (receive interrupt after 8
/// bytes, leaving 8 bytes of room for the handler to get there), if there
/// is a COM1, its interrupts still off ([`enable_interrupt`] turns them
/// on once the IDT and the PIC are ready). The bootloader's own serial
/// logging is off (boot/src/main.rs), so the line is ours alone. QEMU
/// ignores the speed; on a real PC the host's terminal must match it.
///
/// The driver's `init` ends by waiting, with no bound, for the
/// transmitter to empty. So the driver's own presence check comes first,
/// then a wait of the kernel's, bounded by [`DRAIN_TIMEOUT_MICROS`], on
/// the driver's line status; `init` runs only once the transmitter is
/// empty, when its own wait ends at once.
pub fn init() {
    let mut uart = port::com1();
    if !uart.check_present() {
        return;
    }
    let give_up = Deadline::after_micros(DRAIN_TIMEOUT_MICROS);
    while !uart.lsr().contains(LSR::TRANSMITTER_EMPTY) {
        if give_up.passed() {
            return;
        }
        spin_loop();
    }
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

/// Lets COM1 raise IRQ 4 when bytes arrive (if there is a COM1), and
/// once at once: its transmitter is empty, so enabling the
/// transmitter-empty interrupt raises one straight away, whose arrival
/// [`interrupt_arrives`] then waits for.
pub fn enable_interrupt() {
    with_com1(|uart| uart.enable_interrupts(IER::DATA_READY | IER::THR_EMPTY));
}

/// Whether COM1's interrupt reaches the CPU: waits (a bounded time, with
/// interrupts on) for the one [`enable_interrupt`] provoked. Where it does
/// not arrive, receiving is by polling alone. `false` with no COM1.
pub fn interrupt_arrives() -> bool {
    let give_up = Deadline::after_micros(INTERRUPT_TIMEOUT_MICROS);
    while PRESENT.load(Ordering::Acquire) && !INTERRUPT_SEEN.load(Ordering::Acquire) && !give_up.passed() {
        spin_loop();
    }
    if !INTERRUPT_SEEN.load(Ordering::Acquire) {
        with_com1(|uart| uart.disable_interrupts(IER::THR_EMPTY));
    }
    INTERRUPT_SEEN.load(Ordering::Acquire)
}

/// Runs `work` on COM1's driver with interrupts off; nothing where there
/// is no COM1.
fn with_com1<R: Default>(work: impl FnOnce(&mut Uart16550<PioBackend>) -> R) -> R {
    interrupts::without_interrupts(|| COM1.lock().as_mut().map(work).unwrap_or_default())
}

/// The IRQ 4 handler's work: notes that the interrupt arrives, turns the
/// test interrupt of [`enable_interrupt`] off, and moves every waiting
/// byte into the ring. Runs with interrupts off.
pub fn on_interrupt() {
    INTERRUPT_SEEN.store(true, Ordering::Release);
    let mut com1 = COM1.lock();
    let Some(uart) = com1.as_mut() else { return };
    if uart.config().interrupts.contains(IER::THR_EMPTY) {
        uart.disable_interrupts(IER::THR_EMPTY);
    }
    receive_into_ring(uart);
}

/// Moves every byte waiting in the UART into the ring, as the interrupt
/// handler does: the receiving half of every wait.
pub fn poll() {
    with_com1(receive_into_ring);
}

/// Moves every waiting byte from the UART into the ring, dropping (and
/// counting) those received with a line error and those that find the
/// ring full, and counting overruns. The line status read before each
/// byte describes that byte, the one at the head of the receive FIFO
/// (16550 data sheets: its error bits are revealed when it reaches the
/// head), together with the error bits the driver's own reads saw since
/// the last `lsr()`, which this function alone calls: those belong to
/// the same byte, since only this function takes bytes out.
fn receive_into_ring(uart: &mut Uart16550<PioBackend>) {
    loop {
        let status = uart.lsr();
        if status.contains(LSR::OVERRUN_ERROR) {
            OVERRUNS.fetch_add(1, Ordering::Relaxed);
        }
        if !status.contains(LSR::DATA_READY) {
            return;
        }
        let Ok(byte) = uart.try_receive_byte() else { return };
        let error = if status.contains(LSR::BREAK_INTERRUPT) {
            Some(&BREAKS)
        } else if status.contains(LSR::FRAMING_ERROR) {
            Some(&FRAMING_ERRORS)
        } else if status.contains(LSR::PARITY_ERROR) {
            Some(&PARITY_ERRORS)
        } else {
            None
        };
        if let Some(count) = error {
            count.fetch_add(1, Ordering::Relaxed);
            continue;
        }
        let tail = RING_TAIL.load(Ordering::Relaxed);
        if tail.wrapping_sub(RING_HEAD.load(Ordering::Acquire)) == RING_LEN {
            DROPPED.fetch_add(1, Ordering::Relaxed);
            continue;
        }
        RING[tail % RING_LEN].store(byte, Ordering::Relaxed);
        RING_TAIL.store(tail.wrapping_add(1), Ordering::Release);
    }
}

/// The next byte from the ring, if there is one.
fn take_from_ring() -> Option<u8> {
    let head = RING_HEAD.load(Ordering::Relaxed);
    if head == RING_TAIL.load(Ordering::Acquire) {
        return None;
    }
    let byte = RING[head % RING_LEN].load(Ordering::Relaxed);
    RING_HEAD.store(head.wrapping_add(1), Ordering::Release);
    Some(byte)
}

/// The next byte from the host, if one has arrived (polling the UART
/// first).
pub fn try_read_byte() -> Option<u8> {
    poll();
    take_from_ring()
}

/// The next byte from the host, waiting for it until `until` (for ever
/// with `None`); `None` if the deadline passed first. The UART is polled
/// at every turn. Where COM1's interrupt is known to arrive and the
/// caller has a `halt` that is sure to end (the server passes
/// `pic::halt_until_interrupt` where the PIT's tick is known to arrive),
/// the CPU halts between turns until an interrupt (the UART's, or the
/// PIT's tick, let in while it halts), so a lost interrupt delays a byte
/// by one tick at most; elsewhere it polls without pause, which keeps up
/// with a FIFO of 16 bytes at 115200 baud, and a halt that nothing might
/// end never happens. `halt` is called with interrupts off and returns
/// with them off.
pub fn read_byte(until: Option<Deadline>, halt: Option<impl Fn()>) -> Option<u8> {
    loop {
        // With interrupts off between the look and the `hlt` (`sti; hlt`
        // opens them only as the CPU halts), a byte cannot slip in
        // unnoticed in between.
        interrupts::disable();
        if PRESENT.load(Ordering::Acquire) {
            receive_into_ring(COM1.lock().as_mut().expect("COM1 is present"));
        }
        let byte = take_from_ring();
        if byte.is_some() || until.is_some_and(Deadline::passed) {
            interrupts::enable();
            return byte;
        }
        if let Some(halt) = halt.as_ref().filter(|_| INTERRUPT_SEEN.load(Ordering::Acquire)) {
            halt();
        }
        interrupts::enable();
        spin_loop();
    }
}

/// What the line has lost on the way in since boot (polling first, so
/// that the counts include the bytes waiting now).
pub fn losses() -> LineLosses {
    poll();
    let count = |counter: &AtomicU32| counter.load(Ordering::Relaxed);
    LineLosses {
        overruns: count(&OVERRUNS),
        dropped: count(&DROPPED),
        errors: Some(LineErrors {
            framing: count(&FRAMING_ERRORS),
            parity: count(&PARITY_ERRORS),
            breaks: count(&BREAKS),
        }),
    }
}

/// Sends one frame: header line, payload, `\n` (kernel/protocol/src/lib.rs).
pub fn send_frame(kind: FrameKind, payload: &[u8]) {
    send_reply(kind, None, payload);
}

/// Sends a `LOG` frame telling `event`.
pub fn send_log(event: LogEvent) {
    send_frame(FrameKind::Log, event.to_string().as_bytes());
}

/// Sends the frame answering a command line, its header echoing the
/// line's sequence number if the line was sealed (`protocol::Sealed`).
pub fn send_reply(kind: FrameKind, seq: Option<u32>, payload: &[u8]) {
    if PRESENT.load(Ordering::Acquire) {
        let _sending = SENDING.lock();
        write_frame(FrameHeader::for_reply(kind, payload, seq), payload);
    }
}

/// Sends a `FATAL` frame from a fault, NMI or panic handler. Interrupts
/// are off and there is one CPU, so if a frame is being sent, or COM1's
/// driver is in use (the kernel polls it all the time, so an NMI often
/// lands there), the one using it is the code this fault interrupted,
/// which never runs again: the frame goes out without waiting for it (it
/// may then land inside a half-sent one; the host resynchronises on the
/// next header). Should the driver itself fault while sending, the
/// second fatal error exits without a report (`fatal.rs`); the exit
/// status still says the run failed.
pub fn send_fatal(payload: &[u8]) {
    if !PRESENT.load(Ordering::Acquire) {
        return;
    }
    if COM1.is_locked() {
        // SAFETY: the lock's holder is the code this handler interrupted
        // on the one CPU, and `fatal` never returns to it, so from now on
        // nothing else uses the driver. What the holder left half done
        // leaves the UART usable: every step of the driver is a single
        // access to one of its registers.
        unsafe { COM1.force_unlock() };
    }
    write_frame(FrameHeader::for_payload(FrameKind::Fatal, payload), payload);
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
            let sent = with_com1(|uart| {
                receive_into_ring(uart);
                uart.send_bytes(bytes)
            });
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
