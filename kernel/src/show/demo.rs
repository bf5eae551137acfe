//! The demo that runs when no host talks: the show
//! (`scenes::show::ENTRIES_IN_ORDER`: the pages of Listings 38.3 and 40.4,
//! the LaMothe, WGT and Pendleton pieces, the race of every method) in
//! turn, round and round, at `FRAMES_PER_SECOND`, each entry for its
//! `demo_frames()` with the method of its source. Every frame goes through
//! `player::play`, as a `SHOW` would, except that a still page, which
//! `player::play` draws straight onto the screen, is drawn once and left
//! there for its frames (again when a key changes its method). It works
//! with no keyboard and no serial
//! line: the timer alone moves it on. Keys (PS/2, `keyboard`): space or
//! Enter, the next entry; 1 to 8, every entry with that method of
//! `MethodId::ALL` until 0 gives each its own again; Escape, the whole show
//! from the start with each entry's own method.
//!
//! It starts at boot from the first entry ([`Start::default`]), and again
//! when the host asks with `DEMO`, which may name an entry to start at and
//! stay on, and a method for every entry ([`Start`]).
//!
//! Bytes from the host accumulate between its frames while it plays
//! (`line.rs`): a line left incomplete does not hold the show up, and is
//! dropped after its bound. The first complete line from the host stops
//! it and leaves the screen as boot left it, black in the VGA default
//! palette, so that what the host draws is all that is on the screen when
//! it asks for a dump, and the palette is the one `DRAW` uses whichever
//! frame the demo was at.

use raster::MethodId;
use scenes::show::{Stage, ENTRIES_IN_ORDER};

use crate::interrupts::idt;
use crate::show::keyboard::{self, Key};
use crate::show::player::{self, Pacer};
use crate::video::Screen;
use crate::wire::line::{Complete, PendingLine};
use crate::wire::serial;

/// Where the demo starts and what it keeps to.
#[derive(Clone, Copy, Debug, Default)]
pub struct Start {
    /// The entry it starts at: an index into `ENTRIES_IN_ORDER`.
    pub entry: usize,
    /// Stay on the entry: the timer does not move the show on (space and
    /// Enter still do).
    pub stay: bool,
    /// Every entry drawn with this method, as after its digit key.
    pub method: Option<MethodId>,
}

/// Runs the demo on `stage` from `start` until the host completes a line
/// in `pending`, clears the screen, and returns that line. Allocates
/// nothing per frame beyond what the entries and their methods do.
pub fn run(screen: &mut Screen, stage: &mut Stage, start: Start, pending: &mut PendingLine) -> Complete {
    let mut pacer = Pacer::start();
    let mut index = start.entry % ENTRIES_IN_ORDER.len();
    let mut stay = start.stay;
    let mut frame: u32 = 0;
    // The method the viewer picked for every entry, if any.
    let mut picked = start.method;
    // The still page on the screen: its index and its method.
    let mut still_shown: Option<(usize, MethodId)> = None;
    loop {
        let entry = &ENTRIES_IN_ORDER[index];
        let method = picked.unwrap_or_else(|| entry.method_at(frame));
        let still = (!entry.is_animated()).then_some((index, method));
        if still.is_some() && still == still_shown {
            pacer.wait();
        } else {
            player::play(screen, stage, entry, frame, method, Some(&mut pacer));
        }
        still_shown = still;
        // An entry stayed on loops; its frame numbers wrap in `Entry::wrap`.
        frame = frame.wrapping_add(1);
        let mut next = !stay && frame >= entry.demo_frames();
        match keyboard::poll() {
            Some(Key::Next) => next = true,
            Some(Key::Method(method)) => picked = Some(method),
            Some(Key::OwnMethods) => picked = None,
            Some(Key::Restart) => (index, frame, picked, stay, next) = (0, 0, None, false, false),
            None => {}
        }
        if next {
            index = (index + 1) % ENTRIES_IN_ORDER.len();
            frame = 0;
        }
        idt::report();
        while let Some(byte) = serial::try_read_byte() {
            if let Some(complete) = pending.push(byte) {
                screen.clear(0);
                return complete;
            }
        }
        pending.drop_if_idle();
    }
}
