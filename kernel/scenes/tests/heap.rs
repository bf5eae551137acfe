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

use raster::{FillRule, Framebuffer, Heap, Method, MethodId, Point, Polygon, SCREEN};
use scenes::show::{draw_labels, Entry, Stage, ENTRIES_IN_ORDER};

/// The system allocator, counting allocations.
struct Counting;

thread_local! {
    /// Whether this thread's allocations are being counted, and how many
    /// it has made while they were: each counting thread its own, so two
    /// tests counting at once do not count each other's. Const-initialised,
    /// so reading them never allocates.
    static COUNTING: Cell<bool> = const { Cell::new(false) };
    static ALLOCATIONS: Cell<u64> = const { Cell::new(0) };
}

// SAFETY: every call is passed on unchanged to `System`, which upholds
// the `GlobalAlloc` contract; the count is only thread-local reads and a
// write.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if COUNTING.with(Cell::get) {
            ALLOCATIONS.with(|count| count.set(count.get() + 1));
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
    let before = ALLOCATIONS.with(Cell::get);
    COUNTING.with(|counting| counting.set(true));
    work();
    COUNTING.with(|counting| counting.set(false));
    ALLOCATIONS.with(Cell::get) - before
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

/// One shot of the soak: a frame of an entry drawn with a method.
type Shot = (&'static Entry, u32, MethodId);

/// The allocations of `shot` as the kernel's `SHOW` makes them
/// (`kernel/src/show/player.rs`): an animation drawn and labelled on the stage,
/// a still drawn and labelled on the screen (`screen` here).
fn show_allocations(stage: &mut Stage, screen: &mut Framebuffer, (entry, frame, method): Shot) -> u64 {
    allocations(|| {
        if entry.is_animated() {
            stage.draw(entry, frame, method);
            stage.label(entry, frame, method, u64::MAX);
        } else {
            stage.draw_still(entry, method, screen);
            draw_labels(screen, entry, frame, method, u64::MAX);
        }
    })
}

/// A soak cycle's allocations in all and its frame of the most, with what
/// that frame shows, from a stage settled as the soak settles the kernel
/// (`xtask/harness/src/soak.rs`): the cycle's last still shown, then its last shot.
fn soak_cycle(cycle: &[Shot]) -> (u64, u64, Shot) {
    let mut stage = Stage::new();
    let mut screen = Framebuffer::new(SCREEN);
    let last_still = cycle.iter().rev().find(|(entry, ..)| !entry.is_animated());
    for &shot in last_still.into_iter().chain(cycle.last()) {
        show_allocations(&mut stage, &mut screen, shot);
    }
    let counted: Vec<(u64, Shot)> =
        cycle.iter().map(|&shot| (show_allocations(&mut stage, &mut screen, shot), shot)).collect();
    // The last of equals, as `cargo xtask soak` names it.
    let &(most, shot) = counted.iter().max_by_key(|(count, _)| *count).expect("a cycle has shots");
    (counted.iter().map(|(count, _)| count).sum(), most, shot)
}

/// The number after `before` in `text` (thousands separated by commas)
/// and the text after it.
fn figure_after<'a>(text: &'a str, before: &str) -> Option<(u64, &'a str)> {
    let after = &text[text.find(before)? + before.len()..];
    let end = after.find(|c: char| !c.is_ascii_digit() && c != ',').unwrap_or(after.len());
    let number = after[..end].trim_end_matches(',');
    Some((number.replace(',', "").parse().ok()?, &after[number.len()..]))
}

/// docs/testing.md's soak: the allocations of a cycle, and of its frame of
/// the most with what that frame shows, as the host counts them drawing
/// the show as the kernel does (the kernel's count, which `SHOW` answers,
/// is the same code's on the same heap calls).
#[test]
fn testing_md_gives_a_soak_cycles_allocations_as_the_show_makes_them() {
    let page = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/testing.md"))
        .expect("docs/testing.md is there");
    let page = page.split_whitespace().collect::<Vec<_>>().join(" ");
    let cycle: Vec<Shot> = MethodId::ALL
        .into_iter()
        .flat_map(|method| ENTRIES_IN_ORDER.iter().flat_map(move |e| (0..e.frames).map(move |f| (e, f, method))))
        .collect();
    let (total, most, (entry, _, method)) = soak_cycle(&cycle);
    let documented = figure_after(&page, "Each cycle made ").map(|(figure, _)| figure);
    assert_eq!(documented, Some(total), "docs/testing.md's allocations a cycle");
    let (documented, what) = figure_after(&page, "the most in one frame: ").expect("docs/testing.md names the most");
    let shows = format!(", `{}` with `{method}`", entry.name);
    assert_eq!((documented, what.starts_with(&shows)), (most, true), "the most in one frame: {most}{shows}");
}
