//! The `OK` text of `PING`, and the line losses it shares with `READY`:
//! what the serial line lost, the heap, the interrupts survived.

use core::fmt;

use super::fields::{Expected, Fields, Malformed};

/// What the serial line lost on its way into the kernel since boot, as the
/// kernel counted it: `overruns`, overrun errors in the UART's line status
/// (a byte arrived while its FIFO was full; each loses at least one byte),
/// `dropped`, bytes that found the kernel's receive buffer full, and the
/// bytes the UART received with a line error, which the kernel drops
/// ([`LineErrors`]). Text: `overruns=N dropped=M framing=F parity=P
/// breaks=B`. `PING` and `READY` report it, so that a log of a run on a
/// real PC shows any loss.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct LineLosses {
    pub overruns: u32,
    pub dropped: u32,
    /// `None` in what a kernel older than these counts says.
    pub errors: Option<LineErrors>,
}

/// Bytes the UART flagged in its line status as it received them, each
/// dropped by the kernel and counted under its first flag in this order:
/// `breaks`, a break (the line held at 0 for longer than a character:
/// a cable plugged in, an adapter powering up, a terminal's break key; the
/// UART receives it as one 0 byte), `framing` (no stop bit where one
/// belongs: a speed mismatch or noise), `parity` (a parity bit that does
/// not match; the kernel sets no parity, so it counts only with a UART
/// set up otherwise).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct LineErrors {
    pub framing: u32,
    pub parity: u32,
    pub breaks: u32,
}

impl LineLosses {
    /// Reads the losses' fields, next in `fields` (of `PING` or `READY`).
    pub(crate) fn read(fields: &mut Fields<'_>) -> Result<Self, Malformed> {
        let overruns = fields.parsed("overruns")?;
        let dropped = fields.parsed("dropped")?;
        let errors = match fields.next_is("framing") {
            true => Some(LineErrors {
                framing: fields.parsed("framing")?,
                parity: fields.parsed("parity")?,
                breaks: fields.parsed("breaks")?,
            }),
            false => None,
        };
        Ok(Self { overruns, dropped, errors })
    }

    /// Whether nothing was lost.
    pub fn none(&self) -> bool {
        self.overruns == 0 && self.dropped == 0 && self.errors.unwrap_or_default() == LineErrors::default()
    }
}

impl fmt::Display for LineLosses {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "overruns={} dropped={}", self.overruns, self.dropped)?;
        if let Some(LineErrors { framing, parity, breaks }) = self.errors {
            write!(f, " framing={framing} parity={parity} breaks={breaks}")?;
        }
        Ok(())
    }
}

/// The kernel heap as it stands: `used`, the bytes its allocations hold
/// (each rounded up as the allocator rounds it), and `free_largest`, the
/// largest block one allocation could get now. Text: `heap_used=N
/// heap_free_largest=M`. A heap that leaks grows `used`; one that
/// fragments shrinks `free_largest` though `used` is back where it was.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct HeapState {
    pub used: usize,
    pub free_largest: usize,
}

impl fmt::Display for HeapState {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "heap_used={} heap_free_largest={}", self.used, self.free_largest)
    }
}

/// The word a `PING` answer starts with.
pub const PONG: &str = "pong";

/// Interrupts the kernel took and carried on after, since boot: `nmis`,
/// non-maskable interrupts (a chipset's report of a hardware error, a
/// watchdog, a BMC), and `stray`, interrupts on a vector the kernel does
/// not use (a device or a local APIC entry the firmware left live). Each
/// also went out in a `LOG` frame. Text: `nmis=N stray_interrupts=M`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct InterruptCounts {
    pub nmis: u32,
    pub stray: u32,
}

impl fmt::Display for InterruptCounts {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "nmis={} stray_interrupts={}", self.nmis, self.stray)
    }
}

/// The `OK` text of `PING`: `pong overruns=N dropped=M framing=F parity=P
/// breaks=B heap_used=U heap_free_largest=L nmis=I stray_interrupts=S`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct Pong {
    pub losses: LineLosses,
    pub heap: HeapState,
    /// `None` in what a kernel older than these counts says.
    pub interrupts: Option<InterruptCounts>,
}

impl fmt::Display for Pong {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{PONG} {} {}", self.losses, self.heap)?;
        if let Some(interrupts) = self.interrupts {
            write!(f, " {interrupts}")?;
        }
        Ok(())
    }
}

impl Pong {
    /// Parses the text written by `Display` (an older kernel's has no
    /// line errors or interrupt counts).
    pub fn parse(text: &str) -> Result<Self, Malformed> {
        let fields = text.strip_prefix(PONG).and_then(|rest| rest.strip_prefix(' '));
        let fields = fields.ok_or(Malformed { reply: "PING", expected: Expected::Shape("`pong` and its fields") })?;
        let mut fields = Fields::new("PING", fields);
        let losses = LineLosses::read(&mut fields)?;
        let heap = HeapState { used: fields.parsed("heap_used")?, free_largest: fields.parsed("heap_free_largest")? };
        let interrupts = match fields.next_is("nmis") {
            true => Some(InterruptCounts { nmis: fields.parsed("nmis")?, stray: fields.parsed("stray_interrupts")? }),
            false => None,
        };
        fields.end()?;
        Ok(Self { losses, heap, interrupts })
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use std::string::ToString;

    #[test]
    fn pongs_round_trip_and_reject_garbage() {
        let errors = Some(LineErrors { framing: 4, parity: 0, breaks: 1 });
        let losses = LineLosses { overruns: 2, dropped: 0, errors };
        let interrupts = Some(InterruptCounts { nmis: 1, stray: 3 });
        let pong = Pong { losses, heap: HeapState { used: 70_000, free_largest: 4_100_000 }, interrupts };
        assert_eq!(
            pong.to_string(),
            "pong overruns=2 dropped=0 framing=4 parity=0 breaks=1 heap_used=70000 heap_free_largest=4100000 \
             nmis=1 stray_interrupts=3"
        );
        assert_eq!(Pong::parse(&pong.to_string()), Ok(pong));
        let malformed = |expected| Err(Malformed { reply: "PING", expected });
        for (garbage, expected) in [
            ("pong", Expected::Shape("`pong` and its fields")),
            ("ping overruns=2 dropped=0 heap_used=2 heap_free_largest=1", Expected::Shape("`pong` and its fields")),
            ("pong overruns=2 dropped=0", Expected::Field("heap_used")),
            ("pong overruns=2 dropped=0 heap_free_largest=1 heap_used=2", Expected::Field("heap_used")),
            ("pong dropped=0 overruns=2 heap_used=2 heap_free_largest=1", Expected::Field("overruns")),
            ("pong overruns=2 dropped=0 framing=4 breaks=1 heap_used=2 heap_free_largest=1", Expected::Field("parity")),
            ("pong overruns=2 dropped=0 heap_used=2 heap_free_largest=1 nmis=1", Expected::Field("stray_interrupts")),
            ("pong overruns=2 dropped=0 heap_used=2 heap_free_largest=1 stray_interrupts=1", Expected::End),
            ("pong overruns=-1 dropped=0 heap_used=2 heap_free_largest=1", Expected::Value("overruns")),
        ] {
            assert_eq!(Pong::parse(garbage), malformed(expected), "{garbage}");
        }
        assert!(!losses.none() && LineLosses::default().none());
        let only_a_break =
            LineLosses { errors: Some(LineErrors { breaks: 1, ..LineErrors::default() }), ..LineLosses::default() };
        assert!(!only_a_break.none());
    }

    #[test]
    fn an_older_kernels_pong_still_parses_without_the_newer_fields() {
        let pong = Pong::parse("pong overruns=1 dropped=0 heap_used=96 heap_free_largest=4096").unwrap();
        assert_eq!(pong.losses, LineLosses { overruns: 1, dropped: 0, errors: None });
        assert_eq!(pong.interrupts, None);
    }
}
