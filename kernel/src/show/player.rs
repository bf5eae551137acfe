//! The show player: frames of the show (`scenes::show`) on the real
//! screen, one at a time.
//! [`play`] is the one way a frame gets there, for the demo and for
//! `SHOW` alike, so what the host checks is what the demo plays.
//!
//! A still page is drawn straight into the screen's canvas (video memory
//! at 0xA0000 on a VGA), as the books' listings drew: it is drawn once and
//! then stays. An animation's frame is drawn off screen and copied whole
//! at a vertical retrace, so the viewer never sees a frame half drawn over
//! the last one (no tearing). Where the frame is presented in a firmware's
//! framebuffer instead (`video`), it is presented at those same moments:
//! the still page once drawn and labelled, the animation's frame once
//! copied.

use core::hint::spin_loop;

use protocol::ShowReply;
use raster::MethodId;
use scenes::show::{draw_labels, Entry, Stage, FRAMES_PER_SECOND, PALETTE};

use crate::platform::heap;
use crate::time::clock;
use crate::video::Screen;
use crate::wire::serial;

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
        let (report, cycles) = clock::timed(|| stage.draw(entry, frame, method));
        let strays = stage.stray_spans().wrapping_sub(strays);
        stage.label(entry, frame, method, cycles);
        if let Some(pacer) = pacer {
            pacer.wait();
        }
        screen.use_palette(&PALETTE);
        screen.wait_for_retrace();
        screen.blit(stage.pixels());
        (report, cycles, strays)
    } else {
        if let Some(pacer) = pacer {
            pacer.wait();
        }
        screen.use_palette(&PALETTE);
        let strays = screen.canvas().stray_spans();
        let (report, cycles) = clock::timed(|| stage.draw_still(entry, method, screen.canvas()));
        let strays = screen.canvas().stray_spans().wrapping_sub(strays);
        draw_labels(screen.canvas(), entry, frame, method, cycles);
        screen.present();
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

/// Frame times [`FRAMES_PER_SECOND`] apart, from the kernel's clock.
pub struct Pacer {
    /// TSC cycles from one frame to the next.
    frame_cycles: u64,
    /// The TSC count at which the next frame is due.
    next: u64,
}

impl Pacer {
    /// Frame 0 is due now.
    pub fn start() -> Self {
        Self { frame_cycles: clock::cycles_per_second() / u64::from(FRAMES_PER_SECOND), next: clock::cycles() }
    }

    /// Waits until the next frame is due, polling COM1 meanwhile
    /// (`serial::poll`). A frame more than a frame time late is shown at
    /// once and the count starts again from it: a slow frame slows the
    /// show down rather than making it rush afterwards.
    pub fn wait(&mut self) {
        let now = clock::cycles();
        if now > self.next + self.frame_cycles {
            self.next = now;
        }
        while clock::cycles() < self.next {
            serial::poll();
            spin_loop();
        }
        self.next += self.frame_cycles;
    }
}
