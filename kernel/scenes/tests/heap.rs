//! Each method's `MethodInfo::heap` against what it really does, counted
//! by a global allocator; and the show's claim that its frames take
//! nothing from the heap once an entry is running, when the method takes
//! nothing itself.
//!
//! Only the counting thread's allocations count: the test runner's own
//! threads allocate when they please (a loaded machine once put 4 of them
//! into a method's count).

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::sync::atomic::{AtomicU64, Ordering};

use raster::{FillRule, Framebuffer, Heap, Method, MethodId, Point, Polygon, SCREEN};
use scenes::show::{Stage, ENTRIES_IN_ORDER};

/// The system allocator, counting allocations.
struct Counting;

static ALLOCATIONS: AtomicU64 = AtomicU64::new(0);

thread_local! {
    /// Whether this thread's allocations are being counted. Const-initialised,
    /// so reading it never allocates.
    static COUNTING: Cell<bool> = const { Cell::new(false) };
}

// SAFETY: every call is passed on unchanged to `System`, which upholds
// the `GlobalAlloc` contract; the counter is only a thread-local read and
// an atomic add.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if COUNTING.with(Cell::get) {
            ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        }
        // SAFETY: the caller's guarantees for `layout` hold for `System` too.
        unsafe { System.alloc(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: `ptr` came from `System.alloc` with this `layout`.
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// Allocations made by `work` on this thread.
fn allocations(work: impl FnOnce()) -> u64 {
    let before = ALLOCATIONS.load(Ordering::Relaxed);
    COUNTING.with(|counting| counting.set(true));
    work();
    COUNTING.with(|counting| counting.set(false));
    ALLOCATIONS.load(Ordering::Relaxed) - before
}

fn polygon(points: &[(i32, i32)]) -> Polygon {
    Polygon::new(points.iter().map(|&(x, y)| Point::from_pixels(x, y)).collect(), 7)
}

fn fill_allocations(method: &dyn Method, polygon: &Polygon, target: &mut Framebuffer) -> u64 {
    allocations(|| {
        let _ = method.fill(polygon, target);
    })
}

#[test]
fn methods_allocate_as_their_info_says_and_the_show_adds_nothing() {
    let triangle = polygon(&[(10, 10), (200, 40), (60, 180)]);
    let convex = polygon(&[(100, 20), (180, 40), (200, 120), (150, 190), (60, 150), (50, 70)]);
    // A star: not monotone in y, so exact needs its active edge table.
    let star = polygon(&[(160, 10), (190, 190), (30, 70), (290, 70), (130, 190)]);
    // A star of 400 points under the non-zero rule: too many edges for
    // exact's tables on the stack (its edge flags, which need no table,
    // take polygons of so many edges only under the even-odd rule).
    let spikes: Vec<(i32, i32)> = (0..400)
        .map(|i| {
            let (angle, radius) = (f64::from(i) * std::f64::consts::TAU / 400.0, if i % 2 == 0 { 90.0 } else { 60.0 });
            ((160.0 + radius * angle.cos()) as i32, (100.0 + radius * angle.sin()) as i32)
        })
        .collect();
    let many = Polygon { rule: FillRule::NonZero, ..polygon(&spikes) };
    let mut target = Framebuffer::new(SCREEN);
    let mut wrong = Vec::new();
    for method in MethodId::ALL.map(MethodId::method) {
        let info = method.info();
        let simple = [&triangle, &convex].map(|p| fill_allocations(method, p, &mut target));
        let complex = fill_allocations(method, &star, &mut target);
        let huge = fill_allocations(method, &many, &mut target);
        let agrees = match info.heap {
            Heap::Never => simple == [0, 0] && complex == 0 && huge == 0,
            Heap::ManyEdges => simple == [0, 0] && complex == 0 && huge > 0,
            Heap::EveryPolygon => simple.iter().all(|&n| n > 0),
        };
        if !agrees {
            wrong.push(format!(
                "{} says {:?}, allocated {simple:?}, {complex} (star), {huge} (400 edges)",
                info.name, info.heap
            ));
        }
    }
    assert!(wrong.is_empty(), "{wrong:#?}");

    // Every animation of the show's own (convex) polygons, drawn and
    // labelled with each method that takes nothing for convex polygons,
    // allocates nothing after its first frame. (A page drawn by every
    // method in turn is real art, whose outlines are not convex.)
    let mut stage = Stage::new();
    for entry in ENTRIES_IN_ORDER.iter().filter(|e| e.is_animated() && e.page().is_none()) {
        for method in MethodId::ALL.into_iter().filter(|m| m.method().info().heap != Heap::EveryPolygon) {
            stage.draw(entry, 0, method);
            for frame in [1, entry.frames / 2, entry.frames - 1] {
                let count = allocations(|| {
                    stage.draw(entry, frame, method);
                    stage.label(entry, frame, method, u64::MAX);
                });
                assert_eq!(count, 0, "{} frame {frame} with {method}", entry.name);
            }
        }
    }
}
