//! The kernel heap: a static array handed to `linked_list_allocator`,
//! behind a wrapper that counts allocations (`SHOW` reports how many a
//! frame made: the show's own code makes none, some methods do). `raster`
//! allocates (scenes, edge tables) and a dump is a 64,768-byte buffer;
//! 4 MiB is plenty and costs nothing in the image (it is `.bss`).

use core::alloc::{GlobalAlloc, Layout};
use core::sync::atomic::{AtomicBool, AtomicU64, Ordering};

use linked_list_allocator::LockedHeap;

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
