//! Kernel to host: the texts of the `OK` answers to `SHOW` and `PING`
//! and of the `READY` frame, each written by `Display` and read back by
//! `parse`.

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
/// read with [`Fields::optional`], so that a host still reads what an
/// older image says.
struct Fields<'a> {
    fields: core::iter::Peekable<core::str::Split<'a, char>>,
}

impl<'a> Fields<'a> {
    fn new(text: &'a str) -> Self {
        Self { fields: text.split(' ').peekable() }
    }

    /// The value of the next field, if it is called `key`.
    fn text(&mut self, key: &str) -> Option<&'a str> {
        let (k, value) = self.fields.next()?.split_once('=')?;
        (k == key).then_some(value)
    }

    /// The next field's value parsed, if it is called `key`.
    fn parsed<T: core::str::FromStr>(&mut self, key: &str) -> Option<T> {
        self.text(key)?.parse().ok()
    }

    /// Whether the next field is called `key` (it is then read as usual);
    /// an older kernel's text lacks the fields added since.
    fn next_is(&mut self, key: &str) -> bool {
        self.fields.peek().and_then(|field| field.split_once('=')).is_some_and(|(k, _)| k == key)
    }

    /// Whether every field has been read.
    fn end(mut self) -> bool {
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
    fn read(fields: &mut Fields<'_>) -> Option<Self> {
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

/// The `OK` text of `PING`: `pong overruns=N dropped=M heap_used=U
/// heap_free_largest=L`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct Pong {
    pub losses: LineLosses,
    pub heap: HeapState,
}

impl fmt::Display for Pong {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{PONG} {} {}", self.losses, self.heap)
    }
}

impl Pong {
    /// Parses the text written by `Display`.
    pub fn parse(text: &str) -> Option<Self> {
        let mut fields = Fields::new(text.strip_prefix(PONG)?.strip_prefix(' ')?);
        let losses = LineLosses::read(&mut fields)?;
        let heap = HeapState::read(&mut fields)?;
        fields.end().then_some(Self { losses, heap })
    }
}

/// How the kernel knows its time-stamp counter's rate (`kernel/src/clock.rs`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ClockSource {
    /// Counted against the PIT for 10 ms at boot.
    Pit,
    /// Stated by the CPU (CPUID leaf 0x15 or 0x16).
    Cpuid,
    /// Nothing measured it: a rate taken on trust, so times in seconds are
    /// not to be believed.
    Assumed,
}

impl ClockSource {
    pub const ALL: [ClockSource; 3] = [ClockSource::Pit, ClockSource::Cpuid, ClockSource::Assumed];

    pub fn name(self) -> &'static str {
        match self {
            ClockSource::Pit => "pit",
            ClockSource::Cpuid => "cpuid",
            ClockSource::Assumed => "assumed",
        }
    }
}

/// The `OK` text of `CLOCK`: `tsc_hz=N source=pit|cpuid|assumed`, the
/// time-stamp counter's ticks per second and how the kernel knows it.
/// rdtsc ticks over `hz` are seconds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TscRate {
    pub hz: u64,
    pub source: ClockSource,
}

impl fmt::Display for TscRate {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "tsc_hz={} source={}", self.hz, self.source.name())
    }
}

impl TscRate {
    /// Parses the text written by `Display`.
    pub fn parse(text: &str) -> Option<Self> {
        let mut fields = Fields::new(text);
        let hz = fields.parsed("tsc_hz")?;
        let source = fields.text("source")?;
        let source = ClockSource::ALL.into_iter().find(|s| s.name() == source)?;
        fields.end().then_some(Self { hz, source })
    }
}

/// A PCI function's vendor and device IDs, written `vvvv:dddd` in hex as
/// `lspci -n` does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PciId {
    pub vendor: u16,
    pub device: u16,
}

impl fmt::Display for PciId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:04x}:{:04x}", self.vendor, self.device)
    }
}

impl PciId {
    fn parse(text: &str) -> Option<Self> {
        let (vendor, device) = text.split_once(':')?;
        Some(Self { vendor: hex(vendor, 4)?, device: hex(device, 4)? })
    }
}

/// `text` as a number of exactly `digits` hex digits.
fn hex<T: TryFrom<u32>>(text: &str, digits: usize) -> Option<T> {
    let valid = text.len() == digits && text.bytes().all(|b| b.is_ascii_hexdigit());
    valid.then(|| u32::from_str_radix(text, 16).ok()?.try_into().ok()).flatten()
}

/// Where a PCI function sits: bus, device (0-31), function (0-7), written
/// `bb:dd.f` in hex as `lspci` does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PciAddress {
    pub bus: u8,
    pub device: u8,
    pub function: u8,
}

impl fmt::Display for PciAddress {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:02x}:{:02x}.{:x}", self.bus, self.device, self.function)
    }
}

impl PciAddress {
    fn parse(text: &str) -> Option<Self> {
        let (bus, rest) = text.split_once(':')?;
        let (device, function) = rest.split_once('.')?;
        let address = Self { bus: hex(bus, 2)?, device: hex(device, 2)?, function: hex(function, 1)? };
        (address.device < 32 && address.function < 8).then_some(address)
    }
}

/// The machine the kernel found itself on, as far as it can tell without
/// touching a port it has not identified (`kernel/src/machine.rs`). Only on
/// QEMU does the kernel answer `EXIT` and `FAULT`, and write QEMU's exit
/// port after a fatal error.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Machine {
    /// QEMU: its CPUID hypervisor signature and its PCI subsystem IDs.
    Qemu,
    /// Anything else: a PC, or an emulator that does not say what it is.
    #[default]
    Unknown,
}

impl Machine {
    pub const ALL: [Machine; 2] = [Machine::Qemu, Machine::Unknown];

    /// `qemu` or `unknown`, as `READY` writes it.
    pub fn name(self) -> &'static str {
        match self {
            Machine::Qemu => "qemu",
            Machine::Unknown => "unknown",
        }
    }

    /// The machine [`Machine::name`] calls `name`.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|machine| machine.name() == name)
    }
}

/// The firmware that booted the kernel.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Firmware {
    /// A PC BIOS, or a UEFI firmware's compatibility support module (CSM).
    #[default]
    Bios,
    Uefi,
}

impl Firmware {
    pub const ALL: [Firmware; 2] = [Firmware::Bios, Firmware::Uefi];

    /// `bios` or `uefi`, as `READY` writes it.
    pub fn name(self) -> &'static str {
        match self {
            Firmware::Bios => "bios",
            Firmware::Uefi => "uefi",
        }
    }

    /// The firmware [`Firmware::name`] calls `name`.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|firmware| firmware.name() == name)
    }
}

/// How the 320x200 frame reaches the screen.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Video {
    /// The card in mode 13h by the kernel's own register writes; the frame
    /// is video memory at 0xA0000. `mismatches`: the registers and DAC
    /// entries that did not read back as written (each also went out in a
    /// `LOG` frame before `READY`).
    Vga13h { mismatches: usize },
    /// The frame is memory of the kernel's, presented in the firmware's
    /// framebuffer.
    Framebuffer(Presentation),
    /// Nothing shows the frame (no VGA, no framebuffer): the kernel draws
    /// and answers all the same.
    #[default]
    None,
}

/// Where the framebuffer path puts the frame: a `width` x `height`
/// framebuffer, each frame pixel a `scale` x `scale` block, the frame's
/// top left corner at pixel (`left`, `top`), black around it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Presentation {
    pub width: u32,
    pub height: u32,
    pub scale: u32,
    pub left: u32,
    pub top: u32,
}

/// The payload of the `READY` frame the kernel sends once at boot:
/// `firmware=bios|uefi machine=qemu|unknown display=vvvv:dddd
/// display_at=bb:dd.f VIDEO LOSSES`, where VIDEO is `video=vga13h
/// vga_mismatches=K`, `video=framebuffer screen=WxH scale=S offset=X,Y` or
/// `video=none` ([`Video`]) and LOSSES the [`LineLosses`]. `display` is
/// the display controller the kernel uses: the one that decodes the
/// legacy VGA addresses if any does, else the first in bus order
/// (`display=none`, and no `display_at`, if there is none).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct Ready {
    pub firmware: Firmware,
    /// `None` in what a kernel older than the field says.
    pub machine: Option<Machine>,
    pub display: Option<PciId>,
    /// Where `display` sits; `None` with no display, or from an older
    /// kernel.
    pub display_at: Option<PciAddress>,
    pub video: Video,
    pub losses: LineLosses,
}

impl fmt::Display for Ready {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "firmware={} ", self.firmware.name())?;
        if let Some(machine) = self.machine {
            write!(f, "machine={} ", machine.name())?;
        }
        match self.display {
            Some(id) => write!(f, "display={id}")?,
            None => write!(f, "display=none")?,
        }
        if let Some(address) = self.display_at {
            write!(f, " display_at={address}")?;
        }
        match self.video {
            Video::Vga13h { mismatches } => write!(f, " video=vga13h vga_mismatches={mismatches}")?,
            Video::Framebuffer(Presentation { width, height, scale, left, top }) => {
                write!(f, " video=framebuffer screen={width}x{height} scale={scale} offset={left},{top}")?
            }
            Video::None => write!(f, " video=none")?,
        }
        write!(f, " {}", self.losses)
    }
}

impl Ready {
    /// Parses the text written by `Display`.
    pub fn parse(text: &str) -> Option<Self> {
        let mut fields = Fields::new(text);
        let firmware = Firmware::from_name(fields.text("firmware")?)?;
        let machine = match fields.next_is("machine") {
            true => Some(Machine::from_name(fields.text("machine")?)?),
            false => None,
        };
        let display = match fields.text("display")? {
            "none" => None,
            id => Some(PciId::parse(id)?),
        };
        let display_at = match fields.next_is("display_at") {
            true => Some(PciAddress::parse(fields.text("display_at")?)?),
            false => None,
        };
        let video = match fields.text("video")? {
            "vga13h" => Video::Vga13h { mismatches: fields.parsed("vga_mismatches")? },
            "framebuffer" => {
                let (width, height) = fields.text("screen")?.split_once('x')?;
                let scale = fields.parsed("scale")?;
                let (left, top) = fields.text("offset")?.split_once(',')?;
                let number = |text: &str| text.parse().ok();
                Video::Framebuffer(Presentation {
                    width: number(width)?,
                    height: number(height)?,
                    scale,
                    left: number(left)?,
                    top: number(top)?,
                })
            }
            "none" => Video::None,
            _ => return None,
        };
        let losses = LineLosses::read(&mut fields)?;
        fields.end().then_some(Self { firmware, machine, display, display_at, video, losses })
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
        for source in ClockSource::ALL {
            let rate = TscRate { hz: 2_893_421_000, source };
            assert_eq!(TscRate::parse(&rate.to_string()), Some(rate));
        }
        assert_eq!(TscRate { hz: 7, source: ClockSource::Pit }.to_string(), "tsc_hz=7 source=pit");
        for garbage in [
            "tsc_hz=7",
            "tsc_hz=x source=pit",
            "tsc_hz=7 source=hpet",
            "source=pit tsc_hz=7",
            "tsc_hz=7 source=pit x=1",
        ] {
            assert_eq!(TscRate::parse(garbage), None, "{garbage}");
        }
    }

    #[test]
    fn pongs_and_readies_round_trip_and_reject_garbage() {
        let errors = Some(LineErrors { framing: 4, parity: 0, breaks: 1 });
        let losses = LineLosses { overruns: 2, dropped: 0, errors };
        let pong = Pong { losses, heap: HeapState { used: 70_000, free_largest: 4_100_000 } };
        assert_eq!(
            pong.to_string(),
            "pong overruns=2 dropped=0 framing=4 parity=0 breaks=1 heap_used=70000 heap_free_largest=4100000"
        );
        assert_eq!(Pong::parse(&pong.to_string()), Some(pong));
        assert_eq!(Pong::parse("pong"), None);
        assert_eq!(Pong::parse("pong overruns=2 dropped=0"), None);
        assert_eq!(Pong::parse("pong overruns=2 dropped=0 heap_free_largest=1 heap_used=2"), None);
        assert_eq!(Pong::parse("pong dropped=0 overruns=2 heap_used=2 heap_free_largest=1"), None);
        assert_eq!(Pong::parse("pong overruns=2 dropped=0 framing=4 breaks=1 heap_used=2 heap_free_largest=1"), None);
        assert!(!losses.none() && LineLosses::default().none());
        let only_a_break =
            LineLosses { errors: Some(LineErrors { breaks: 1, ..LineErrors::default() }), ..LineLosses::default() };
        assert!(!only_a_break.none());

        let display = Some(PciId { vendor: 0x1013, device: 0x00b8 });
        let display_at = Some(PciAddress { bus: 0, device: 0x1f, function: 2 });
        let ready = Ready {
            firmware: Firmware::Bios,
            machine: Some(Machine::Qemu),
            display,
            display_at,
            video: Video::Vga13h { mismatches: 3 },
            losses,
        };
        assert_eq!(
            ready.to_string(),
            "firmware=bios machine=qemu display=1013:00b8 display_at=00:1f.2 video=vga13h vga_mismatches=3 \
             overruns=2 dropped=0 framing=4 parity=0 breaks=1"
        );
        let presentation = Presentation { width: 800, height: 600, scale: 2, left: 80, top: 100 };
        let framed = Ready {
            firmware: Firmware::Uefi,
            machine: Some(Machine::Unknown),
            video: Video::Framebuffer(presentation),
            ..ready
        };
        assert_eq!(
            framed.to_string(),
            "firmware=uefi machine=unknown display=1013:00b8 display_at=00:1f.2 video=framebuffer screen=800x600 \
             scale=2 offset=80,100 overruns=2 dropped=0 framing=4 parity=0 breaks=1"
        );
        let headless = Ready { display: None, display_at: None, video: Video::None, ..ready };
        assert_eq!(
            headless.to_string(),
            "firmware=bios machine=qemu display=none video=none overruns=2 dropped=0 framing=4 parity=0 breaks=1"
        );
        for ready in [ready, framed, headless] {
            assert_eq!(Ready::parse(&ready.to_string()), Some(ready));
        }
        for garbage in [
            "firmware=bios display=1013:b8 video=vga13h vga_mismatches=3 overruns=2 dropped=0",
            "firmware=bios display=1013:00b8 video=vga13h vga_mismatches=3 overruns=2",
            "firmware=bios display=1013:00b8 video=vga13h vga_mismatches=3 overruns=2 dropped=0 more=1",
            "firmware=coreboot display=1013:00b8 video=none overruns=2 dropped=0",
            "firmware=uefi display=none video=framebuffer screen=800x600 scale=2 overruns=2 dropped=0",
            "firmware=uefi display=none video=framebuffer screen=800 scale=2 offset=80,100 overruns=2 dropped=0",
            "firmware=bios display=none video=vga13h overruns=2 dropped=0",
            "display=1013:00b8 vga_mismatches=3 overruns=2 dropped=0",
            "vga: 0 mismatches",
            "firmware=bios machine=bochs display=none video=none overruns=2 dropped=0",
            "firmware=bios display=1013:00b8 display_at=00:20.0 video=none overruns=2 dropped=0",
            "firmware=bios display=1013:00b8 display_at=0:1.0 video=none overruns=2 dropped=0",
            "firmware=bios display=1013:00b8 display_at=00:01.8 video=none overruns=2 dropped=0",
            "firmware=bios display=none video=none overruns=2 dropped=0 framing=1 parity=0",
            "firmware=bios display=none video=none overruns=2 dropped=0 machine=qemu",
        ] {
            assert_eq!(Ready::parse(garbage), None, "{garbage}");
        }
    }

    #[test]
    fn an_older_kernels_ready_and_pong_still_parse_without_the_newer_fields() {
        let ready = Ready::parse("firmware=bios display=1234:1111 video=vga13h vga_mismatches=0 overruns=0 dropped=0");
        let expected = Ready {
            firmware: Firmware::Bios,
            machine: None,
            display: Some(PciId { vendor: 0x1234, device: 0x1111 }),
            display_at: None,
            video: Video::Vga13h { mismatches: 0 },
            losses: LineLosses { overruns: 0, dropped: 0, errors: None },
        };
        assert_eq!(ready, Some(expected));
        let pong = Pong::parse("pong overruns=1 dropped=0 heap_used=96 heap_free_largest=4096").unwrap();
        assert_eq!(pong.losses, LineLosses { overruns: 1, dropped: 0, errors: None });
    }
}
