//! The kernel heap: a static array handed to `linked_list_allocator`,
//! behind a wrapper that counts allocations (`SHOW` reports how many a
//! frame made: the show's own code makes none, some methods do). `raster`
//! allocates (scenes, edge tables) and a dump is a 64,768-byte buffer;
//! 4 MiB is plenty and costs nothing in the image (it is `.bss`). `PING`
//! reports the heap's state ([`state`]), so a run of hours can show
//! whether it leaks or fragments.

use core::alloc::{GlobalAlloc, Layout};
use core::sync::atomic::{AtomicBool, AtomicU64, Ordering};

use linked_list_allocator::{Heap, LockedHeap};
use protocol::HeapState;

const HEAP_SIZE: usize = 4 * 1024 * 1024;

static mut HEAP: [u8; HEAP_SIZE] = [0; HEAP_SIZE];

/// Whether `HEAP` has been handed out, so it is handed out only once.
static HEAP_GIVEN: AtomicBool = AtomicBool::new(false);

#[global_allocator]
static ALLOCATOR: Counting = Counting { heap: LockedHeap::empty(), allocations: AtomicU64::new(0) };

/// The heap, counting every allocation it is asked for.
struct Counting {
    heap: LockedHeap,
    /// Calls to `alloc`, successful or not. `alloc_zeroed` and `realloc`
    /// keep `GlobalAlloc`'s default bodies, which call `alloc`, so they
    /// count too.
    allocations: AtomicU64,
}

// SAFETY: every call is passed on unchanged to `LockedHeap`, a correct
// allocator; counting touches no memory the allocator hands out.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        self.allocations.fetch_add(1, Ordering::Relaxed);
        // SAFETY: the caller upholds `alloc`'s contract, which is the same.
        unsafe { self.heap.alloc(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: the caller upholds `dealloc`'s contract, and `ptr` came
        // from `self.heap` (everything here does).
        unsafe { self.heap.dealloc(ptr, layout) }
    }
}

/// Gives the allocator its memory; later calls do nothing.
pub fn init() {
    if HEAP_GIVEN.swap(true, Ordering::SeqCst) {
        return;
    }
    // SAFETY: `HEAP` is used nowhere else, and the flag above lets this
    // run once, so the allocator owns those bytes alone for the whole run.
    unsafe { ALLOCATOR.heap.lock().init((&raw mut HEAP).cast::<u8>(), HEAP_SIZE) };
}

/// Heap allocations made since boot.
pub fn allocations() -> u64 {
    ALLOCATOR.allocations.load(Ordering::Relaxed)
}

/// The heap's bytes in use and the largest block one allocation could get
/// now, found by trying. The allocator is held locked throughout, so
/// nothing else allocates in between, and every trial block is given back
/// at once: the allocator merges it with its neighbours, which leaves its
/// free list as it was.
pub fn state() -> HeapState {
    let mut heap = ALLOCATOR.heap.lock();
    HeapState { used: heap.used(), free_largest: largest_free_block(&mut heap) }
}

/// Allocations here are multiples of this (the allocator rounds sizes up
/// to it and keeps its free blocks aligned to it).
const GRAIN: usize = core::mem::align_of::<usize>();

/// Whether `heap` has a block for `size` bytes (aligned to [`GRAIN`]).
fn fits(heap: &mut Heap, size: usize) -> bool {
    let Ok(layout) = Layout::from_size_align(size, GRAIN) else { return false };
    match heap.allocate_first_fit(layout) {
        Ok(block) => {
            // SAFETY: `block` was just allocated from `heap` with `layout`
            // and nothing else has seen it.
            unsafe { heap.deallocate(block, layout) };
            true
        }
        Err(()) => false,
    }
}

/// The largest multiple of [`GRAIN`] that `heap` can allocate in one
/// block. A free block of `B` bytes holds `B` exactly, or anything up to
/// `B - 16`, but not `B - 8` (the allocator will not leave a remainder too
/// small for its list node): so the search finds the edge below `B` and
/// then tries `B`.
fn largest_free_block(heap: &mut Heap) -> usize {
    if !fits(heap, GRAIN) {
        return 0;
    }
    // In grains: `low` fits, `high` does not (nothing larger than the free
    // bytes can).
    let (mut low, mut high) = (1, heap.free() / GRAIN + 1);
    while high - low > 1 {
        let middle = low + (high - low) / 2;
        if fits(heap, middle * GRAIN) {
            low = middle;
        } else {
            high = middle;
        }
    }
    if fits(heap, (low + 2) * GRAIN) {
        low += 2;
    }
    low * GRAIN
}
