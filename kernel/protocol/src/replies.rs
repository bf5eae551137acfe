//! Kernel to host: the texts of the `OK` answers to `SHOW`, `PING` and
//! `CLOCK`, each written by `Display` and read back by `parse` (`READY`'s
//! is in `ready`).

use core::fmt;

use raster::MethodId;

/// The `OK` text of `SHOW`: what was drawn and what it cost, as
/// `entry=E frame=F method=M cycles=C allocs=A polygons=P refused=R strays=S`.
/// The host renders the same frame with `method` and `cycles` to compare.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ShowReply<'a> {
    pub entry: &'a str,
    /// The frame number drawn, already reduced modulo the entry's frames.
    pub frame: u32,
    pub method: MethodId,
    /// rdtsc cycles of the polygon drawing (labels excluded).
    pub cycles: u64,
    /// Heap allocations made while drawing and labelling the frame.
    pub allocs: u64,
    pub polygons: usize,
    pub refused: usize,
    /// Spans the method emitted outside the screen (a method bug).
    pub strays: usize,
}

impl fmt::Display for ShowReply<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let Self { entry, frame, method, cycles, allocs, polygons, refused, strays } = self;
        write!(
            f,
            "entry={entry} frame={frame} method={method} cycles={cycles} allocs={allocs} polygons={polygons} refused={refused} strays={strays}"
        )
    }
}

impl<'a> ShowReply<'a> {
    /// Parses the text written by `Display`; `None` if a field is missing,
    /// repeated in the wrong order or malformed.
    pub fn parse(text: &'a str) -> Option<Self> {
        let mut fields = Fields::new(text);
        let reply = Self {
            entry: fields.text("entry")?,
            frame: fields.parsed("frame")?,
            method: fields.parsed("method")?,
            cycles: fields.parsed("cycles")?,
            allocs: fields.parsed("allocs")?,
            polygons: fields.parsed("polygons")?,
            refused: fields.parsed("refused")?,
            strays: fields.parsed("strays")?,
        };
        fields.end().then_some(reply)
    }
}

/// Space-separated `key=value` fields read in a fixed order, as the `SHOW`,
/// `PING` and `READY` texts are written. Fields a kernel gained later are
/// read with [`Fields::next_is`], so that a host still reads what an
/// older image says.
pub(crate) struct Fields<'a> {
    fields: core::iter::Peekable<core::str::Split<'a, char>>,
}

impl<'a> Fields<'a> {
    pub(crate) fn new(text: &'a str) -> Self {
        Self { fields: text.split(' ').peekable() }
    }

    /// The value of the next field, if it is called `key`.
    pub(crate) fn text(&mut self, key: &str) -> Option<&'a str> {
        let (k, value) = self.fields.next()?.split_once('=')?;
        (k == key).then_some(value)
    }

    /// The next field's value parsed, if it is called `key`.
    pub(crate) fn parsed<T: core::str::FromStr>(&mut self, key: &str) -> Option<T> {
        self.text(key)?.parse().ok()
    }

    /// Whether the next field is called `key` (it is then read as usual);
    /// an older kernel's text lacks the fields added since.
    pub(crate) fn next_is(&mut self, key: &str) -> bool {
        self.fields.peek().and_then(|field| field.split_once('=')).is_some_and(|(k, _)| k == key)
    }

    /// Whether every field has been read.
    pub(crate) fn end(mut self) -> bool {
        self.fields.next().is_none()
    }
}

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
    pub(crate) fn read(fields: &mut Fields<'_>) -> Option<Self> {
        let overruns = fields.parsed("overruns")?;
        let dropped = fields.parsed("dropped")?;
        let errors = if fields.next_is("framing") {
            Some(LineErrors {
                framing: fields.parsed("framing")?,
                parity: fields.parsed("parity")?,
                breaks: fields.parsed("breaks")?,
            })
        } else {
            None
        };
        Some(Self { overruns, dropped, errors })
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

impl HeapState {
    fn read(fields: &mut Fields<'_>) -> Option<Self> {
        Some(Self { used: fields.parsed("heap_used")?, free_largest: fields.parsed("heap_free_largest")? })
    }
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
    /// Parses the text written by `Display`.
    pub fn parse(text: &str) -> Option<Self> {
        let mut fields = Fields::new(text.strip_prefix(PONG)?.strip_prefix(' ')?);
        let losses = LineLosses::read(&mut fields)?;
        let heap = HeapState::read(&mut fields)?;
        let interrupts = match fields.next_is("nmis") {
            true => Some(InterruptCounts { nmis: fields.parsed("nmis")?, stray: fields.parsed("stray_interrupts")? }),
            false => None,
        };
        fields.end().then_some(Self { losses, heap, interrupts })
    }
}

/// How the kernel knows its time-stamp counter's rate (`kernel/src/clock.rs`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ClockSource {
    /// Counted against the PIT at boot.
    Pit,
    /// Counted against the ACPI power management timer (3.579545 MHz),
    /// found through the ACPI tables.
    PmTimer,
    /// Counted against the HPET's main counter, found through the ACPI
    /// tables.
    Hpet,
    /// Stated by the CPU (CPUID leaf 0x15 or 0x16), where nothing could
    /// measure it.
    Cpuid,
    /// Nothing measured or stated it: a rate taken on trust, so times in
    /// seconds are not to be believed.
    Assumed,
}

impl ClockSource {
    pub const ALL: [ClockSource; 5] =
        [ClockSource::Pit, ClockSource::PmTimer, ClockSource::Hpet, ClockSource::Cpuid, ClockSource::Assumed];

    pub fn name(self) -> &'static str {
        match self {
            ClockSource::Pit => "pit",
            ClockSource::PmTimer => "pmtimer",
            ClockSource::Hpet => "hpet",
            ClockSource::Cpuid => "cpuid",
            ClockSource::Assumed => "assumed",
        }
    }
}

/// The rate each source gave, where the machine has it: the kernel
/// measures against every timer it finds and reads what the CPU states,
/// so that each can be checked against the others. Text: `pit_hz=A
/// pmtimer_hz=B hpet_hz=C cpuid_hz=D`, each only where that source is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct ClockReadings {
    pub pit: Option<u64>,
    pub pm_timer: Option<u64>,
    pub hpet: Option<u64>,
    pub cpuid: Option<u64>,
}

impl ClockReadings {
    /// Each reading with its field name, in the order of the text.
    fn named(&self) -> [(&'static str, Option<u64>); 4] {
        [("pit_hz", self.pit), ("pmtimer_hz", self.pm_timer), ("hpet_hz", self.hpet), ("cpuid_hz", self.cpuid)]
    }
}

/// The `OK` text of `CLOCK`: `tsc_hz=N source=S` and the [`ClockReadings`],
/// the time-stamp counter's ticks per second, how the kernel knows it,
/// and what every source gave. rdtsc ticks over `hz` are seconds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TscRate {
    pub hz: u64,
    pub source: ClockSource,
    pub readings: ClockReadings,
}

impl fmt::Display for TscRate {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "tsc_hz={} source={}", self.hz, self.source.name())?;
        for (name, reading) in self.readings.named() {
            if let Some(hz) = reading {
                write!(f, " {name}={hz}")?;
            }
        }
        Ok(())
    }
}

impl TscRate {
    /// Parses the text written by `Display` (an older kernel's has no
    /// readings).
    pub fn parse(text: &str) -> Option<Self> {
        let mut fields = Fields::new(text);
        let hz = fields.parsed("tsc_hz")?;
        let source = fields.text("source")?;
        let source = ClockSource::ALL.into_iter().find(|s| s.name() == source)?;
        let mut reading = |name| match fields.next_is(name) {
            true => fields.parsed(name).map(Some),
            false => Some(None),
        };
        let readings = ClockReadings {
            pit: reading("pit_hz")?,
            pm_timer: reading("pmtimer_hz")?,
            hpet: reading("hpet_hz")?,
            cpuid: reading("cpuid_hz")?,
        };
        fields.end().then_some(Self { hz, source, readings })
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use std::string::ToString;

    #[test]
    fn show_replies_round_trip_and_reject_garbage() {
        let reply = ShowReply {
            entry: "race",
            frame: 3,
            method: MethodId::Wgt,
            cycles: 12345,
            allocs: 0,
            polygons: 9,
            refused: 1,
            strays: 0,
        };
        let text = reply.to_string();
        assert_eq!(ShowReply::parse(&text), Some(reply));
        assert_eq!(ShowReply::parse("entry=race frame=3"), None);
        assert_eq!(ShowReply::parse(&text.replace("cycles=12345", "cycles=x")), None);
        assert_eq!(ShowReply::parse(&std::format!("{text} extra=1")), None);
        assert_eq!(ShowReply::parse(&text.replace("method=wgt", "method=wgt2")), None);
    }

    #[test]
    fn tsc_rates_round_trip_and_reject_garbage() {
        let readings =
            ClockReadings { pit: Some(2_893_000_000), pm_timer: None, hpet: Some(2_894_000_000), cpuid: None };
        for source in ClockSource::ALL {
            for readings in [readings, ClockReadings::default()] {
                let rate = TscRate { hz: 2_893_421_000, source, readings };
                assert_eq!(TscRate::parse(&rate.to_string()), Some(rate));
            }
        }
        let rate = TscRate { hz: 7, source: ClockSource::Pit, readings: ClockReadings::default() };
        assert_eq!(rate.to_string(), "tsc_hz=7 source=pit");
        let rate = TscRate { hz: 7, source: ClockSource::PmTimer, readings };
        assert_eq!(rate.to_string(), "tsc_hz=7 source=pmtimer pit_hz=2893000000 hpet_hz=2894000000");
        for garbage in [
            "tsc_hz=7",
            "tsc_hz=x source=pit",
            "tsc_hz=7 source=rtc",
            "source=pit tsc_hz=7",
            "tsc_hz=7 source=pit x=1",
            "tsc_hz=7 source=pit hpet_hz=1 pit_hz=2",
            "tsc_hz=7 source=pit pit_hz=x",
            "tsc_hz=7 source=pit pit_hz=1 pit_hz=1",
        ] {
            assert_eq!(TscRate::parse(garbage), None, "{garbage}");
        }
    }

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
        assert_eq!(Pong::parse(&pong.to_string()), Some(pong));
        assert_eq!(Pong::parse("pong"), None);
        assert_eq!(Pong::parse("pong overruns=2 dropped=0"), None);
        assert_eq!(Pong::parse("pong overruns=2 dropped=0 heap_free_largest=1 heap_used=2"), None);
        assert_eq!(Pong::parse("pong dropped=0 overruns=2 heap_used=2 heap_free_largest=1"), None);
        assert_eq!(Pong::parse("pong overruns=2 dropped=0 framing=4 breaks=1 heap_used=2 heap_free_largest=1"), None);
        assert_eq!(Pong::parse("pong overruns=2 dropped=0 heap_used=2 heap_free_largest=1 nmis=1"), None);
        assert_eq!(Pong::parse("pong overruns=2 dropped=0 heap_used=2 heap_free_largest=1 stray_interrupts=1"), None);
        assert!(!losses.none() && LineLosses::default().none());
        let only_a_break =
            LineLosses { errors: Some(LineErrors { breaks: 1, ..LineErrors::default() }), ..LineLosses::default() };
        assert!(!only_a_break.none());
    }

    #[test]
    fn an_older_kernels_pong_and_clock_still_parse_without_the_newer_fields() {
        let pong = Pong::parse("pong overruns=1 dropped=0 heap_used=96 heap_free_largest=4096").unwrap();
        assert_eq!(pong.losses, LineLosses { overruns: 1, dropped: 0, errors: None });
        assert_eq!(pong.interrupts, None);
        let rate = TscRate::parse("tsc_hz=2596138016 source=pit").unwrap();
        assert_eq!(rate.readings, ClockReadings::default());
    }
}
