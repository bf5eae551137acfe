//! The page attribute table (PAT): the eight memory types a page's PAT,
//! PCD and PWT bits choose from, read back for `VGACHECK`, and one entry
//! reprogrammed to write-combining for the firmware's framebuffer.
//!
//! A CPU starts with the PAT write-back, write-through, UC-, uncacheable,
//! and the same four again (Intel's manual, volume 3, "Page Attribute
//! Table"). Nothing offers write-combining until an entry is changed.
//! [`write_combining_entry`] changes entry 1 (selected by PWT alone), the
//! entry Linux gives WC too: no page the bootloader or the kernel maps
//! selects it before (they set neither PWT nor PCD, except the kernel's
//! own uncacheable pages, which select entry 3), and the upper four
//! entries, selected with the 4 KiB page's PAT bit, are left alone, since
//! some older CPUs misread that bit (Intel's specification updates list
//! it; Linux avoids them for that reason).
//!
//! The change follows the manual's sequence for changing the PAT (the
//! same as for the MTRRs, "MTRR Considerations in MP Systems", without
//! the MTRR steps): interrupts off, caching off (CR0.CD set, NW clear),
//! the caches written back and invalidated (WBINVD), the TLBs flushed
//! (global pages too, by clearing CR4.PGE), the MSR written, the caches
//! and TLBs flushed again, caching and PGE back on. The kernel runs on
//! one CPU (the firmware leaves the others waiting for a start-up IPI),
//! so there is no other CPU to bring along.

use core::arch::asm;

use protocol::MemoryType;
use spin::Once;
use x86_64::instructions::{interrupts, tlb};
use x86_64::registers::control::{Cr0, Cr0Flags, Cr4, Cr4Flags};
use x86_64::registers::model_specific::Msr;

/// IA32_PAT: eight 8-bit entries, each a memory type in its low 3 bits.
/// Every x86-64 CPU has it.
const IA32_PAT: u32 = 0x277;
/// The entry [`write_combining_entry`] programs, and its encoding.
const WRITE_COMBINING_ENTRY: u8 = 1;
const WRITE_COMBINING_BITS: u64 = 1;

/// A PAT entry's memory type: `None` for an encoding the manual reserves.
pub fn entry_type(index: u8) -> Option<MemoryType> {
    decode((read() >> (8 * u32::from(index % 8))) as u8)
}

/// The whole MSR, as `VGACHECK` prints it.
pub fn read() -> u64 {
    // SAFETY: reading IA32_PAT, which every x86-64 CPU has, changes
    // nothing.
    unsafe { Msr::new(IA32_PAT).read() }
}

/// The type encoded in the low 3 bits of `bits`.
fn decode(bits: u8) -> Option<MemoryType> {
    match bits & 0b111 {
        0 => Some(MemoryType::Uncacheable),
        1 => Some(MemoryType::WriteCombining),
        4 => Some(MemoryType::WriteThrough),
        5 => Some(MemoryType::WriteProtected),
        6 => Some(MemoryType::WriteBack),
        7 => Some(MemoryType::UncachedMinus),
        _ => None,
    }
}

/// The first of entries 0 to 3 that holds `memory_type`, if one does.
pub fn entry_holding(memory_type: MemoryType) -> Option<u8> {
    (0..4).find(|&index| entry_type(index) == Some(memory_type))
}

/// The entry holding write-combining: one of entries 0 to 3 that already
/// does, else entry [`WRITE_COMBINING_ENTRY`] once reprogrammed (the
/// first call does it; see the module docs).
pub fn write_combining_entry() -> u8 {
    static ENTRY: Once<u8> = Once::new();
    *ENTRY.call_once(|| {
        entry_holding(MemoryType::WriteCombining).unwrap_or_else(|| {
            let shift = 8 * u32::from(WRITE_COMBINING_ENTRY);
            let pat = read() & !(0xFF << shift) | WRITE_COMBINING_BITS << shift;
            interrupts::without_interrupts(|| rewrite(pat));
            WRITE_COMBINING_ENTRY
        })
    })
}

/// Writes IA32_PAT by the manual's sequence. Interrupts must be off.
fn rewrite(pat: u64) {
    let cr0 = Cr0::read();
    let cr4 = Cr4::read();
    // SAFETY: CD set and NW clear is the no-fill cache mode the sequence
    // asks for; memory stays coherent, only slower, until CR0 is restored.
    unsafe { Cr0::write((cr0 | Cr0Flags::CACHE_DISABLE) - Cr0Flags::NOT_WRITE_THROUGH) };
    write_back_and_invalidate_caches();
    // SAFETY: clearing PGE only flushes global TLB entries (and stops
    // making new ones) until it is set again below.
    unsafe { Cr4::write(cr4 - Cr4Flags::PAGE_GLOBAL) };
    tlb::flush_all();
    // SAFETY: no page selects entry 1 (module docs), so changing its type
    // changes no mapping in use; the caches and TLBs hold nothing of the
    // old type, and are flushed again below.
    unsafe { Msr::new(IA32_PAT).write(pat) };
    write_back_and_invalidate_caches();
    tlb::flush_all();
    // SAFETY: both registers get back the values they had.
    unsafe {
        Cr4::write(cr4);
        Cr0::write(cr0);
    }
}

fn write_back_and_invalidate_caches() {
    // SAFETY: WBINVD writes every modified cache line back to memory and
    // drops the lines: memory ends up as the program wrote it.
    unsafe { asm!("wbinvd", options(nostack, preserves_flags)) };
}

/// Makes every store before it globally visible before any store after
/// it: write-combining stores sit in the CPU's write-combining buffers,
/// in no promised order, until something drains them (Intel's manual,
/// volume 3, "Buffering of Write Combining Memory Locations").
pub fn store_fence() {
    // SAFETY: SFENCE orders stores and touches no memory itself; every
    // x86-64 CPU has it.
    unsafe { asm!("sfence", options(nostack, preserves_flags)) };
}
