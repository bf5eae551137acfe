//! A vector that storms: a source that fires again at once after every end
//! of interrupt (a level-triggered line an I/O APIC entry the firmware left
//! unmasked keeps high, with no driver to serve its device) would take the
//! CPU for good, one interrupt after the other. The stray interrupt handler
//! (`idt.rs`) counts each vector's arrivals over a window; at
//! [`STORM_LIMIT`] within [`STORM_WINDOW_MICROS`] (10,000 a second: no
//! source the kernel leaves alone comes near) it masks the vector where it
//! comes from, an I/O APIC entry or an entry of the local vector table
//! (`ioapic.rs`, `apic.rs`), and [`report`] tells of it in a `LOG` frame.
//! The kernel uses none of these vectors, so nothing it needs is masked.

use core::sync::atomic::{AtomicU32, AtomicU64, Ordering};

use protocol::{LogEvent, MaskedAt};

use crate::interrupts::{apic, ioapic};
use crate::time::clock;
use crate::wire::serial;

/// Arrivals of one vector within [`STORM_WINDOW_MICROS`] that make a storm.
const STORM_LIMIT: u32 = 1_000;
const STORM_WINDOW_MICROS: u64 = 100_000;

/// Per vector: when its window started (TSC) and its arrivals in it; where
/// its storm was masked ([`encode`]d, 0 for none) and what [`report`] told.
static WINDOW_START: [AtomicU64; 256] = [const { AtomicU64::new(0) }; 256];
static IN_WINDOW: [AtomicU32; 256] = [const { AtomicU32::new(0) }; 256];
static MASKED: [AtomicU64; 256] = [const { AtomicU64::new(0) }; 256];
static REPORTED: [AtomicU64; 256] = [const { AtomicU64::new(0) }; 256];

/// Counts an arrival of `vector`, and masks its source if it storms. Call
/// from its interrupt handler, before its end of interrupt.
pub fn guard(vector: u8) {
    let at = usize::from(vector);
    let now = clock::cycles();
    if now.wrapping_sub(WINDOW_START[at].load(Ordering::Relaxed)) > clock::cycles_in_micros(STORM_WINDOW_MICROS) {
        WINDOW_START[at].store(now, Ordering::Relaxed);
        IN_WINDOW[at].store(1, Ordering::Relaxed);
        return;
    }
    if IN_WINDOW[at].fetch_add(1, Ordering::Relaxed) + 1 == STORM_LIMIT {
        let on_io_apic = ioapic::mask_vector(vector);
        let in_local_apic = apic::mask_vector(vector);
        let masked = match (on_io_apic, in_local_apic) {
            (Some(interrupt), _) => MaskedAt::IoApic { interrupt },
            (None, true) => MaskedAt::LocalApic,
            (None, false) => MaskedAt::Nowhere,
        };
        MASKED[at].store(encode(masked), Ordering::Release);
    }
}

/// Whether a storm on `vector` has been masked.
pub fn masked(vector: u8) -> bool {
    MASKED[usize::from(vector)].load(Ordering::Acquire) != 0
}

/// Sends a `LOG` frame for each storm stopped since the last call. Call
/// from the main flow only.
pub fn report() {
    for (vector, (masked, reported)) in (0..=u8::MAX).zip(MASKED.iter().zip(&REPORTED)) {
        let masked = masked.load(Ordering::Acquire);
        if masked != 0 && reported.swap(masked, Ordering::Relaxed) != masked {
            let window_ms = (STORM_WINDOW_MICROS / 1000) as u32;
            serial::send_log(LogEvent::InterruptStorm {
                vector,
                count: STORM_LIMIT,
                window_ms,
                masked: decode(masked),
            });
        }
    }
}

/// `MaskedAt` in an atomic: a tag in the low byte (never 0), the I/O
/// APIC's interrupt above it.
fn encode(masked: MaskedAt) -> u64 {
    match masked {
        MaskedAt::Nowhere => 1,
        MaskedAt::LocalApic => 2,
        MaskedAt::IoApic { interrupt } => 3 | u64::from(interrupt) << 8,
    }
}

fn decode(encoded: u64) -> MaskedAt {
    match encoded & 0xFF {
        1 => MaskedAt::Nowhere,
        2 => MaskedAt::LocalApic,
        _ => MaskedAt::IoApic { interrupt: (encoded >> 8) as u32 },
    }
}
