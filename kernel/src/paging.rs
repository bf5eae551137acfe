//! The VGA window's mapping: the kernel's own, in 4 KiB pages that the
//! CPU may not cache.
//!
//! The bootloader maps all of physical memory for the kernel at an offset,
//! in 2 MiB pages, write-back. The first of them covers RAM (0 to
//! 0x9FFFF), the VGA window (0xA0000 to 0xBFFFF) and the option and BIOS
//! ROMs (0xC0000 to 0xFFFFF), which a PC's firmware gives different memory
//! types through its fixed-range MTRRs (write-back, uncacheable,
//! write-protect). Intel's manual (volume 3, "Large Page Size
//! Considerations" in the MTRR chapter) leaves undefined what a CPU does
//! with a large page whose range has more than one MTRR type, and Linux
//! maps the first 2 MiB with 4 KiB pages for that reason. Under QEMU's
//! TCG memory types do nothing, so no emulator shows it.
//!
//! So [`map_vga_window`] splits that first 2 MiB page into 512 pages of
//! 4 KiB, each mapping what it mapped before with the same rights (so each
//! takes its MTRR's type on its own), and gives the 16 pages of the VGA
//! window the uncacheable type from the page attribute table (PAT): UC
//! wins over whatever the MTRRs say, so the CPU neither caches nor
//! combines writes to video memory, nor reads it speculatively, whatever
//! the firmware set up. Write-combining would let the CPU merge the
//! frame's 8-byte stores into bursts; it was not chosen because no
//! emulator here can measure it (TCG ignores memory types, so `cargo
//! xtask kbench` times the two alike) and UC is the type a PC's firmware
//! gives this range itself.
//!
//! [`window_mapping`] reads back how the window is mapped, from the page
//! tables and the PAT, for `VGACHECK`.

use core::fmt;
use core::sync::atomic::{AtomicU64, Ordering};

use bootloader_api::info::{MemoryRegionKind, MemoryRegions};
use bootloader_api::BootInfo;
use x86_64::instructions::tlb;
use x86_64::registers::control::Cr3;
use x86_64::registers::model_specific::Msr;
use x86_64::structures::paging::mapper::{MappedFrame, TranslateResult};
use x86_64::structures::paging::{
    FrameAllocator, Mapper, OffsetPageTable, Page, PageSize, PageTable, PageTableFlags, PhysFrame, Size2MiB, Size4KiB,
    Translate,
};
use x86_64::{align_up, PhysAddr, VirtAddr};

/// The VGA window the kernel maps: 0xA0000 to 0xAFFFF, the 64 KiB that
/// graphics modes with a 64 KiB window (Graphics register 6 = 05, mode
/// 13h's) use; the 64,000 bytes of the frame are its start.
const WINDOW_PHYSICAL: u64 = 0xA0000;
const WINDOW_LEN: u64 = 0x10000;
/// Frames for new page tables come from usable RAM above 1 MiB, clear of
/// anything a BIOS keeps below it.
const LOWEST_FREE_FRAME: u64 = 0x10_0000;
/// IA32_PAT: eight 8-bit entries, each a memory type in its low 3 bits.
/// Every x86-64 CPU has it.
const IA32_PAT: u32 = 0x277;

/// The physical-memory offset, once [`map_vga_window`] has run: where
/// [`window_mapping`] finds the page tables.
static PHYSICAL_OFFSET: AtomicU64 = AtomicU64::new(0);

/// Maps the VGA window in 4 KiB uncacheable pages (see the module docs)
/// and returns its virtual address: the same one as before,
/// `physical_memory_offset + 0xA0000`, now mapped the new way. Panics if
/// the bootloader did not map physical memory (main.rs's config asks for
/// it) or mapped it otherwise than in 2 MiB pages, as bootloader 0.11.17
/// (pinned in boot/Cargo.toml) does, or if no usable RAM is left for one
/// page table. Call once, before anything touches the window.
pub fn map_vga_window(boot_info: &BootInfo) -> VirtAddr {
    let offset = boot_info
        .physical_memory_offset
        .into_option()
        .map(VirtAddr::new)
        .expect("the bootloader did not map physical memory, so 0xA0000 is out of reach");
    PHYSICAL_OFFSET.store(offset.as_u64(), Ordering::Relaxed);
    let start = offset + WINDOW_PHYSICAL;
    let mut frames = UsableFrames { regions: &boot_info.memory_regions, next: LOWEST_FREE_FRAME };
    // SAFETY: the offset maps all physical memory (the bootloader's
    // config), and this is the only page table handle alive.
    let mut table = unsafe { active_page_table(offset) };
    split_large_page(&mut table, Page::containing_address(start), &mut frames);
    let flags = PageTableFlags::PRESENT | PageTableFlags::WRITABLE | PageTableFlags::NO_EXECUTE | uncacheable_bits();
    for page in window_pages(start) {
        // SAFETY: the page maps the VGA window, which no Rust object
        // lives in; only its cache type changes, before any access.
        match unsafe { table.update_flags(page, flags) } {
            Ok(flush) => flush.flush(),
            Err(error) => panic!("the VGA window's page {:?} could not be remapped: {error:?}", page.start_address()),
        }
    }
    start
}

/// The 4 KiB pages of the window starting at `start`.
fn window_pages(start: VirtAddr) -> impl Iterator<Item = Page<Size4KiB>> {
    let first = Page::containing_address(start);
    Page::range(first, first + WINDOW_LEN / Size4KiB::SIZE)
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
fn split_large_page(table: &mut OffsetPageTable<'static>, page: Page<Size4KiB>, frames: &mut UsableFrames<'_>) {
    let large = Page::<Size2MiB>::containing_address(page.start_address());
    let offset = table.phys_offset();
    // SAFETY (of each `&mut *`): page tables are plain data reached
    // through the offset map; nothing else holds a reference to them.
    let level_3_address = table.level_4_table()[large.p4_index()].addr();
    let level_3 = unsafe { &mut *(offset + level_3_address.as_u64()).as_mut_ptr::<PageTable>() };
    let level_2 = unsafe { &mut *(offset + level_3[large.p3_index()].addr().as_u64()).as_mut_ptr::<PageTable>() };
    let entry = &mut level_2[large.p2_index()];
    assert!(
        entry.flags().contains(PageTableFlags::PRESENT | PageTableFlags::HUGE_PAGE),
        "the bootloader's map of physical memory is not in 2 MiB pages here"
    );
    let rights = entry.flags() - PageTableFlags::HUGE_PAGE;
    let frame = frames.allocate_frame().expect("no usable RAM left for a page table");
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
}

/// PWT and PCD bits selecting the first of PAT entries 0 to 3 that holds
/// the uncacheable type (entry 3 in the PAT a CPU starts with, and in
/// Linux's); entry 3 if none does (then [`window_mapping`] reports what
/// it holds).
fn uncacheable_bits() -> PageTableFlags {
    let index = (0..4).find(|&index| pat_type(index) == MemoryType::Uncacheable).unwrap_or(3);
    pat_bits(index)
}

/// The PTE bits selecting PAT entry `index` (0 to 3) in a 4 KiB page.
fn pat_bits(index: u8) -> PageTableFlags {
    let mut bits = PageTableFlags::empty();
    bits.set(PageTableFlags::WRITE_THROUGH, index & 1 != 0);
    bits.set(PageTableFlags::NO_CACHE, index & 2 != 0);
    bits
}

/// The memory type PAT entry `index` (0 to 7) holds.
fn pat_type(index: u8) -> MemoryType {
    // SAFETY: reading IA32_PAT, which every x86-64 CPU has, changes
    // nothing.
    let pat = unsafe { Msr::new(IA32_PAT).read() };
    MemoryType::from_bits((pat >> (8 * u32::from(index))) as u8)
}

/// A PAT memory type.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MemoryType {
    Uncacheable,
    WriteCombining,
    WriteThrough,
    WriteProtected,
    WriteBack,
    /// UC-: uncacheable, unless an MTRR says write-combining.
    UncachedMinus,
    /// An encoding the manual reserves.
    Reserved(u8),
}

impl MemoryType {
    fn from_bits(bits: u8) -> Self {
        match bits & 0b111 {
            0 => Self::Uncacheable,
            1 => Self::WriteCombining,
            4 => Self::WriteThrough,
            5 => Self::WriteProtected,
            6 => Self::WriteBack,
            7 => Self::UncachedMinus,
            other => Self::Reserved(other),
        }
    }
}

impl fmt::Display for MemoryType {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Uncacheable => write!(f, "uncacheable (UC)"),
            Self::WriteCombining => write!(f, "write-combining (WC)"),
            Self::WriteThrough => write!(f, "write-through (WT)"),
            Self::WriteProtected => write!(f, "write-protected (WP)"),
            Self::WriteBack => write!(f, "write-back (WB)"),
            Self::UncachedMinus => write!(f, "uncacheable minus (UC-)"),
            Self::Reserved(bits) => write!(f, "reserved type {bits}"),
        }
    }
}

/// How one page of the window is mapped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct PageMapping {
    /// Bytes the page spans.
    size: u64,
    /// The PAT entry its PWT, PCD (and, for 4 KiB pages, PAT) bits select.
    pat_index: u8,
}

/// How the VGA window is mapped, read back from the page tables and the
/// PAT: `VGACHECK` reports it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct WindowMapping {
    /// The distinct pages the window's 64 KiB lie in.
    pages: usize,
    /// How the first of them is mapped, and whether all the others are
    /// mapped the same way.
    first: PageMapping,
    uniform: bool,
}

/// How the window is mapped now; `None` before [`map_vga_window`], or if
/// part of the window is not mapped.
pub fn window_mapping() -> Option<WindowMapping> {
    let offset = VirtAddr::new(PHYSICAL_OFFSET.load(Ordering::Relaxed));
    if offset.is_null() {
        return None;
    }
    // SAFETY: the offset maps all physical memory (it came from the boot
    // info), and this is the only page table handle alive.
    let table = unsafe { active_page_table(offset) };
    let start = offset + WINDOW_PHYSICAL;
    let mut seen: Option<(PhysAddr, PageMapping)> = None;
    let mut mapping: Option<WindowMapping> = None;
    for page in window_pages(start) {
        let TranslateResult::Mapped { frame, flags, .. } = table.translate(page.start_address()) else { return None };
        let (size, pat_bit) = match frame {
            MappedFrame::Size4KiB(_) => (Size4KiB::SIZE, flags.contains(PageTableFlags::HUGE_PAGE)),
            // Bit 12 of a large page's entry, its PAT bit, is not a valid
            // frame address bit: the translation above fails if it is set.
            MappedFrame::Size2MiB(_) => (Size2MiB::SIZE, false),
            MappedFrame::Size1GiB(_) => (1 << 30, false),
        };
        let pat_index = u8::from(flags.contains(PageTableFlags::WRITE_THROUGH))
            | u8::from(flags.contains(PageTableFlags::NO_CACHE)) << 1
            | u8::from(pat_bit) << 2;
        let this = PageMapping { size, pat_index };
        if seen.is_some_and(|(base, _)| base == frame.start_address()) {
            continue;
        }
        seen = Some((frame.start_address(), this));
        mapping = Some(match mapping {
            None => WindowMapping { pages: 1, first: this, uniform: true },
            Some(so_far) => {
                WindowMapping { pages: so_far.pages + 1, uniform: so_far.uniform && so_far.first == this, ..so_far }
            }
        });
    }
    mapping
}

impl fmt::Display for WindowMapping {
    /// E.g. `window 0xa0000-0xaffff: 16 pages of 4 KiB, uncacheable (UC),
    /// PAT entry 3`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let Self { pages, first: PageMapping { size, pat_index }, uniform } = *self;
        let end = WINDOW_PHYSICAL + WINDOW_LEN - 1;
        write!(f, "window {WINDOW_PHYSICAL:#x}-{end:#x}: {pages} page{}", if pages == 1 { "" } else { "s" })?;
        if size >= Size2MiB::SIZE {
            write!(f, " of {} MiB", size >> 20)?;
        } else {
            write!(f, " of {} KiB", size >> 10)?;
        }
        write!(f, ", {}, PAT entry {pat_index}", pat_type(pat_index))?;
        if !uniform {
            write!(f, " (the first; the others differ)")?;
        }
        Ok(())
    }
}

/// 4 KiB frames of usable RAM from the boot info's memory map, from
/// [`LOWEST_FREE_FRAME`] up, each handed out once. The kernel takes one,
/// for the new page table; nothing else of the kernel's uses the map's
/// usable RAM (its heap is a static array).
struct UsableFrames<'a> {
    regions: &'a MemoryRegions,
    /// The lowest address not yet handed out.
    next: u64,
}

// SAFETY: every frame returned lies inside a region the bootloader marks
// usable (free: it marks what it used itself as its own), and `next`
// moves past it, so none is handed out twice.
unsafe impl FrameAllocator<Size4KiB> for UsableFrames<'_> {
    fn allocate_frame(&mut self) -> Option<PhysFrame<Size4KiB>> {
        let region = self
            .regions
            .iter()
            .filter(|region| region.kind == MemoryRegionKind::Usable)
            .find(|region| region.end >= align_up(self.next.max(region.start), Size4KiB::SIZE) + Size4KiB::SIZE)?;
        let start = align_up(self.next.max(region.start), Size4KiB::SIZE);
        self.next = start + Size4KiB::SIZE;
        Some(PhysFrame::containing_address(PhysAddr::new(start)))
    }
}
