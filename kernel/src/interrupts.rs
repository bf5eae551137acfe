//! The IDT: breakpoint, page fault, general protection fault and double
//! fault (on its own stack, see `gdt.rs`). Each reports what happened in a
//! `FATAL` frame and ends the run (`fatal.rs`): the harness provokes them
//! with `FAULT` to prove that a kernel bug is reported, never silent.
//! Hardware interrupts stay disabled, so no other vector can fire.

use spin::Lazy;
use x86_64::registers::control::Cr2;
use x86_64::structures::idt::{InterruptDescriptorTable, InterruptStackFrame, PageFaultErrorCode};

use crate::fatal::fatal;
use crate::gdt::DOUBLE_FAULT_IST_INDEX;

static IDT: Lazy<InterruptDescriptorTable> = Lazy::new(|| {
    let mut idt = InterruptDescriptorTable::new();
    idt.breakpoint.set_handler_fn(breakpoint);
    idt.page_fault.set_handler_fn(page_fault);
    idt.general_protection_fault.set_handler_fn(general_protection_fault);
    let double_fault_entry = idt.double_fault.set_handler_fn(double_fault);
    // SAFETY: `gdt::init` loads a TSS whose IST slot
    // `DOUBLE_FAULT_IST_INDEX` holds a stack used for nothing else.
    unsafe { double_fault_entry.set_stack_index(DOUBLE_FAULT_IST_INDEX) };
    idt
});

/// Loads the IDT and keeps hardware interrupts off: everything here polls,
/// and the PIC is not remapped, so the timer's IRQ 0 would arrive as vector
/// 8, a "double fault". Call after `gdt::init`, which sets up the
/// double-fault stack.
pub fn init() {
    x86_64::instructions::interrupts::disable();
    IDT.load();
}

extern "x86-interrupt" fn breakpoint(frame: InterruptStackFrame) {
    fatal(format_args!("breakpoint at {:#x}", frame.instruction_pointer.as_u64()))
}

extern "x86-interrupt" fn page_fault(frame: InterruptStackFrame, error: PageFaultErrorCode) {
    // CR2 holds the address whose access faulted.
    let address = Cr2::read_raw();
    fatal(format_args!(
        "page fault at {address:#x} ({error:?}), instruction at {:#x}",
        frame.instruction_pointer.as_u64()
    ))
}

extern "x86-interrupt" fn general_protection_fault(frame: InterruptStackFrame, error: u64) {
    fatal(format_args!("general protection fault (error code {error:#x}) at {:#x}", frame.instruction_pointer.as_u64()))
}

extern "x86-interrupt" fn double_fault(frame: InterruptStackFrame, error: u64) -> ! {
    fatal(format_args!(
        "double fault (error code {error:#x}) at {:#x}, stack pointer {:#x}",
        frame.instruction_pointer.as_u64(),
        frame.stack_pointer.as_u64()
    ))
}
