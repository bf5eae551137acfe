//! Our own GDT, with a TSS whose interrupt stack table holds a separate
//! stack for double faults: a kernel stack overflow faults on the guard
//! page below the stack, and the CPU can only report that on a stack that
//! is still good (phil-opp/blog_os, "Double Faults").

use spin::Lazy;
use x86_64::instructions::segmentation::{Segment, CS, DS, ES, SS};
use x86_64::instructions::tables::load_tss;
use x86_64::structures::gdt::{Descriptor, GlobalDescriptorTable, SegmentSelector};
use x86_64::structures::tss::TaskStateSegment;
use x86_64::VirtAddr;

/// The IST slot of the double-fault stack (`idt.rs` names it in the
/// IDT).
pub const DOUBLE_FAULT_IST_INDEX: u16 = 0;

const DOUBLE_FAULT_STACK_SIZE: usize = 5 * 4096;

/// Only the CPU writes it, when it switches to it for a double fault.
/// `u128` elements make it 16-byte aligned, as a stack should be.
static mut DOUBLE_FAULT_STACK: [u128; DOUBLE_FAULT_STACK_SIZE / 16] = [0; DOUBLE_FAULT_STACK_SIZE / 16];

static TSS: Lazy<TaskStateSegment> = Lazy::new(|| {
    let mut tss = TaskStateSegment::new();
    // The stack grows down: the IST entry is its top.
    let bottom = VirtAddr::from_ptr(&raw const DOUBLE_FAULT_STACK);
    tss.interrupt_stack_table[usize::from(DOUBLE_FAULT_IST_INDEX)] = bottom + DOUBLE_FAULT_STACK_SIZE as u64;
    tss
});

struct Selectors {
    code: SegmentSelector,
    data: SegmentSelector,
    tss: SegmentSelector,
}

static GDT: Lazy<(GlobalDescriptorTable, Selectors)> = Lazy::new(|| {
    let mut gdt = GlobalDescriptorTable::new();
    let code = gdt.append(Descriptor::kernel_code_segment());
    let data = gdt.append(Descriptor::kernel_data_segment());
    let tss = gdt.append(Descriptor::tss_segment(&TSS));
    (gdt, Selectors { code, data, tss })
});

/// Loads the GDT, reloads the segment registers from it (the bootloader's
/// selectors mean nothing in our table) and loads the TSS.
pub fn init() {
    let (gdt, selectors) = &*GDT;
    gdt.load();
    // SAFETY: the selectors index descriptors of the GDT just loaded, which
    // lives for the whole run: a 64-bit ring-0 code segment, a ring-0 data
    // segment and an available TSS that is loaded only here.
    unsafe {
        CS::set_reg(selectors.code);
        SS::set_reg(selectors.data);
        DS::set_reg(selectors.data);
        ES::set_reg(selectors.data);
        load_tss(selectors.tss);
    }
}
