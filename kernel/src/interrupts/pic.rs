//! The two 8259 interrupt controllers: where their IRQs land, which ones
//! pass, the end of an interrupt, and the server's halt, which counts on
//! the PIT's IRQ 0 to end it.
//!
//! The BIOS leaves the master on vectors 8-15, the CPU's own exception
//! vectors (IRQ 0 would look like a double fault), so both are moved to
//! 0x20-0x2F first, and every IRQ but COM1's is masked: the keyboard and
//! the VGA are polled. The PIT's IRQ 0 is let in only while the kernel
//! halts waiting for a byte ([`halt_until_interrupt`]), and only where it
//! was seen to arrive at boot ([`check_timer`]): a PC without a PIT, or
//! whose PIT does not reach the 8259 (the HPET's legacy replacement
//! route), would never wake a halt that counts on it.

use core::sync::atomic::{AtomicBool, Ordering};

use crate::platform::port::{io_delay, pic};
use crate::time::clock::Deadline;

/// Where the PICs' IRQs land: 0-7 from the master, 8-15 from the slave,
/// just past the 32 vectors the CPU reserves for exceptions.
pub const MASTER_VECTORS: u8 = 0x20;
const SLAVE_VECTORS: u8 = MASTER_VECTORS + 8;
/// The PIT's IRQ line, and COM1's.
const TIMER_IRQ: u8 = 0;
const COM1_IRQ: u8 = 4;
pub const TIMER_VECTOR: u8 = MASTER_VECTORS + TIMER_IRQ;
pub const COM1_VECTOR: u8 = MASTER_VECTORS + COM1_IRQ;
/// The master's input the slave is cascaded on.
const CASCADE_IRQ: u8 = 2;
/// The RTC's IRQ 8: the slave's input 0.
const RTC_IRQ_ON_SLAVE: u8 = 0;

/// Initialisation command word 1: start initialising, ICW4 follows,
/// cascaded, edge triggered.
const ICW1_INIT_WITH_ICW4: u8 = 0x11;
/// ICW3: the master has the slave on IRQ 2; the slave's cascade identity.
const ICW3_SLAVE_ON_IRQ2: u8 = 1 << CASCADE_IRQ;
const ICW3_CASCADE_IDENTITY: u8 = CASCADE_IRQ;
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
/// Operation command word 3: the next read of the command port returns
/// the in-service register; and, after it, the request register again.
const READ_IN_SERVICE: u8 = 0x0B;
const READ_REQUESTS: u8 = 0x0A;

/// Longest wait at boot for the PIT's IRQ 0: two of its 55 ms periods.
const TIMER_CHECK_MICROS: u64 = 110_000;

/// Whether the PIT's IRQ 0 has reached the CPU at least once.
static TIMER_SEEN: AtomicBool = AtomicBool::new(false);

/// Puts the PICs' IRQs on [`MASTER_VECTORS`] and [`SLAVE_VECTORS`] and
/// masks all but COM1's. Initialising clears the masks, hence the order.
/// An 8259 needs time between the words of its initialisation on the old
/// boards (Linux and the `pic8259` crate wait the same way), hence an
/// I/O delay after each. Call with interrupts off.
pub fn remap() {
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

/// Ends the interrupt on `vector` if a PIC has it in service, and says
/// whether one did. A spurious IRQ (7 or 15: a request that went away
/// before the CPU took it) is in no in-service register and gets no end
/// of interrupt from its own PIC; the master, whose cascade input did
/// carry a spurious IRQ 15, still gets one.
pub fn end_if_in_service(vector: u8) -> bool {
    let mut ended = false;
    let master_irq = match vector.checked_sub(MASTER_VECTORS) {
        Some(irq @ 0..8) => irq,
        Some(8..16) => {
            if in_service(pic::SLAVE_COMMAND) & (1 << (vector - SLAVE_VECTORS)) != 0 {
                pic::SLAVE_COMMAND.write(END_OF_INTERRUPT);
                ended = true;
            }
            CASCADE_IRQ
        }
        _ => return false,
    };
    if in_service(pic::MASTER_COMMAND) & (1 << master_irq) != 0 {
        pic::MASTER_COMMAND.write(END_OF_INTERRUPT);
        ended = true;
    }
    ended
}

/// The in-service register of the PIC whose command port is `command`.
fn in_service(command: crate::platform::port::IoPort<u8>) -> u8 {
    command.write(READ_IN_SERVICE);
    let in_service = command.read();
    command.write(READ_REQUESTS);
    in_service
}

/// The PIT's IRQ 0 handler's work: notes that the timer's interrupt
/// arrives.
pub fn on_timer_tick() {
    TIMER_SEEN.store(true, Ordering::Release);
}

/// Lets the RTC's IRQ 8 in (`true`: the slave's input 0 and the master's
/// cascade input unmasked) or masks it again, for the test-only `FAULT
/// strayirq` (`fault.rs`).
pub fn let_in_rtc(on: bool) {
    let (slave, master) = match on {
        true => (SLAVE_MASK & !(1 << RTC_IRQ_ON_SLAVE), MASTER_MASK & !(1 << CASCADE_IRQ)),
        false => (SLAVE_MASK, MASTER_MASK),
    };
    x86_64::instructions::interrupts::without_interrupts(|| {
        pic::SLAVE_DATA.write(slave);
        pic::MASTER_DATA.write(master);
    });
}

/// Lets IRQ 0 in and waits, a bounded time, for it to arrive, with
/// interrupts on; then masks it again. Afterwards [`timer_arrives`] says
/// whether it did. Call once interrupts are enabled.
pub fn check_timer() {
    pic::MASTER_DATA.write(MASTER_MASK_HALTED);
    let give_up = Deadline::after_micros(TIMER_CHECK_MICROS);
    while !TIMER_SEEN.load(Ordering::Acquire) && !give_up.passed() {
        core::hint::spin_loop();
    }
    x86_64::instructions::interrupts::without_interrupts(|| pic::MASTER_DATA.write(MASTER_MASK));
}

/// Whether the PIT's IRQ 0 was seen to arrive, so that a halt waiting for
/// an interrupt is sure to end within one of its periods.
pub fn timer_arrives() -> bool {
    TIMER_SEEN.load(Ordering::Acquire)
}

/// Halts until an interrupt, with the PIT's IRQ 0 let in meanwhile, so
/// that the halt ends within one PIT period (55 ms) whatever else does or
/// does not arrive. Call with interrupts off (after finding nothing to
/// do), and only where [`timer_arrives`]; returns with them off.
pub fn halt_until_interrupt() {
    pic::MASTER_DATA.write(MASTER_MASK_HALTED);
    x86_64::instructions::interrupts::enable_and_hlt();
    x86_64::instructions::interrupts::disable();
    pic::MASTER_DATA.write(MASTER_MASK);
}
