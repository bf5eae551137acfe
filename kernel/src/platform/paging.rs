//! The kernel's changes to the bootloader's page tables: device memory in
//! 4 KiB pages of a memory type of its choosing, and how a range is
//! mapped, read back for `READY` and `VGACHECK`.
//!
//! The bootloader maps all of physical memory for the kernel at an offset,
//! at least the first 4 GiB, in 2 MiB pages, write-back by the PAT: RAM,
//! the VGA window (0xA0000 to 0xBFFFF), the ROMs, the local APIC, the HPET
//! and the PCI devices' memory alike. A PC's firmware gives those ranges
//! different memory types through its MTRRs (write-back, uncacheable,
//! write-protect), and Intel's manual (volume 3, "Large Page Size
//! Considerations" in the MTRR chapter) leaves undefined what a CPU does
//! with a large page whose range has more than one; Linux maps the first
//! 2 MiB in 4 KiB pages for that reason. So [`set_memory_type`] splits
//! each 2 MiB page it touches into 512 pages of 4 KiB, each mapping what
//! it mapped before with the same rights (so each takes its MTRR's type
//! on its own), and gives the pages of the range the type asked for
//! through the PAT (`pat.rs`), which wins over the MTRRs for uncacheable
//! and write-combining (the manual's table of effective types). Under
//! QEMU's TCG memory types do nothing, so no emulator shows the effect;
//! [`mapping`] reads the page tables back, which is what `VGACHECK`
//! reports.

use alloc::vec::Vec;
use core::fmt;
use core::ptr::NonNull;
use core::sync::atomic::{AtomicU64, Ordering};

use bootloader_api::info::MemoryRegionKind;
use bootloader_api::BootInfo;
use protocol::{MemoryType, PageMapping};
use spin::Mutex;
use volatile::VolatilePtr;
use x86_64::instructions::tlb;
use x86_64::registers::control::Cr3;
use x86_64::structures::paging::mapper::{MappedFrame, TranslateResult};
use x86_64::structures::paging::{
    FrameAllocator, Mapper, OffsetPageTable, Page, PageSize, PageTable, PageTableFlags, PhysFrame, Size1GiB, Size2MiB,
    Size4KiB, Translate,
};
use x86_64::{align_up, PhysAddr, VirtAddr};

use crate::platform::pat;

/// Frames for new page tables come from usable RAM above 1 MiB, clear of
/// anything a BIOS keeps below it.
const LOWEST_FREE_FRAME: u64 = 0x10_0000;

/// The physical-memory offset, once [`init`] has run.
static PHYSICAL_OFFSET: AtomicU64 = AtomicU64::new(0);
/// Where new page tables come from; also serialises every change.
static FRAMES: Mutex<UsableFrames> = Mutex::new(UsableFrames { regions: Vec::new(), next: LOWEST_FREE_FRAME });

/// Notes where the bootloader mapped physical memory and which RAM is
/// free for page tables. Panics if the bootloader did not map physical
/// memory (main.rs's config asks for it). Call once, after `heap::init`.
pub fn init(boot_info: &BootInfo) {
    let offset = boot_info
        .physical_memory_offset
        .into_option()
        .expect("the bootloader did not map physical memory, so device memory is out of reach");
    PHYSICAL_OFFSET.store(offset, Ordering::Relaxed);
    let usable = boot_info.memory_regions.iter().filter(|region| region.kind == MemoryRegionKind::Usable);
    FRAMES.lock().regions = usable.map(|region| (region.start, region.end)).collect();
}

/// Where the physical-memory map puts `address`, if [`init`] has run and
/// the map reaches it.
pub fn physical(address: u64) -> Option<VirtAddr> {
    let offset = PHYSICAL_OFFSET.load(Ordering::Relaxed);
    if offset == 0 {
        return None;
    }
    let virtual_address = VirtAddr::try_new(offset.checked_add(address)?).ok()?;
    let _frames = FRAMES.lock();
    // SAFETY: the offset maps all physical memory, and the lock held
    // keeps every other page table handle away.
    let table = unsafe { active_page_table(VirtAddr::new(offset)) };
    table.translate_addr(virtual_address).is_some().then_some(virtual_address)
}

/// Copies the bytes at physical address `address` into `buffer`, through
/// the physical-memory map; `None` (and nothing read) if the map does not
/// reach all of them. For firmware tables in RAM or ROM, which reading
/// does not change: never for device memory, where a read can have side
/// effects.
pub fn read_physical(address: u64, buffer: &mut [u8]) -> Option<()> {
    let last = address.checked_add(buffer.len().max(1) as u64 - 1)?;
    let start = physical(address)?;
    // Every page in between is mapped if the first and the last are: the
    // bootloader maps physical memory from 0 to its end in one piece.
    physical(last)?;
    for (offset, byte) in (0..).zip(buffer.iter_mut()) {
        // SAFETY: `start + offset` lies in the mapped range checked above,
        // physical memory the caller says reading does not change; a
        // volatile read of a byte there touches no Rust object.
        *byte = unsafe { (start + offset).as_ptr::<u8>().read_volatile() };
    }
    Some(())
}

/// The 32-bit device register at `offset` from `base`, for volatile
/// access.
///
/// # Safety
/// `base` must be a block of device registers (no Rust object lives
/// there), mapped for the whole run with the type the device needs
/// ([`set_memory_type`]), and `offset` one of its 32-bit registers.
pub unsafe fn register(base: VirtAddr, offset: u64) -> VolatilePtr<'static, u32> {
    let address = NonNull::new((base + offset).as_mut_ptr::<u32>());
    // SAFETY: the caller's block is device memory, valid for volatile
    // access for the whole run; its address is a mapped one above the
    // physical-memory map's offset, so not null.
    unsafe { VolatilePtr::new(address.expect("a mapped register's address is not null")) }
}

/// The physical address `address` is mapped to, if it is mapped.
pub fn to_physical(address: VirtAddr) -> Option<PhysAddr> {
    let offset = VirtAddr::new(PHYSICAL_OFFSET.load(Ordering::Relaxed));
    if offset.is_null() {
        return None;
    }
    let _frames = FRAMES.lock();
    // SAFETY: the offset maps all physical memory, and the lock held
    // keeps every other page table handle away.
    unsafe { active_page_table(offset) }.translate_addr(address)
}

/// Why [`set_memory_type`] could not do its work.
pub enum TypeError {
    /// No PAT entry among 0 to 3 holds that type.
    NoPatEntry(MemoryType),
    /// A page of the range is not mapped, or in a 1 GiB page.
    Unmapped(VirtAddr),
    /// No usable RAM left for a page table.
    NoFrame,
}

impl fmt::Display for TypeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NoPatEntry(memory_type) => write!(f, "no PAT entry holds {}", memory_type.description()),
            Self::Unmapped(address) => write!(f, "{:#x} is not mapped in 4 KiB or 2 MiB pages", address.as_u64()),
            Self::NoFrame => write!(f, "no usable RAM is left for a page table"),
        }
    }
}

/// Maps the `len` bytes from `start` (already mapped, by the bootloader's
/// map of physical memory or another mapping of its) in 4 KiB pages of
/// `memory_type`, each with the rights it had: a 2 MiB page the range
/// touches is split first (see the module docs). Write-combining programs
/// its PAT entry first (`pat::write_combining_entry`). Nothing may access
/// the range with another type meanwhile: call before using it.
pub fn set_memory_type(start: VirtAddr, len: u64, memory_type: MemoryType) -> Result<(), TypeError> {
    let entry = match memory_type {
        MemoryType::WriteCombining => pat::write_combining_entry(),
        other => pat::entry_holding(other).ok_or(TypeError::NoPatEntry(other))?,
    };
    let offset = VirtAddr::new(PHYSICAL_OFFSET.load(Ordering::Relaxed));
    if offset.is_null() {
        return Err(TypeError::Unmapped(start));
    }
    let mut frames = FRAMES.lock();
    // SAFETY: the offset maps all physical memory, and the lock held
    // keeps every other page table handle away.
    let mut table = unsafe { active_page_table(offset) };
    for page in pages(start, len) {
        let flags = match table.translate(page.start_address()) {
            TranslateResult::Mapped { frame: MappedFrame::Size4KiB(_), flags, .. } => flags,
            TranslateResult::Mapped { frame: MappedFrame::Size2MiB(_), flags, .. } => {
                split_large_page(&mut table, page, &mut frames)?;
                flags - PageTableFlags::HUGE_PAGE
            }
            _ => return Err(TypeError::Unmapped(page.start_address())),
        };
        let cache_bits = PageTableFlags::WRITE_THROUGH | PageTableFlags::NO_CACHE | PAT_BIT_4KIB;
        let flags = (flags - cache_bits) | pat_bits(entry);
        // SAFETY: the page maps device memory (or a framebuffer), which no
        // Rust object lives in; only its cache type changes, before the
        // caller accesses it with the new one.
        match unsafe { table.update_flags(page, flags) } {
            Ok(flush) => flush.flush(),
            Err(_) => return Err(TypeError::Unmapped(page.start_address())),
        }
    }
    Ok(())
}

/// The 4 KiB pages holding the `len` bytes from `start`.
fn pages(start: VirtAddr, len: u64) -> impl Iterator<Item = Page<Size4KiB>> {
    let first = Page::containing_address(start);
    let last = Page::containing_address(start + len.max(1) - 1);
    Page::range_inclusive(first, last)
}

/// The PAT bit of a 4 KiB page's entry is bit 7, where a larger page's
/// entry has its page-size bit.
const PAT_BIT_4KIB: PageTableFlags = PageTableFlags::HUGE_PAGE;

/// The bits of a 4 KiB page's entry selecting PAT entry `index` (0 to 3).
fn pat_bits(index: u8) -> PageTableFlags {
    let mut bits = PageTableFlags::empty();
    bits.set(PageTableFlags::WRITE_THROUGH, index & 1 != 0);
    bits.set(PageTableFlags::NO_CACHE, index & 2 != 0);
    bits
}

/// The page tables in use, through the physical-memory map at `offset`.
///
/// # Safety
/// All of physical memory must be mapped at `offset`, and no other
/// reference to the page tables may be alive while the result is.
unsafe fn active_page_table(offset: VirtAddr) -> OffsetPageTable<'static> {
    let (level_4, _) = Cr3::read();
    let table = (offset + level_4.start_address().as_u64()).as_mut_ptr::<PageTable>();
    // SAFETY: CR3 holds the level-4 table in use, which the caller's
    // offset maps, and the caller holds no other reference to it.
    unsafe { OffsetPageTable::new(&mut *table, offset) }
}

/// Replaces the 2 MiB page holding `page` with a table of 512 4 KiB
/// pages mapping the same memory with the same rights. The new table is
/// filled in while the old mapping still stands, then swapped in by one
/// write of the level-2 entry, so nothing the kernel uses goes unmapped
/// for a moment (the page tables themselves may live in that memory).
fn split_large_page(
    table: &mut OffsetPageTable<'static>,
    page: Page<Size4KiB>,
    frames: &mut UsableFrames,
) -> Result<(), TypeError> {
    let large = Page::<Size2MiB>::containing_address(page.start_address());
    let offset = table.phys_offset();
    // SAFETY (of each `&mut *`): page tables are plain data reached
    // through the offset map; nothing else holds a reference to them.
    let level_3_address = table.level_4_table()[large.p4_index()].addr();
    let level_3 = unsafe { &mut *(offset + level_3_address.as_u64()).as_mut_ptr::<PageTable>() };
    let level_2 = unsafe { &mut *(offset + level_3[large.p3_index()].addr().as_u64()).as_mut_ptr::<PageTable>() };
    let entry = &mut level_2[large.p2_index()];
    if !entry.flags().contains(PageTableFlags::PRESENT | PageTableFlags::HUGE_PAGE) {
        return Err(TypeError::Unmapped(page.start_address()));
    }
    let rights = entry.flags() - PageTableFlags::HUGE_PAGE;
    let frame = frames.allocate_frame().ok_or(TypeError::NoFrame)?;
    let level_1 = unsafe { &mut *(offset + frame.start_address().as_u64()).as_mut_ptr::<PageTable>() };
    level_1.zero();
    for (index, small) in level_1.iter_mut().enumerate() {
        let memory = PhysFrame::<Size4KiB>::containing_address(entry.addr() + index as u64 * Size4KiB::SIZE);
        small.set_frame(memory, rights);
    }
    entry.set_frame(frame, rights);
    // INVLPG drops the large page's TLB entry and every cached
    // paging-structure entry (Intel's manual, volume 3, "Operations that
    // Invalidate TLBs and Paging-Structure Caches"), so the CPU walks to
    // the new table from now on.
    tlb::flush(large.start_address());
    Ok(())
}

/// How the `len` bytes from `start` are mapped now, read back from the
/// page tables and the PAT: the distinct pages the range lies in, how the
/// first is mapped, and whether every other is mapped the same way.
/// `None` before [`init`], or if part of the range is not mapped.
pub fn mapping(start: VirtAddr, len: u64) -> Option<PageMapping> {
    let offset = VirtAddr::new(PHYSICAL_OFFSET.load(Ordering::Relaxed));
    if offset.is_null() {
        return None;
    }
    let _frames = FRAMES.lock();
    // SAFETY: the offset maps all physical memory (it came from the boot
    // info), and the lock held keeps every other page table handle away.
    let table = unsafe { active_page_table(offset) };
    let mut seen: Option<PhysAddr> = None;
    let mut mapping: Option<PageMapping> = None;
    for page in pages(start, len) {
        let TranslateResult::Mapped { frame, flags, .. } = table.translate(page.start_address()) else { return None };
        let (page_size, pat_bit) = match frame {
            MappedFrame::Size4KiB(_) => (Size4KiB::SIZE, flags.contains(PAT_BIT_4KIB)),
            // Bit 12 of a large page's entry, its PAT bit, is not a valid
            // frame address bit: the translation above fails if it is set.
            MappedFrame::Size2MiB(_) => (Size2MiB::SIZE, false),
            MappedFrame::Size1GiB(_) => (Size1GiB::SIZE, false),
        };
        if seen == Some(frame.start_address()) {
            continue;
        }
        seen = Some(frame.start_address());
        let pat_entry = u8::from(flags.contains(PageTableFlags::WRITE_THROUGH))
            | u8::from(flags.contains(PageTableFlags::NO_CACHE)) << 1
            | u8::from(pat_bit) << 2;
        let this = PageMapping { pages: 1, page_size, pat_entry, memory: pat::entry_type(pat_entry), uniform: true };
        mapping = Some(match mapping {
            None => this,
            Some(so_far) => PageMapping {
                pages: so_far.pages + 1,
                uniform: so_far.uniform && (this.page_size, this.pat_entry) == (so_far.page_size, so_far.pat_entry),
                ..so_far
            },
        });
    }
    mapping
}

/// 4 KiB frames of usable RAM from the boot info's memory map, from
/// [`LOWEST_FREE_FRAME`] up, each handed out once: the kernel's new page
/// tables. Nothing else of the kernel's uses the map's usable RAM (its
/// heap is a static array).
struct UsableFrames {
    /// The usable regions, start and end.
    regions: Vec<(u64, u64)>,
    /// The lowest address not yet handed out.
    next: u64,
}

// SAFETY: every frame returned lies inside a region the bootloader marks
// usable (free: it marks what it used itself as its own), and `next`
// moves past it, so none is handed out twice.
unsafe impl FrameAllocator<Size4KiB> for UsableFrames {
    fn allocate_frame(&mut self) -> Option<PhysFrame<Size4KiB>> {
        let next = self.next;
        let start = self
            .regions
            .iter()
            .map(|&(start, end)| (align_up(next.max(start), Size4KiB::SIZE), end))
            .find(|&(start, end)| end >= start + Size4KiB::SIZE)?
            .0;
        self.next = start + Size4KiB::SIZE;
        Some(PhysFrame::containing_address(PhysAddr::new(start)))
    }
}
