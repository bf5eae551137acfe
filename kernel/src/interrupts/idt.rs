//! The IDT: every one of the 256 vectors has a handler.
//!
//! - Every exception the CPU can raise (vectors 0 to 31; the ones the
//!   architecture reserves, 15, 22 to 27 and 31, are never raised) is
//!   reported, by name, in a `FATAL` frame and ends the run (`fatal.rs`),
//!   so a kernel bug is reported, never silent and never mistaken for
//!   another. The harness provokes some with `FAULT`. The double fault
//!   runs on a stack of its own (`gdt.rs`). A machine check is fatal too.
//! - A non-maskable interrupt is not an error of the kernel's: a chipset
//!   reports a PCI system error (SERR#) or an I/O channel check (IOCHK#)
//!   with one, a BMC sends one to ask for a diagnosis, a TCO watchdog on
//!   its first expiry. The handler reads why from port 0x61 (bits 7 and
//!   6), clears what it read (bits 2 and 3 set, then cleared again, as
//!   Linux does), counts it and returns: the show plays on.
//! - COM1's IRQ 4 moves the received bytes into `serial`'s ring buffer,
//!   and the PIT's IRQ 0 wakes a halt (`pic.rs`). Each is ended wherever
//!   it is in service: at the 8259 that raised it, or at the local APIC
//!   where its vector came through it (an I/O APIC entry the firmware left
//!   live, a self-IPI): ended at the 8259 alone, it would stay in service
//!   at the local APIC and hold back its priority class for good.
//! - Every other vector, 0x20 to 0xFF, is one the kernel did not ask for:
//!   an LVT entry of the local APIC the firmware left live (thermal,
//!   CMCI, error, performance counter), its spurious vector, an unmasked
//!   I/O APIC entry, a spurious 8259 IRQ. Each is counted and returns,
//!   after an end of interrupt where the local APIC or a PIC has it in
//!   service (`apic.rs`, `pic.rs`): left in service, it would block every
//!   interrupt of its priority or below. A vector that storms (comes again
//!   at once after each end, unbounded) is masked at its source
//!   (`storm.rs`).
//!
//! Handlers only count (atomics, nothing else is safe to touch from an
//! NMI): [`report`], from the show's frames and the server, sends a
//! `LOG` frame per NMI and per vector that came again since, and `PING`
//! tells the totals ([`counts`]).

use core::sync::atomic::{AtomicU32, AtomicU8, Ordering};

use protocol::{EndedAt, FatalReport, InterruptCounts, LogEvent, PageFaultCode, PAGE_FAULT_VECTOR};
use spin::Lazy;
use x86_64::registers::control::Cr2;
use x86_64::set_general_handler;
use x86_64::structures::idt::{InterruptDescriptorTable, InterruptStackFrame};

use crate::interrupts::fatal::fatal;
use crate::interrupts::gdt::DOUBLE_FAULT_IST_INDEX;
use crate::interrupts::{apic, pic, storm};
use crate::platform::port::system_control;
use crate::wire::serial;

/// The exceptions: vectors 0 to 31.
const EXCEPTIONS: core::ops::Range<u8> = 0..32;
/// The rest: interrupts.
const INTERRUPTS: core::ops::RangeInclusive<u8> = 32..=255;

/// Port 0x61 (system control port B) bits: read, the NMI's reasons; written,
/// the latches that clear them (and mask them while set).
const SERR: u8 = 1 << 7;
const IOCHK: u8 = 1 << 6;
const CLEAR_SERR: u8 = 1 << 2;
const CLEAR_IOCHK: u8 = 1 << 3;
/// The bits of port 0x61 that read back what was written (timer 2 gate,
/// speaker data, the two latches).
const WRITABLE: u8 = 0x0F;

/// Stray interrupts by vector, and what ended each vector's last one
/// (`ENDED_BY_*` bits); NMIs and the port 0x61 value the last one read.
static STRAY: [AtomicU32; 256] = [const { AtomicU32::new(0) }; 256];
static ENDED_BY: [AtomicU8; 256] = [const { AtomicU8::new(0) }; 256];
const ENDED_BY_APIC: u8 = 1;
const ENDED_BY_PIC: u8 = 2;
static NMIS: AtomicU32 = AtomicU32::new(0);
static NMI_REASON: AtomicU8 = AtomicU8::new(0);
/// The counts [`report`] has told of, touched by the main flow only.
static REPORTED_STRAY: [AtomicU32; 256] = [const { AtomicU32::new(0) }; 256];
static REPORTED_NMIS: AtomicU32 = AtomicU32::new(0);

static IDT: Lazy<InterruptDescriptorTable> = Lazy::new(|| {
    let mut idt = InterruptDescriptorTable::new();
    set_general_handler!(&mut idt, exception, EXCEPTIONS);
    set_general_handler!(&mut idt, stray_interrupt, INTERRUPTS);
    // Replace general ones: the double fault needs its own stack.
    let double_fault_entry = idt.double_fault.set_handler_fn(double_fault);
    // SAFETY: `gdt::init` loads a TSS whose IST slot
    // `DOUBLE_FAULT_IST_INDEX` holds a stack used for nothing else.
    unsafe { double_fault_entry.set_stack_index(DOUBLE_FAULT_IST_INDEX) };
    idt.non_maskable_interrupt.set_handler_fn(non_maskable_interrupt);
    idt[pic::TIMER_VECTOR].set_handler_fn(timer_tick);
    idt[pic::COM1_VECTOR].set_handler_fn(com1_received);
    idt
});

/// Loads the IDT and moves and masks the PICs, with interrupts off; they
/// stay off until [`enable`]. Call after `gdt::init`, which sets up the
/// double-fault stack.
pub fn init() {
    x86_64::instructions::interrupts::disable();
    IDT.load();
    pic::remap();
}

/// Lets the unmasked IRQ (COM1's) in.
pub fn enable() {
    x86_64::instructions::interrupts::enable();
}

extern "x86-interrupt" fn timer_tick(_frame: InterruptStackFrame) {
    pic::on_timer_tick();
    end_interrupt(pic::TIMER_VECTOR);
}

extern "x86-interrupt" fn com1_received(_frame: InterruptStackFrame) {
    serial::on_interrupt();
    end_interrupt(pic::COM1_VECTOR);
}

/// Ends the interrupt on `vector` wherever it is in service: the local
/// APIC, an 8259, both or neither; says where, as `ENDED_BY_*` bits.
fn end_interrupt(vector: u8) -> u8 {
    (if apic::end_if_in_service(vector) { ENDED_BY_APIC } else { 0 })
        | (if pic::end_if_in_service(vector) { ENDED_BY_PIC } else { 0 })
}

/// Reads port 0x61 for the reason, clears the latch of each reason
/// found, counts, and returns to whatever it interrupted.
extern "x86-interrupt" fn non_maskable_interrupt(_frame: InterruptStackFrame) {
    let reason = system_control::PORT_B.read();
    let latches =
        (if reason & SERR != 0 { CLEAR_SERR } else { 0 }) | (if reason & IOCHK != 0 { CLEAR_IOCHK } else { 0 });
    if latches != 0 {
        system_control::PORT_B.write(reason & WRITABLE | latches);
        system_control::PORT_B.write(reason & WRITABLE & !latches);
    }
    NMI_REASON.store(reason, Ordering::Relaxed);
    NMIS.fetch_add(1, Ordering::Release);
}

/// A vector from 0x20 to 0xFF that nothing asked for: counted, ended
/// where it is in service, and returned from.
fn stray_interrupt(_frame: InterruptStackFrame, vector: u8, _error: Option<u64>) {
    storm::guard(vector);
    let ended = end_interrupt(vector);
    ENDED_BY[usize::from(vector)].store(ended, Ordering::Relaxed);
    STRAY[usize::from(vector)].fetch_add(1, Ordering::Release);
}

/// Every exception but the double fault and the NMI: reports it by name
/// and ends the run.
fn exception(frame: InterruptStackFrame, vector: u8, error: Option<u64>) {
    let at = frame.instruction_pointer.as_u64();
    match (vector, error) {
        // CR2 holds the address whose access faulted.
        (PAGE_FAULT_VECTOR, Some(code)) => {
            fatal(FatalReport::PageFault { address: Cr2::read_raw(), code: PageFaultCode::new(code), at })
        }
        _ => fatal(FatalReport::Exception { vector, error, at }),
    }
}

extern "x86-interrupt" fn double_fault(frame: InterruptStackFrame, error: u64) -> ! {
    let (at, stack) = (frame.instruction_pointer.as_u64(), frame.stack_pointer.as_u64());
    fatal(FatalReport::DoubleFault { error, at, stack })
}

/// Stray interrupts taken on `vector` since boot.
pub fn stray_count(vector: u8) -> u32 {
    STRAY[usize::from(vector)].load(Ordering::Acquire)
}

/// NMIs and stray interrupts taken since boot, for `PING`.
pub fn counts() -> InterruptCounts {
    let stray = STRAY.iter().map(|count| count.load(Ordering::Acquire)).fold(0u32, u32::wrapping_add);
    InterruptCounts { nmis: NMIS.load(Ordering::Acquire), stray }
}

/// Sends a `LOG` frame for each NMI, and each vector's stray interrupts,
/// taken since the last call: `NMI 1 (port 0x61 = 0x20: no SERR#, no
/// IOCHK#); the kernel carries on` or `stray interrupt: vector 0x99, 2 so
/// far, ended at the local APIC; returned`. Call from the main flow only.
pub fn report() {
    storm::report();
    let nmis = NMIS.load(Ordering::Acquire);
    if REPORTED_NMIS.swap(nmis, Ordering::Relaxed) != nmis {
        let reason = NMI_REASON.load(Ordering::Relaxed);
        serial::send_log(LogEvent::Nmi { count: nmis, reason, serr: reason & SERR != 0, iochk: reason & IOCHK != 0 });
    }
    for (vector, (count, reported)) in (0..=u8::MAX).zip(STRAY.iter().zip(&REPORTED_STRAY)) {
        let count = count.load(Ordering::Acquire);
        if reported.swap(count, Ordering::Relaxed) != count {
            let ended = ENDED_BY[usize::from(vector)].load(Ordering::Relaxed);
            let ended = EndedAt::of(ended & ENDED_BY_APIC != 0, ended & ENDED_BY_PIC != 0);
            serial::send_log(LogEvent::StrayInterrupt { vector, count, ended });
        }
    }
}
