//! `BENCH`: times every method drawing a built-in scene onto the real
//! screen with the time-stamp counter.
//!
//! Under QEMU the counter follows QEMU's virtual clock: host time, or with
//! `-icount` executed instructions. Either way it is reported on its own,
//! never next to the host lab's nanoseconds.

use alloc::vec::Vec;

use protocol::{BenchReply, BenchRow};
use raster::MethodId;
use scenes::Scene;

use crate::time::clock;
use crate::video::Screen;
use crate::wire::serial;

/// The `BENCH` answer for `scene`: per method in `raster::MethodId::ALL`
/// order, the median of `repeats` whole-scene draws, how many of the
/// scene's polygons the method declined, and the first one's reason.
/// Bounded: `MethodId::ALL.len() * repeats` draws, `repeats` being at most
/// `protocol::BENCH_MAX_REPEATS`. The screen keeps the last draw. COM1 is
/// polled between draws.
pub fn run(screen: &mut Screen, scene: &Scene, repeats: u8) -> BenchReply {
    let mut rows = Vec::with_capacity(MethodId::ALL.len());
    let mut samples = Vec::with_capacity(usize::from(repeats.max(1)));
    for method in MethodId::ALL {
        samples.clear();
        let mut refused = (0, None);
        for _ in 0..repeats.max(1) {
            // Between draws, outside the timing: a BENCH takes seconds.
            serial::poll();
            let (drawn, cycles) = clock::timed(|| screen.draw(scene, method));
            samples.push(cycles);
            refused = (drawn.report.refused, drawn.report.first_refusal);
        }
        samples.sort_unstable();
        rows.push(BenchRow { method, cycles: samples[samples.len() / 2], refused: refused.0, refusal: refused.1 });
    }
    BenchReply { rows }
}
