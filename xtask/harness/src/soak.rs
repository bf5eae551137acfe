//! The soak: the whole show played through `SHOW` with every method, cycle
//! after cycle, with the kernel heap read (`PING`) after each cycle. A
//! kernel left showing the demo for hours must end every cycle with its
//! heap where the cycle before left it: no more bytes in use (a leak), no
//! smaller largest free block (fragmentation); and every frame must cost
//! the same allocations and draw the same polygons, refusals and strays
//! (none) in every cycle. Before the first cycle the kernel is settled
//! into the state every cycle ends in ([`settle`]), and its heap there is
//! the baseline. `tests/tests/soak.rs` plays a sample of the
//! frames; `cargo xtask soak` plays every one.

use std::time::{Duration, Instant};

use anyhow::Result;
use protocol::HeapState;
use raster::MethodId;
use scenes::show::{Entry, ENTRIES_IN_ORDER};

use crate::client::Console;

/// One `SHOW` of a cycle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shot {
    pub entry: &'static Entry,
    pub frame: u32,
    pub method: MethodId,
}

/// The shots of one cycle: for each method in `MethodId::ALL` order, the
/// show in demo order with that method (as the digit keys play it), every
/// `step`-th frame of each entry from frame 0 (a still's one frame).
pub fn plan(step: u32) -> Vec<Shot> {
    let step = step.max(1) as usize;
    MethodId::ALL
        .into_iter()
        .flat_map(|method| {
            ENTRIES_IN_ORDER
                .iter()
                .flat_map(move |entry| (0..entry.frames).step_by(step).map(move |frame| Shot { entry, frame, method }))
        })
        .collect()
}

/// What one frame cost, as `SHOW` answered: everything but its cycles,
/// which vary from run to run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Figures {
    pub allocs: u64,
    pub polygons: usize,
    pub refused: usize,
    pub strays: usize,
}

/// One cycle played.
#[derive(Clone, Debug)]
pub struct Cycle {
    /// Per shot of the plan, in order.
    pub figures: Vec<Figures>,
    /// The heap after the cycle.
    pub heap: HeapState,
    pub elapsed: Duration,
}

impl Cycle {
    /// Allocations over the whole cycle.
    pub fn allocations(&self) -> u64 {
        self.figures.iter().map(|figures| figures.allocs).sum()
    }
}

/// Puts the kernel in the state every cycle ends in, and reads the heap
/// there: the baseline. The stage keeps the still page it built last
/// (`scenes::show::Stage`): after boot that is the demo's first page, at
/// the end of a cycle the plan's last still, so this shows that still,
/// then the plan's last shot.
pub fn settle(console: &mut Console, plan: &[Shot]) -> Result<HeapState> {
    let last_still = plan.iter().rev().find(|shot| !shot.entry.is_animated());
    for shot in last_still.into_iter().chain(plan.last()) {
        console.show(shot.entry.name, shot.frame, Some(shot.method))?;
    }
    Ok(console.pong()?.heap)
}

/// Plays `plan` once on the kernel behind `console`, calling `progress`
/// after each shot, then reads the heap.
pub fn play(console: &mut Console, plan: &[Shot], mut progress: impl FnMut()) -> Result<Cycle> {
    let started = Instant::now();
    let mut figures = Vec::with_capacity(plan.len());
    for shot in plan {
        let reply = console.show(shot.entry.name, shot.frame, Some(shot.method))?;
        figures.push(Figures {
            allocs: reply.allocs,
            polygons: reply.polygons,
            refused: reply.refused,
            strays: reply.strays,
        });
        progress();
    }
    let heap = console.pong()?.heap;
    Ok(Cycle { figures, heap, elapsed: started.elapsed() })
}

/// What is wrong with cycle `number` (from 1): a heap that ends holding
/// more than `settled` (the heap before the first cycle, see [`settle`])
/// or with a smaller largest free block, and each shot that strayed or
/// whose figures differ from the `first` cycle's (at most `limit` shots
/// named).
pub fn problems(
    plan: &[Shot],
    settled: HeapState,
    first: &Cycle,
    cycle: &Cycle,
    number: usize,
    limit: usize,
) -> Vec<String> {
    let mut problems = Vec::new();
    let after = cycle.heap;
    if after.used > settled.used {
        problems.push(format!(
            "cycle {number}: the heap holds {} bytes, {} more than before the first cycle",
            after.used,
            after.used - settled.used
        ));
    }
    if after.free_largest < settled.free_largest {
        problems.push(format!(
            "cycle {number}: the largest free block is {} bytes, {} fewer than before the first cycle",
            after.free_largest,
            settled.free_largest - after.free_largest
        ));
    }
    let shots = plan.iter().zip(first.figures.iter().zip(&cycle.figures));
    let wrong = shots.filter(|(_, (was, now))| was != now || now.strays != 0);
    for (shot, (was, now)) in wrong.take(limit) {
        problems.push(format!(
            "cycle {number}: {} frame {} with {}: {now:?}, in cycle 1 {was:?}",
            shot.entry.name, shot.frame, shot.method
        ));
    }
    problems
}

#[cfg(test)]
mod tests {
    use super::*;

    fn figures(allocs: u64) -> Figures {
        Figures { allocs, polygons: 4, refused: 0, strays: 0 }
    }

    fn cycle(figures: Vec<Figures>, used: usize, free_largest: usize) -> Cycle {
        Cycle { figures, heap: HeapState { used, free_largest }, elapsed: Duration::ZERO }
    }

    #[test]
    fn the_plan_plays_the_show_once_per_method_every_step_th_frame() {
        let every = plan(1);
        let frames: u32 = ENTRIES_IN_ORDER.iter().map(|entry| entry.frames).sum();
        assert_eq!(every.len(), frames as usize * MethodId::ALL.len());
        assert_eq!((every[0].entry.name, every[0].frame, every[0].method), ("abrash38-1", 0, MethodId::ALL[0]));
        let sampled = plan(10);
        let race = sampled.iter().filter(|shot| shot.entry.name == "race" && shot.method == MethodId::Exact);
        assert_eq!(race.map(|shot| shot.frame).collect::<Vec<_>>(), (0..560).step_by(10).collect::<Vec<_>>());
    }

    /// The frames of a cycle docs/testing.md gives: the number before
    /// `before`, with its thousands separated by commas.
    fn frames_before(page: &str, before: &str) -> Option<usize> {
        let figure = page[..page.find(before)?].rsplit(' ').next()?;
        figure.replace(',', "").parse().ok()
    }

    #[test]
    fn testing_md_gives_the_frames_of_a_cycle_as_the_plan_makes_them() {
        let page = std::fs::read_to_string(crate::workspace::root().join("docs/testing.md"))
            .expect("docs/testing.md is there");
        let page = page.split_whitespace().collect::<Vec<_>>().join(" ");
        assert_eq!(frames_before(&page, " frames a cycle."), Some(plan(1).len()), "docs/testing.md's soak");
        assert_eq!(frames_before("entry in demo order, 9,480 frames a cycle.", " frames a cycle."), Some(9480));
    }

    const SETTLED: HeapState = HeapState { used: 1000, free_largest: 5000 };

    #[test]
    fn a_cycle_like_the_first_has_no_problems() {
        let plan = &plan(100)[..2];
        let first = cycle(vec![figures(3), figures(0)], 1000, 5000);
        assert!(problems(plan, SETTLED, &first, &first, 1, 10).is_empty());
        let same = cycle(vec![figures(3), figures(0)], 1000, 5000);
        assert!(problems(plan, SETTLED, &first, &same, 2, 10).is_empty());
        let better = cycle(vec![figures(3), figures(0)], 900, 5100);
        assert!(problems(plan, SETTLED, &first, &better, 2, 10).is_empty());
    }

    #[test]
    fn growth_fragmentation_changed_figures_and_strays_are_named() {
        let plan = &plan(100)[..2];
        let first = cycle(vec![figures(3), figures(0)], 1000, 5000);
        let stray = Figures { strays: 1, ..figures(0) };
        let worse = cycle(vec![figures(4), stray], 1016, 4984);
        let problems = problems(plan, SETTLED, &first, &worse, 3, 10);
        assert_eq!(problems.len(), 4, "{problems:#?}");
        assert_eq!(problems[0], "cycle 3: the heap holds 1016 bytes, 16 more than before the first cycle");
        assert_eq!(problems[1], "cycle 3: the largest free block is 4984 bytes, 16 fewer than before the first cycle");
        assert!(problems[2].starts_with("cycle 3: abrash38-1 frame 0 with abrash_float: Figures { allocs: 4"));
        assert!(problems[3].contains("strays: 1"), "{}", problems[3]);
    }
}
