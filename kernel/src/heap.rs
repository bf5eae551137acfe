//! The kernel heap: a static array handed to `linked_list_allocator`.
//! `raster` allocates (scenes, edge tables) and a dump is a 64,768-byte
//! buffer; 4 MiB is plenty and costs nothing in the image (it is `.bss`).

use core::sync::atomic::{AtomicBool, Ordering};

use linked_list_allocator::LockedHeap;

const HEAP_SIZE: usize = 4 * 1024 * 1024;

static mut HEAP: [u8; HEAP_SIZE] = [0; HEAP_SIZE];

/// Whether `HEAP` has been handed out, so it is handed out only once.
static HEAP_GIVEN: AtomicBool = AtomicBool::new(false);

#[global_allocator]
static ALLOCATOR: LockedHeap = LockedHeap::empty();

/// Gives the allocator its memory; later calls do nothing.
pub fn init() {
    if HEAP_GIVEN.swap(true, Ordering::SeqCst) {
        return;
    }
    // SAFETY: `HEAP` is used nowhere else, and the flag above lets this
    // run once, so the allocator owns those bytes alone for the whole run.
    unsafe { ALLOCATOR.lock().init((&raw mut HEAP).cast::<u8>(), HEAP_SIZE) };
}
