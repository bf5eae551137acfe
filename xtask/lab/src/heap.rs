//! Heap allocations, counted: the lab binary installs [`Counting`] as its
//! global allocator, so that what a fill takes from the heap per polygon is
//! a number in results.json. Elsewhere (unit tests, benches) nothing counts,
//! and [`counting`] says so.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicU64, Ordering};

/// The system allocator, counting allocations.
pub struct Counting;

static ALLOCATIONS: AtomicU64 = AtomicU64::new(0);

// SAFETY: every call is passed on unchanged to `System`, which upholds the
// `GlobalAlloc` contract; the counter is only an atomic add.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        // SAFETY: the caller's guarantees for `layout` hold for `System` too.
        unsafe { System.alloc(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: `ptr` came from `System.alloc` with this `layout`.
        unsafe { System.dealloc(ptr, layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        // SAFETY: `ptr` came from `System` with `layout`; the caller's
        // guarantees for `new_size` hold for `System` too.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

/// Allocations (and reallocations) made so far by every thread.
pub fn allocations() -> u64 {
    ALLOCATIONS.load(Ordering::Relaxed)
}

/// Whether allocations are being counted: whether [`Counting`] is the
/// global allocator.
pub fn counting() -> bool {
    let before = allocations();
    drop(std::hint::black_box(Box::new(0u8)));
    allocations() > before
}

/// Allocations `work` makes per item, over `items` items; `None` when
/// nothing counts. Other threads must not allocate meanwhile.
pub fn per_item(items: usize, work: impl FnOnce()) -> Option<f64> {
    if !counting() || items == 0 {
        return None;
    }
    let before = allocations();
    work();
    Some((allocations() - before) as f64 / items as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The test binary keeps the system allocator: nothing is counted, and
    /// no count is made up.
    #[test]
    fn without_the_counting_allocator_there_is_no_count() {
        assert!(!counting());
        assert_eq!(per_item(3, || drop(vec![1, 2, 3])), None);
    }
}
