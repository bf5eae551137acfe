//! The test-only `FAULT` command: provokes each kind of fault for real, so
//! the harness can prove that the handlers in `interrupts.rs` and the
//! panic handler report it, by its name, and exit QEMU with the failure
//! code; and raises a stray interrupt, which the kernel must survive.
//! Answered only on QEMU (`server.rs`).

use core::arch::asm;
use core::hint::black_box;

use protocol::{Fatal, FaultKind, Raised, StrayRaised};

use crate::clock::Deadline;
use crate::fatal::fatal;
use crate::{apic, interrupts};

/// An address no page maps: level-4 entry 27 of the lower half. The
/// bootloader hands out level-4 entries from index 0 up (no ASLR in our
/// config) and uses a handful, for the kernel, its stack, the boot info
/// and the physical-memory map.
const UNMAPPED_ADDRESS: u64 = 0xdeadbeef000;

/// Each frame of `overflow_stack` holds this many `u64`s (512 bytes), so
/// the 80 KiB kernel stack runs out after some 160 calls.
const FRAME_WORDS: usize = 64;

/// The vector `FAULT strayinterrupt` raises: in the local APIC's priority
/// class 9, which nothing on a PC is set up to use while this kernel
/// runs.
const STRAY_VECTOR: u8 = 0x99;
/// Longest wait for the local APIC to deliver it.
const DELIVERY_TIMEOUT_MICROS: u64 = 100_000;

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
        FaultKind::StrayInterrupt => return raise_stray_interrupt(),
    }
    fatal(Fatal::HandlerReturned(kind))
}

/// Raises [`STRAY_VECTOR`] as a device would, through the local APIC (a
/// self-IPI, which the APIC then has in service until its end of
/// interrupt), and waits for it to be taken; with no local APIC, by
/// `int`. Call with interrupts on (the server runs so).
fn raise_stray_interrupt() -> StrayRaised {
    let before = interrupts::stray_count(STRAY_VECTOR);
    let raised = if apic::send_to_self(STRAY_VECTOR) {
        Raised::LocalApic
    } else {
        // SAFETY: `int` calls the vector's handler on this stack (the
        // kernel's target has no red zone to clobber), which counts and
        // returns; it touches no Rust object.
        unsafe { asm!("int {vector}", vector = const STRAY_VECTOR) };
        Raised::Int
    };
    let give_up = Deadline::after_micros(DELIVERY_TIMEOUT_MICROS);
    while interrupts::stray_count(STRAY_VECTOR) == before && !give_up.passed() {
        core::hint::spin_loop();
    }
    StrayRaised { vector: STRAY_VECTOR, raised, taken: interrupts::stray_count(STRAY_VECTOR) }
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
