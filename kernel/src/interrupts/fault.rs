//! The test-only `FAULT` command: provokes each kind of fault for real, so
//! the harness can prove that the handlers in `idt.rs` and the
//! panic handler report it, by its name, and exit QEMU with the failure
//! code; and raises stray interrupts, which the kernel must survive: on a
//! vector through the local APIC, a device's IRQ through the 8259s, and a
//! level-triggered storm through the I/O APIC. Answered only on QEMU
//! (`server/commands.rs`).

use core::arch::asm;
use core::hint::black_box;

use protocol::{FatalReport, FaultKind, Raised, StrayRaised, STORM_VECTOR, STRAY_VECTOR};

use crate::interrupts::fatal::fatal;
use crate::interrupts::{apic, idt, ioapic, pic, storm};
use crate::time::clock::Deadline;
use crate::time::rtc;

/// An address no page maps: level-4 entry 27 of the lower half. The
/// bootloader hands out level-4 entries from index 0 up (no ASLR in our
/// config) and uses a handful, for the kernel, its stack, the boot info
/// and the physical-memory map.
const UNMAPPED_ADDRESS: u64 = 0xdeadbeef000;

/// Each frame of `overflow_stack` holds this many `u64`s (512 bytes), so
/// the 80 KiB kernel stack runs out after some 160 calls.
const FRAME_WORDS: usize = 64;

/// Longest wait for a stray interrupt to arrive: the local APIC's
/// delivery, or the RTC's next periodic interrupt (1 ms apart).
const DELIVERY_TIMEOUT_MICROS: u64 = 100_000;
/// Where the RTC's IRQ 8 lands through the 8259s: the slave's first vector.
const RTC_PIC_VECTOR: u8 = pic::MASTER_VECTORS + 8;
/// Longest wait for the storm guard to stop a storm (`storm.rs`: 1,000
/// arrivals within 100 ms).
const STORM_TIMEOUT_MICROS: u64 = 2_000_000;

/// Provokes `kind`. A fault's handler ends the run; should one ever
/// return, the run ends here, reported all the same. A stray interrupt
/// is survived: the answer says how it was raised and how many the
/// kernel has taken on its vector.
pub fn provoke(kind: FaultKind) -> StrayRaised {
    match kind {
        FaultKind::DivideError => {
            black_box(divide_by_zero());
        }
        // SAFETY: `ud2`, the opcode made to be undefined, touches
        // nothing; the invalid opcode handler never returns, so the asm
        // block never completes.
        FaultKind::InvalidOpcode => unsafe { asm!("ud2", options(nomem, nostack, noreturn)) },
        FaultKind::Breakpoint => x86_64::instructions::interrupts::int3(),
        FaultKind::PageFault => {
            black_box(read_unmapped());
        }
        FaultKind::DoubleFault => {
            black_box(overflow_stack(0));
        }
        FaultKind::Panic => panic!("FAULT panic: the host asked for it"),
        FaultKind::StrayInterrupt(vector) => return raise_stray_interrupt(vector),
        FaultKind::StrayIrq => return raise_through_the_pics(),
        FaultKind::InterruptStorm => return raise_a_storm(),
    }
    fatal(FatalReport::HandlerReturned(kind))
}

/// Raises `vector` as a device would, through the local APIC (a self-IPI,
/// which the APIC then has in service until its end of interrupt), and
/// waits for it to be taken; with no local APIC, by `int` for
/// [`STRAY_VECTOR`] alone. Call with interrupts on (the server runs so).
fn raise_stray_interrupt(vector: u8) -> StrayRaised {
    let before = idt::stray_count(vector);
    let raised = if apic::send_to_self(vector) {
        Raised::LocalApic
    } else if vector == STRAY_VECTOR {
        // SAFETY: `int` calls the vector's handler on this stack (the
        // kernel's target has no red zone to clobber), which counts and
        // returns; it touches no Rust object.
        unsafe { asm!("int {vector}", vector = const STRAY_VECTOR) };
        Raised::Int
    } else {
        Raised::NotRaised
    };
    wait_while(|| idt::stray_count(vector) == before, DELIVERY_TIMEOUT_MICROS);
    StrayRaised { vector, raised, taken: idt::stray_count(vector) }
}

/// Lets one periodic interrupt of the RTC through the two 8259s (IRQ 8 on
/// the slave, cascaded on the master's IRQ 2: the vector ends at both),
/// and waits for it to be taken; then stops the RTC and masks its IRQ.
fn raise_through_the_pics() -> StrayRaised {
    let before = idt::stray_count(RTC_PIC_VECTOR);
    // IRQ 8 low first: the 8259s take an edge.
    rtc::acknowledge();
    pic::let_in_rtc(true);
    rtc::periodic(true);
    wait_while(|| idt::stray_count(RTC_PIC_VECTOR) == before, DELIVERY_TIMEOUT_MICROS);
    rtc::periodic(false);
    pic::let_in_rtc(false);
    rtc::acknowledge();
    StrayRaised { vector: RTC_PIC_VECTOR, raised: Raised::Pic, taken: idt::stray_count(RTC_PIC_VECTOR) }
}

/// Routes the RTC's IRQ 8 level-triggered through the I/O APIC to
/// [`STORM_VECTOR`] and starts its periodic interrupt without ever reading
/// register C: its line stays high, so each end of interrupt brings the
/// vector again at once, until the storm guard masks the entry
/// (`storm.rs`). Then the RTC is stopped and the entry put back.
fn raise_a_storm() -> StrayRaised {
    let routed = apic::id().and_then(|apic_id| ioapic::route_rtc_level(STORM_VECTOR, apic_id));
    let Some(routed) = routed else {
        let taken = idt::stray_count(STORM_VECTOR);
        return StrayRaised { vector: STORM_VECTOR, raised: Raised::NotRaised, taken };
    };
    rtc::acknowledge();
    rtc::periodic(true);
    wait_while(|| !storm::masked(STORM_VECTOR), STORM_TIMEOUT_MICROS);
    rtc::periodic(false);
    rtc::acknowledge();
    ioapic::restore(routed);
    StrayRaised { vector: STORM_VECTOR, raised: Raised::IoApicLevel, taken: idt::stray_count(STORM_VECTOR) }
}

/// Spins while `waiting` holds, `micros` at the most.
fn wait_while(waiting: impl Fn() -> bool, micros: u64) {
    let give_up = Deadline::after_micros(micros);
    while waiting() && !give_up.passed() {
        core::hint::spin_loop();
    }
}

/// Divides by zero with `div`: a divide error. (In asm: Rust's `/` checks
/// for zero itself and panics instead.)
fn divide_by_zero() -> u32 {
    let quotient: u32;
    // SAFETY: the division touches only registers; it faults, and the
    // divide error handler never returns, so the asm block never
    // completes.
    unsafe {
        asm!(
            "div {divisor:e}",
            divisor = in(reg) 0u32,
            inout("eax") 1u32 => quotient,
            inout("edx") 0u32 => _,
            options(nomem, nostack),
        );
    }
    quotient
}

/// Reads [`UNMAPPED_ADDRESS`]: a page fault with CR2 set to it.
fn read_unmapped() -> u8 {
    let value: u8;
    // SAFETY: the load touches no Rust object; it faults, and the page
    // fault handler never returns, so the asm block never completes. (In
    // asm rather than `read_volatile`, which would be undefined behaviour
    // for an address where nothing lives.)
    unsafe {
        asm!(
            "mov {value}, byte ptr [{address}]",
            address = in(reg) UNMAPPED_ADDRESS,
            value = out(reg_byte) value,
            options(nostack, readonly, preserves_flags),
        );
    }
    value
}

/// Recurses until the kernel stack reaches its guard page. The page fault
/// there cannot be delivered on the same, exhausted stack, so the CPU
/// raises a double fault, which runs on the IST stack of `gdt.rs`: the
/// genuine article, and the reason the IST stack exists.
#[expect(unconditional_recursion, reason = "overflowing the stack is the point")]
fn overflow_stack(depth: u64) -> u64 {
    // `black_box` keeps the frame and the call: no tail call, no folding.
    let frame = black_box([depth; FRAME_WORDS]);
    overflow_stack(frame[0].wrapping_add(1)).wrapping_add(frame[FRAME_WORDS - 1])
}
