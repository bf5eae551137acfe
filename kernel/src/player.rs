//! The show player: frames of the show (`scenes::show`) on the real
//! screen, one at a time.
//! [`play`] is the one way a frame gets there, for the demo and for
//! `SHOW` alike, so what the host checks is what the demo plays.

use core::hint::spin_loop;

use protocol::ShowReply;
use raster::MethodId;
use scenes::show::{Entry, Stage, FRAMES_PER_SECOND, PALETTE};

use crate::pit::{Stopwatch, TICKS_PER_SECOND};
use crate::video::Screen;
use crate::{bench, heap, vga};

/// PIT ticks from one show frame to the next.
const FRAME_TICKS: u64 = TICKS_PER_SECOND / FRAMES_PER_SECOND as u64;

/// Draws frame `frame` of `entry` with `method` on `stage`, labels it with
/// the rdtsc cycles the draw took, then, in the show's palette, at the
/// start of a vertical retrace (and after `pacer`'s next frame time if
/// there is one), copies it to the screen. Returns what the `SHOW` reply
/// says; allocates nothing itself, so `allocs` counts what the entry and
/// the method allocated.
pub fn play(
    screen: &mut Screen,
    stage: &mut Stage,
    entry: &'static Entry,
    frame: u32,
    method: MethodId,
    pacer: Option<&mut Pacer>,
) -> ShowReply<'static> {
    let allocations = heap::allocations();
    let strays = stage.stray_spans();
    let (report, cycles) = bench::timed(|| stage.draw(entry, frame, method.method()));
    let strays = stage.stray_spans().wrapping_sub(strays);
    stage.label(entry, frame, method.method(), cycles);
    let allocs = heap::allocations().wrapping_sub(allocations);
    if let Some(pacer) = pacer {
        pacer.wait();
    }
    screen.use_palette(&PALETTE);
    vga::wait_for_retrace();
    screen.blit(stage.pixels());
    ShowReply {
        entry: entry.name,
        frame: entry.wrap(frame),
        method,
        cycles,
        allocs,
        polygons: report.polygons,
        refused: report.refused,
        strays,
    }
}

/// Frame times [`FRAMES_PER_SECOND`] apart, from the PIT.
pub struct Pacer {
    stopwatch: Stopwatch,
    /// PIT ticks since the start at which the next frame is due.
    next: u64,
}

impl Pacer {
    /// Frame 0 is due now.
    pub fn start() -> Self {
        Self { stopwatch: Stopwatch::start(), next: 0 }
    }

    /// Waits until the next frame is due. A frame more than a frame time
    /// late is shown at once and the count starts again from it: a slow
    /// frame slows the show down rather than making it rush afterwards.
    fn wait(&mut self) {
        let now = self.stopwatch.elapsed_ticks();
        if now > self.next + FRAME_TICKS {
            self.next = now;
        }
        while self.stopwatch.elapsed_ticks() < self.next {
            spin_loop();
        }
        self.next += FRAME_TICKS;
    }
}
