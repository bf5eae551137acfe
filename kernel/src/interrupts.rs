//! The IDT and the interrupt controllers.
//!
//! Every exception vector the CPU can raise has a handler (the ones the
//! architecture reserves, 15, 22 to 27 and 31, are never raised): each
//! reports what happened, by name, in a `FATAL` frame and ends the run
//! (`fatal.rs`), so a kernel bug is reported, never silent and never
//! mistaken for another (a divide error without its own handler would
//! have become a double fault). The harness provokes some with `FAULT`.
//! The double fault runs on a stack of its own (`gdt.rs`). A non-maskable
//! interrupt is fatal too, except after the kernel has stopped for good
//! (`exit.rs`): the run ended cleanly, and the halt goes on.
//!
//! Two hardware interrupts are used. COM1's IRQ 4, whose handler moves
//! the received bytes into `serial`'s ring buffer: a speed-up only, since
//! the kernel also polls the UART wherever it waits, and does not rely on
//! the interrupt where it never arrives (`serial.rs`). And the PIT's IRQ 0,
//! let in only while the kernel halts waiting for a byte
//! ([`halt_until_interrupt`]), so that a halt ends within one tick (55 ms)
//! even if COM1's interrupt is lost. The BIOS leaves the master 8259 PIC
//! on vectors 8-15, the CPU's own exception vectors (IRQ 0 would look like
//! a double fault), so both PICs are moved to 0x20-0x2F first, and every
//! other IRQ is masked: the keyboard and the VGA are polled.

use spin::Lazy;
use x86_64::registers::control::Cr2;
use x86_64::set_general_handler;
use x86_64::structures::idt::{InterruptDescriptorTable, InterruptStackFrame, PageFaultErrorCode};

use crate::fatal::fatal;
use crate::gdt::DOUBLE_FAULT_IST_INDEX;
use crate::port::{io_delay, pic};
use crate::{exit, serial};

/// Where the PICs' IRQs land: 0-7 from the master, 8-15 from the slave,
/// just past the 32 vectors the CPU reserves for exceptions.
const MASTER_VECTORS: u8 = 0x20;
const SLAVE_VECTORS: u8 = MASTER_VECTORS + 8;
/// The PIT's IRQ line, and COM1's.
const TIMER_IRQ: u8 = 0;
const COM1_IRQ: u8 = 4;
const TIMER_VECTOR: u8 = MASTER_VECTORS + TIMER_IRQ;
const COM1_VECTOR: u8 = MASTER_VECTORS + COM1_IRQ;
/// The vector of the master's IRQ 7, which it also raises for an interrupt
/// that went away before the CPU took it (a spurious one).
const MASTER_SPURIOUS_VECTOR: u8 = MASTER_VECTORS + 7;
/// The exceptions: vectors 0 to 31.
const EXCEPTIONS: core::ops::Range<u8> = 0..32;
const NMI_VECTOR: u8 = 2;
const PAGE_FAULT_VECTOR: u8 = 14;

/// Initialisation command word 1: start initialising, ICW4 follows,
/// cascaded, edge triggered.
const ICW1_INIT_WITH_ICW4: u8 = 0x11;
/// ICW3: the master has the slave on IRQ 2; the slave's cascade identity.
const ICW3_SLAVE_ON_IRQ2: u8 = 1 << 2;
const ICW3_CASCADE_IDENTITY: u8 = 2;
/// ICW4: 8086 mode, normal end of interrupt.
const ICW4_8086: u8 = 0x01;
/// Interrupt mask registers: a set bit masks that IRQ. The master passes
/// IRQ 4 only (and IRQ 0 while the kernel halts); the slave (and the
/// cascade to it) nothing.
const MASTER_MASK: u8 = !(1 << COM1_IRQ);
const MASTER_MASK_HALTED: u8 = MASTER_MASK & !(1 << TIMER_IRQ);
const SLAVE_MASK: u8 = 0xFF;
/// Operation command word 2: non-specific end of interrupt.
const END_OF_INTERRUPT: u8 = 0x20;

/// The exceptions' names, by vector, as the manuals give them; the
/// reserved vectors have none.
const EXCEPTION_NAMES: [&str; 32] = [
    "divide error",
    "debug exception",
    "non-maskable interrupt",
    "breakpoint",
    "overflow",
    "bound range exceeded",
    "invalid opcode",
    "device not available",
    "double fault",
    "coprocessor segment overrun",
    "invalid TSS",
    "segment not present",
    "stack-segment fault",
    "general protection fault",
    "page fault",
    "reserved exception 15",
    "x87 floating-point error",
    "alignment check",
    "machine check",
    "SIMD floating-point exception",
    "virtualization exception",
    "control protection exception",
    "reserved exception 22",
    "reserved exception 23",
    "reserved exception 24",
    "reserved exception 25",
    "reserved exception 26",
    "reserved exception 27",
    "hypervisor injection exception",
    "VMM communication exception",
    "security exception",
    "reserved exception 31",
];

static IDT: Lazy<InterruptDescriptorTable> = Lazy::new(|| {
    let mut idt = InterruptDescriptorTable::new();
    set_general_handler!(&mut idt, exception, EXCEPTIONS);
    // Replaces the general one: the double fault needs its own stack.
    let double_fault_entry = idt.double_fault.set_handler_fn(double_fault);
    // SAFETY: `gdt::init` loads a TSS whose IST slot
    // `DOUBLE_FAULT_IST_INDEX` holds a stack used for nothing else.
    unsafe { double_fault_entry.set_stack_index(DOUBLE_FAULT_IST_INDEX) };
    idt[TIMER_VECTOR].set_handler_fn(timer_tick);
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
/// An 8259 needs time between the words of its initialisation on the old
/// boards (Linux and the `pic8259` crate wait the same way), hence an
/// I/O delay after each.
fn remap_pics() {
    let words = [
        (pic::MASTER_COMMAND, ICW1_INIT_WITH_ICW4),
        (pic::SLAVE_COMMAND, ICW1_INIT_WITH_ICW4),
        (pic::MASTER_DATA, MASTER_VECTORS),
        (pic::SLAVE_DATA, SLAVE_VECTORS),
        (pic::MASTER_DATA, ICW3_SLAVE_ON_IRQ2),
        (pic::SLAVE_DATA, ICW3_CASCADE_IDENTITY),
        (pic::MASTER_DATA, ICW4_8086),
        (pic::SLAVE_DATA, ICW4_8086),
        (pic::MASTER_DATA, MASTER_MASK),
        (pic::SLAVE_DATA, SLAVE_MASK),
    ];
    for (port, word) in words {
        port.write(word);
        io_delay();
    }
}

/// Halts until an interrupt, with the PIT's IRQ 0 let in meanwhile, so
/// that the halt ends within one PIT period (55 ms) where there is a PIT,
/// whatever else does or does not arrive. Call with interrupts off (after
/// finding nothing to do); returns with them off.
pub fn halt_until_interrupt() {
    pic::MASTER_DATA.write(MASTER_MASK_HALTED);
    x86_64::instructions::interrupts::enable_and_hlt();
    x86_64::instructions::interrupts::disable();
    pic::MASTER_DATA.write(MASTER_MASK);
}

extern "x86-interrupt" fn timer_tick(_frame: InterruptStackFrame) {
    pic::MASTER_COMMAND.write(END_OF_INTERRUPT);
}

extern "x86-interrupt" fn com1_received(_frame: InterruptStackFrame) {
    serial::on_interrupt();
    pic::MASTER_COMMAND.write(END_OF_INTERRUPT);
}

/// IRQ 7 is masked, so anything on its vector is spurious: the master has
/// not marked it in service, and must not be sent an end of interrupt.
extern "x86-interrupt" fn master_spurious(_frame: InterruptStackFrame) {}

/// Every exception but the double fault: reports it by name and ends the
/// run. An NMI after the kernel stopped for good returns to the halt.
fn exception(frame: InterruptStackFrame, vector: u8, error: Option<u64>) {
    if vector == NMI_VECTOR && exit::stopped() {
        return;
    }
    let name = EXCEPTION_NAMES[usize::from(vector % 32)];
    let at = frame.instruction_pointer.as_u64();
    match (vector, error) {
        (PAGE_FAULT_VECTOR, Some(code)) => {
            // CR2 holds the address whose access faulted.
            let address = Cr2::read_raw();
            let code = PageFaultErrorCode::from_bits_truncate(code);
            fatal(format_args!("page fault at {address:#x} ({code:?}), instruction at {at:#x}"))
        }
        (_, Some(code)) => fatal(format_args!("{name} (error code {code:#x}) at {at:#x}")),
        (_, None) => fatal(format_args!("{name} at {at:#x}")),
    }
}

extern "x86-interrupt" fn double_fault(frame: InterruptStackFrame, error: u64) -> ! {
    fatal(format_args!(
        "double fault (error code {error:#x}) at {:#x}, stack pointer {:#x}",
        frame.instruction_pointer.as_u64(),
        frame.stack_pointer.as_u64()
    ))
}
