//! The IDT and the interrupt controllers.
//!
//! CPU faults (breakpoint, page fault, general protection fault, double
//! fault on its own stack, see `gdt.rs`) report what happened in a `FATAL`
//! frame and end the run (`fatal.rs`): the harness provokes them with
//! `FAULT` to prove that a kernel bug is reported, never silent.
//!
//! One hardware interrupt is used: COM1's IRQ 4, whose handler moves the
//! received bytes into `serial`'s ring buffer. The BIOS leaves the master
//! 8259 PIC on vectors 8-15, the CPU's own exception vectors (IRQ 0 would
//! look like a double fault), so both PICs are moved to 0x20-0x2F first,
//! and every IRQ but 4 is masked: the PIT, the keyboard and the VGA are
//! polled.

use spin::Lazy;
use x86_64::registers::control::Cr2;
use x86_64::structures::idt::{InterruptDescriptorTable, InterruptStackFrame, PageFaultErrorCode};

use crate::fatal::fatal;
use crate::gdt::DOUBLE_FAULT_IST_INDEX;
use crate::port::pic;
use crate::serial;

/// Where the PICs' IRQs land: 0-7 from the master, 8-15 from the slave,
/// just past the 32 vectors the CPU reserves for exceptions.
const MASTER_VECTORS: u8 = 0x20;
const SLAVE_VECTORS: u8 = MASTER_VECTORS + 8;
/// COM1's IRQ line.
const COM1_IRQ: u8 = 4;
const COM1_VECTOR: u8 = MASTER_VECTORS + COM1_IRQ;
/// The vector of the master's IRQ 7, which it also raises for an interrupt
/// that went away before the CPU took it (a spurious one).
const MASTER_SPURIOUS_VECTOR: u8 = MASTER_VECTORS + 7;

/// Initialisation command word 1: start initialising, ICW4 follows,
/// cascaded, edge triggered.
const ICW1_INIT_WITH_ICW4: u8 = 0x11;
/// ICW3: the master has the slave on IRQ 2; the slave's cascade identity.
const ICW3_SLAVE_ON_IRQ2: u8 = 1 << 2;
const ICW3_CASCADE_IDENTITY: u8 = 2;
/// ICW4: 8086 mode, normal end of interrupt.
const ICW4_8086: u8 = 0x01;
/// Interrupt mask registers: a set bit masks that IRQ. The master passes
/// IRQ 4 only; the slave (and the cascade to it) nothing.
const MASTER_MASK: u8 = !(1 << COM1_IRQ);
const SLAVE_MASK: u8 = 0xFF;
/// Operation command word 2: non-specific end of interrupt.
const END_OF_INTERRUPT: u8 = 0x20;

static IDT: Lazy<InterruptDescriptorTable> = Lazy::new(|| {
    let mut idt = InterruptDescriptorTable::new();
    idt.breakpoint.set_handler_fn(breakpoint);
    idt.page_fault.set_handler_fn(page_fault);
    idt.general_protection_fault.set_handler_fn(general_protection_fault);
    let double_fault_entry = idt.double_fault.set_handler_fn(double_fault);
    // SAFETY: `gdt::init` loads a TSS whose IST slot
    // `DOUBLE_FAULT_IST_INDEX` holds a stack used for nothing else.
    unsafe { double_fault_entry.set_stack_index(DOUBLE_FAULT_IST_INDEX) };
    idt[COM1_VECTOR].set_handler_fn(com1_received);
    idt[MASTER_SPURIOUS_VECTOR].set_handler_fn(master_spurious);
    idt
});

/// Loads the IDT and moves and masks the PICs, with interrupts off; they
/// stay off until [`enable`]. Call after `gdt::init`, which sets up the
/// double-fault stack.
pub fn init() {
    x86_64::instructions::interrupts::disable();
    IDT.load();
    remap_pics();
}

/// Lets the unmasked IRQ (COM1's) in.
pub fn enable() {
    x86_64::instructions::interrupts::enable();
}

/// Puts the PICs' IRQs on [`MASTER_VECTORS`] and [`SLAVE_VECTORS`] and
/// masks all but COM1's. Initialising clears the masks, hence the order.
fn remap_pics() {
    pic::MASTER_COMMAND.write(ICW1_INIT_WITH_ICW4);
    pic::SLAVE_COMMAND.write(ICW1_INIT_WITH_ICW4);
    pic::MASTER_DATA.write(MASTER_VECTORS);
    pic::SLAVE_DATA.write(SLAVE_VECTORS);
    pic::MASTER_DATA.write(ICW3_SLAVE_ON_IRQ2);
    pic::SLAVE_DATA.write(ICW3_CASCADE_IDENTITY);
    pic::MASTER_DATA.write(ICW4_8086);
    pic::SLAVE_DATA.write(ICW4_8086);
    pic::MASTER_DATA.write(MASTER_MASK);
    pic::SLAVE_DATA.write(SLAVE_MASK);
}

extern "x86-interrupt" fn com1_received(_frame: InterruptStackFrame) {
    serial::receive_waiting_bytes();
    pic::MASTER_COMMAND.write(END_OF_INTERRUPT);
}

/// IRQ 7 is masked, so anything on its vector is spurious: the master has
/// not marked it in service, and must not be sent an end of interrupt.
extern "x86-interrupt" fn master_spurious(_frame: InterruptStackFrame) {}

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
