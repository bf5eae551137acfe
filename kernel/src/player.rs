//! The show player: frames of the show (`scenes::show`) on the real
//! screen, one at a time.
//! [`play`] is the one way a frame gets there, for the demo and for
//! `SHOW` alike, so what the host checks is what the demo plays.
//!
//! A still page is drawn straight into video memory at 0xA0000, as the
//! books' listings drew: it is drawn once and then stays. An animation's
//! frame is drawn off screen and copied whole at a vertical retrace, so
//! the viewer never sees a frame half drawn over the last one (no
//! tearing).

use core::hint::spin_loop;

use protocol::ShowReply;
use raster::MethodId;
use scenes::show::{draw_labels, Entry, Stage, FRAMES_PER_SECOND, PALETTE};

use crate::pit::{Stopwatch, TICKS_PER_SECOND};
use crate::video::Screen;
use crate::{bench, heap, vga};

/// PIT ticks from one show frame to the next.
const FRAME_TICKS: u64 = TICKS_PER_SECOND / FRAMES_PER_SECOND as u64;

/// Puts frame `frame` of `entry`, drawn with `method` and labelled with
/// the rdtsc cycles the draw took, on the screen in the show's palette,
/// after `pacer`'s next frame time if there is one: a still page drawn
/// straight onto the screen, an animation's frame drawn on `stage` and
/// copied to the screen at the start of a vertical retrace. Returns what
/// the `SHOW` reply says; allocates nothing itself, so `allocs` counts
/// what the entry and the method allocated.
pub fn play(
    screen: &mut Screen,
    stage: &mut Stage,
    entry: &'static Entry,
    frame: u32,
    method: MethodId,
    pacer: Option<&mut Pacer>,
) -> ShowReply<'static> {
    let allocations = heap::allocations();
    let (report, cycles, strays) = if entry.is_animated() {
        let strays = stage.stray_spans();
        let (report, cycles) = bench::timed(|| stage.draw(entry, frame, method.method()));
        let strays = stage.stray_spans().wrapping_sub(strays);
        stage.label(entry, frame, method.method(), cycles);
        if let Some(pacer) = pacer {
            pacer.wait();
        }
        screen.use_palette(&PALETTE);
        vga::wait_for_retrace();
        screen.blit(stage.pixels());
        (report, cycles, strays)
    } else {
        if let Some(pacer) = pacer {
            pacer.wait();
        }
        screen.use_palette(&PALETTE);
        let strays = screen.stray_spans();
        let (report, cycles) = bench::timed(|| stage.draw_still(entry, method.method(), screen));
        let strays = screen.stray_spans().wrapping_sub(strays);
        draw_labels(screen, entry, frame, method.method(), cycles);
        (report, cycles, strays)
    };
    let allocs = heap::allocations().wrapping_sub(allocations);
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
    pub fn wait(&mut self) {
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
