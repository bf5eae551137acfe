//! The serial protocol between the kernel and the host, shared by both
//! sides so they cannot drift apart. The README's "The serial protocol" section is the
//! prose version of this file.
//!
//! Host to kernel: one ASCII command per line (`\n`, a `\r` before it is
//! ignored), at most [`MAX_LINE`] bytes. Kernel to host: frames, each a
//! header line `@KIND LEN CRC32\n` (LEN in decimal, CRC32 of the payload in
//! 8 lowercase hex digits), then LEN payload bytes, then `\n`. Anything
//! between frames is noise and the host skips it.
#![no_std]

use core::fmt;

use raster::MethodId;

/// Longest command line the kernel accepts, terminator excluded.
pub const MAX_LINE: usize = 4096;
/// Bytes in a mode-13h framebuffer.
pub const FRAMEBUFFER_LEN: usize = 320 * 200;
/// Bytes in a dump: the framebuffer read back from 0xA0000, then the 256
/// DAC entries read back as 6-bit red, green, blue.
pub const DUMP_LEN: usize = FRAMEBUFFER_LEN + 768;
/// The byte that starts every frame header.
pub const FRAME_MARK: u8 = b'@';

/// Draws per method a `BENCH` without REPEATS times.
pub const BENCH_DEFAULT_REPEATS: u8 = 3;
/// Most draws per method a `BENCH` may ask for: keeps one `BENCH` within a
/// few seconds of emulated time.
pub const BENCH_MAX_REPEATS: u8 = 31;
/// The first line of a `BENCH` payload: the unit of the numbers after it.
pub const BENCH_UNIT_LINE: &str = "# rdtsc ticks per scene draw, median of the repeats; on a PC, cycles; under QEMU, \
     its virtual clock: emulated instructions with -icount shift=0, host time without";

/// What `DEMO` takes for "every entry" where an entry is named.
pub const EVERY_ENTRY: &str = "*";

/// The exit code a host sends with `EXIT` to end a run cleanly.
pub const EXIT_SUCCESS: u8 = 0x10;
/// The exit code the kernel uses after a panic or CPU exception.
pub const EXIT_FAILURE: u8 = 0x11;

/// The process status QEMU's isa-debug-exit gives for kernel exit `code`:
/// `(code << 1) | 1`, so 0x10 gives 33 and 0x11 gives 35.
pub const fn qemu_status(code: u8) -> i32 {
    ((code as i32) << 1) | 1
}

/// Which CPU fault the test-only `FAULT` command provokes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FaultKind {
    Breakpoint,
    PageFault,
    DoubleFault,
    Panic,
}

impl FaultKind {
    pub const ALL: [FaultKind; 4] =
        [FaultKind::Breakpoint, FaultKind::PageFault, FaultKind::DoubleFault, FaultKind::Panic];

    pub const fn name(self) -> &'static str {
        match self {
            FaultKind::Breakpoint => "breakpoint",
            FaultKind::PageFault => "pagefault",
            FaultKind::DoubleFault => "doublefault",
            FaultKind::Panic => "panic",
        }
    }
}

/// A host request.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Command<'a> {
    /// `PING`: answers `OK` with a [`Pong`], `pong overruns=N dropped=M`.
    Ping,
    /// `LIST`: answers a `LIST` frame, lines `scene NAME`, `show NAME FRAMES`
    /// and `method NAME`.
    List,
    /// `DRAW SCENE [METHOD]`: draws a built-in scene; answers `OK`.
    Draw { scene: &'a str, method: Option<MethodId> },
    /// `SHOW ENTRY FRAME [METHOD]`: draws frame FRAME of a show entry
    /// (`scenes::show`) exactly as the demo shows it, labels included, in
    /// the show's palette; answers `OK` with [`ShowReply`]'s fields.
    Show { entry: &'a str, frame: u32, method: Option<MethodId> },
    /// `CLEAR C`: fills the screen with colour C.
    Clear(u8),
    /// `POLY METHOD <poly line>`: fills one polygon written as a scene-file
    /// `poly` line without the keyword, e.g. `POLY exact color=4 0,0 9,0 0,9`.
    Poly { method: MethodId, spec: &'a str },
    /// `DUMP`: answers a `DUMP` frame of [`DUMP_LEN`] bytes.
    Dump,
    /// `VGACHECK`: reads every mode-13h register and the DAC back; answers
    /// `OK` or an `ERR` listing the mismatches.
    VgaCheck,
    /// `DEMO [ENTRY|*] [METHOD]`: answers `OK`, then plays the demo again
    /// until the next byte from the host, as it plays after boot; with
    /// ENTRY (a show entry; `*` is every entry) from that entry, staying on
    /// it, and with METHOD every entry drawn with that method, as the digit
    /// keys do.
    Demo { entry: Option<&'a str>, method: Option<MethodId> },
    /// `BENCH SCENE [REPEATS]`: draws a built-in scene REPEATS times
    /// ([`BENCH_DEFAULT_REPEATS`] if absent, 1 to [`BENCH_MAX_REPEATS`])
    /// with every method; answers a `BENCH` frame.
    Bench { scene: &'a str, repeats: u8 },
    /// `EXIT CODE`: leaves QEMU through isa-debug-exit with CODE (0-255).
    Exit(u8),
    /// `FAULT KIND`: test only; provokes a fault, which must be reported.
    Fault(FaultKind),
}

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
/// `PING` and `READY` texts are written.
struct Fields<'a> {
    fields: core::str::Split<'a, char>,
}

impl<'a> Fields<'a> {
    fn new(text: &'a str) -> Self {
        Self { fields: text.split(' ') }
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

    /// Whether every field has been read.
    fn end(mut self) -> bool {
        self.fields.next().is_none()
    }
}

/// What the serial line lost on its way into the kernel since boot, as the
/// kernel counted it: `overruns`, overrun errors in the UART's line status
/// (a byte arrived while its FIFO was full; each loses at least one byte),
/// and `dropped`, bytes that found the kernel's receive buffer full. Text:
/// `overruns=N dropped=M`. `PING` and `READY` report it, so that a log of
/// a run on a real PC shows any loss.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct LineLosses {
    pub overruns: u32,
    pub dropped: u32,
}

impl LineLosses {
    fn read(fields: &mut Fields<'_>) -> Option<Self> {
        Some(Self { overruns: fields.parsed("overruns")?, dropped: fields.parsed("dropped")? })
    }

    /// Whether nothing was lost.
    pub fn none(&self) -> bool {
        *self == Self::default()
    }
}

impl fmt::Display for LineLosses {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "overruns={} dropped={}", self.overruns, self.dropped)
    }
}

/// The word a `PING` answer starts with.
pub const PONG: &str = "pong";

/// The `OK` text of `PING`: `pong overruns=N dropped=M`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct Pong {
    pub losses: LineLosses,
}

impl fmt::Display for Pong {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{PONG} {}", self.losses)
    }
}

impl Pong {
    /// Parses the text written by `Display`.
    pub fn parse(text: &str) -> Option<Self> {
        let mut fields = Fields::new(text.strip_prefix(PONG)?.strip_prefix(' ')?);
        let losses = LineLosses::read(&mut fields)?;
        fields.end().then_some(Self { losses })
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
        let hex = |word: &str| (word.len() == 4).then(|| u16::from_str_radix(word, 16).ok()).flatten();
        Some(Self { vendor: hex(vendor)?, device: hex(device)? })
    }
}

/// The payload of the `READY` frame the kernel sends once at boot:
/// `display=vvvv:dddd vga_mismatches=K overruns=N dropped=M`. `display` is
/// the first PCI display controller found (`none` if there is none),
/// `vga_mismatches` the mode-13h registers and DAC entries that did not
/// read back as written (each one also went out before it in a `LOG`
/// frame).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct Ready {
    pub display: Option<PciId>,
    pub vga_mismatches: usize,
    pub losses: LineLosses,
}

impl fmt::Display for Ready {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.display {
            Some(id) => write!(f, "display={id}")?,
            None => write!(f, "display=none")?,
        }
        write!(f, " vga_mismatches={} {}", self.vga_mismatches, self.losses)
    }
}

impl Ready {
    /// Parses the text written by `Display`.
    pub fn parse(text: &str) -> Option<Self> {
        let mut fields = Fields::new(text);
        let display = match fields.text("display")? {
            "none" => None,
            id => Some(PciId::parse(id)?),
        };
        let vga_mismatches = fields.parsed("vga_mismatches")?;
        let losses = LineLosses::read(&mut fields)?;
        fields.end().then_some(Self { display, vga_mismatches, losses })
    }
}

/// Why a command line was rejected.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CommandError<'a> {
    Empty,
    NotAscii,
    TooLong,
    Unknown(&'a str),
    MissingArgument(&'static str),
    BadArgument(&'a str),
    /// A method name that is none of [`MethodId::ALL`]'s.
    UnknownMethod(&'a str),
    ExtraArgument(&'a str),
}

impl fmt::Display for CommandError<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CommandError::Empty => write!(f, "empty command"),
            CommandError::NotAscii => write!(f, "command is not printable ASCII"),
            CommandError::TooLong => write!(f, "command longer than {MAX_LINE} bytes"),
            CommandError::Unknown(word) => write!(f, "unknown command `{word}`"),
            CommandError::MissingArgument(what) => write!(f, "missing argument: {what}"),
            CommandError::BadArgument(word) => write!(f, "bad argument `{word}`"),
            CommandError::UnknownMethod(word) => write!(f, "`{word}`: {}", raster::UnknownMethod),
            CommandError::ExtraArgument(word) => write!(f, "unexpected argument `{word}`"),
        }
    }
}

impl<'a> Command<'a> {
    /// Parses one line (without its terminator).
    pub fn parse(line: &'a [u8]) -> Result<Self, CommandError<'a>> {
        if line.len() > MAX_LINE {
            return Err(CommandError::TooLong);
        }
        let line = line.strip_suffix(b"\r").unwrap_or(line);
        if !line.iter().all(|b| (0x20..0x7f).contains(b) || *b == b'\t') {
            return Err(CommandError::NotAscii);
        }
        let line = core::str::from_utf8(line).map_err(|_| CommandError::NotAscii)?;
        let mut words = line.split_ascii_whitespace();
        let name = words.next().ok_or(CommandError::Empty)?;
        let command = match name {
            "PING" => Command::Ping,
            "LIST" => Command::List,
            "DRAW" => Command::Draw {
                scene: words.next().ok_or(CommandError::MissingArgument("scene"))?,
                method: words.next().map(parse_method).transpose()?,
            },
            "SHOW" => {
                let entry = words.next().ok_or(CommandError::MissingArgument("entry"))?;
                let frame = words.next().ok_or(CommandError::MissingArgument("frame"))?;
                let frame = frame.parse().map_err(|_| CommandError::BadArgument(frame))?;
                Command::Show { entry, frame, method: words.next().map(parse_method).transpose()? }
            }
            "CLEAR" => Command::Clear(parse_u8(words.next().ok_or(CommandError::MissingArgument("colour"))?)?),
            "POLY" => {
                let method = words.next().ok_or(CommandError::MissingArgument("method"))?;
                let rest = line.trim_start();
                let rest = rest[name.len()..].trim_start();
                let spec = rest[method.len()..].trim();
                if spec.is_empty() {
                    return Err(CommandError::MissingArgument("polygon"));
                }
                return Ok(Command::Poly { method: parse_method(method)?, spec });
            }
            "DUMP" => Command::Dump,
            "BENCH" => {
                let scene = words.next().ok_or(CommandError::MissingArgument("scene"))?;
                let repeats = match words.next() {
                    None => BENCH_DEFAULT_REPEATS,
                    Some(word) => match parse_u8(word)? {
                        n @ 1..=BENCH_MAX_REPEATS => n,
                        _ => return Err(CommandError::BadArgument(word)),
                    },
                };
                Command::Bench { scene, repeats }
            }
            "VGACHECK" => Command::VgaCheck,
            "DEMO" => Command::Demo {
                entry: words.next().filter(|&entry| entry != EVERY_ENTRY),
                method: words.next().map(parse_method).transpose()?,
            },
            "EXIT" => Command::Exit(parse_u8(words.next().ok_or(CommandError::MissingArgument("code"))?)?),
            "FAULT" => {
                let kind = words.next().ok_or(CommandError::MissingArgument("fault kind"))?;
                let fault =
                    FaultKind::ALL.into_iter().find(|k| k.name() == kind).ok_or(CommandError::BadArgument(kind))?;
                Command::Fault(fault)
            }
            other => return Err(CommandError::Unknown(other)),
        };
        match words.next() {
            Some(extra) => Err(CommandError::ExtraArgument(extra)),
            None => Ok(command),
        }
    }
}

fn parse_u8(word: &str) -> Result<u8, CommandError<'_>> {
    word.parse().map_err(|_| CommandError::BadArgument(word))
}

fn parse_method(word: &str) -> Result<MethodId, CommandError<'_>> {
    word.parse().map_err(|_| CommandError::UnknownMethod(word))
}

impl fmt::Display for Command<'_> {
    /// The command line as the host sends it (no terminator).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Command::Ping => write!(f, "PING"),
            Command::List => write!(f, "LIST"),
            Command::Draw { scene, method: Some(method) } => write!(f, "DRAW {scene} {method}"),
            Command::Draw { scene, method: None } => write!(f, "DRAW {scene}"),
            Command::Show { entry, frame, method: Some(method) } => write!(f, "SHOW {entry} {frame} {method}"),
            Command::Show { entry, frame, method: None } => write!(f, "SHOW {entry} {frame}"),
            Command::Clear(color) => write!(f, "CLEAR {color}"),
            Command::Poly { method, spec } => write!(f, "POLY {method} {spec}"),
            Command::Dump => write!(f, "DUMP"),
            Command::Bench { scene, repeats } => write!(f, "BENCH {scene} {repeats}"),
            Command::VgaCheck => write!(f, "VGACHECK"),
            Command::Demo { entry: None, method: None } => write!(f, "DEMO"),
            Command::Demo { entry, method: None } => write!(f, "DEMO {}", entry.unwrap_or(EVERY_ENTRY)),
            Command::Demo { entry, method: Some(method) } => {
                write!(f, "DEMO {} {method}", entry.unwrap_or(EVERY_ENTRY))
            }
            Command::Exit(code) => write!(f, "EXIT {code}"),
            Command::Fault(kind) => write!(f, "FAULT {}", kind.name()),
        }
    }
}

/// What a frame carries.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FrameKind {
    /// Sent once at boot when the console is ready; payload: a [`Ready`].
    Ready,
    /// A command succeeded; payload: a short text.
    Ok,
    /// A command failed; payload: what was wrong. The kernel keeps serving.
    Err,
    /// Answer to `LIST`.
    List,
    /// Answer to `DUMP`: [`DUMP_LEN`] bytes.
    Dump,
    /// Answer to `BENCH`: [`BENCH_UNIT_LINE`], then a `METHOD CYCLES
    /// REFUSED [REFUSAL]` line per method, in [`MethodId::ALL`] order, each
    /// ending in `\n`: the polygons of the scene it declined, and the first
    /// one's reason (`raster::Refusal::name`).
    Bench,
    /// Unrequested information, e.g. a VGA register mismatch at boot.
    Log,
    /// A panic or CPU exception; the kernel exits QEMU with a failure code.
    Fatal,
}

impl FrameKind {
    pub const ALL: [FrameKind; 8] = [
        FrameKind::Ready,
        FrameKind::Ok,
        FrameKind::Err,
        FrameKind::List,
        FrameKind::Dump,
        FrameKind::Bench,
        FrameKind::Log,
        FrameKind::Fatal,
    ];

    pub const fn name(self) -> &'static str {
        match self {
            FrameKind::Ready => "READY",
            FrameKind::Ok => "OK",
            FrameKind::Err => "ERR",
            FrameKind::List => "LIST",
            FrameKind::Dump => "DUMP",
            FrameKind::Bench => "BENCH",
            FrameKind::Log => "LOG",
            FrameKind::Fatal => "FATAL",
        }
    }

    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|k| k.name() == name)
    }
}

/// The header line of a frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FrameHeader {
    pub kind: FrameKind,
    pub len: usize,
    pub crc: u32,
}

impl FrameHeader {
    /// The header for `payload`.
    pub fn for_payload(kind: FrameKind, payload: &[u8]) -> Self {
        Self { kind, len: payload.len(), crc: crc32fast::hash(payload) }
    }

    /// Parses a header line (without `\n`); `None` if it is not one.
    pub fn parse(line: &str) -> Option<Self> {
        let rest = line.strip_prefix(FRAME_MARK as char)?;
        let mut words = rest.split(' ');
        let kind = FrameKind::from_name(words.next()?)?;
        let len = words.next()?.parse().ok()?;
        let crc = words.next().filter(|w| w.len() == 8)?;
        let crc = u32::from_str_radix(crc, 16).ok()?;
        words.next().is_none().then_some(Self { kind, len, crc })
    }

    /// Whether `payload` is the one this header announced.
    pub fn matches(&self, payload: &[u8]) -> bool {
        payload.len() == self.len && crc32fast::hash(payload) == self.crc
    }
}

impl fmt::Display for FrameHeader {
    /// The header line without its `\n`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "@{} {} {:08x}", self.kind.name(), self.len, self.crc)
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use std::string::ToString;

    #[test]
    fn commands_round_trip_through_their_text() {
        let commands = [
            Command::Ping,
            Command::List,
            Command::Draw { scene: "abrash38-1", method: Some(MethodId::AbrashFloat) },
            Command::Draw { scene: "abrash38-2", method: None },
            Command::Clear(7),
            Command::Show { entry: "race", frame: 31, method: None },
            Command::Show { entry: "lamothe-rotate", frame: 0, method: Some(MethodId::Exact) },
            Command::Poly { method: MethodId::Exact, spec: "color=4 0,0 9.5,0 0,9" },
            Command::Dump,
            Command::Bench { scene: "abrash38-3", repeats: 1 },
            Command::Demo { entry: None, method: None },
            Command::Demo { entry: Some("race"), method: None },
            Command::Demo { entry: Some("lamothe-rotate"), method: Some(MethodId::Exact) },
            Command::Demo { entry: None, method: Some(MethodId::Wgt) },
            Command::Bench { scene: "abrash38-1", repeats: BENCH_MAX_REPEATS },
            Command::VgaCheck,
            Command::Exit(16),
            Command::Fault(FaultKind::PageFault),
        ];
        for command in commands {
            let text = command.to_string();
            assert_eq!(Command::parse(text.as_bytes()), Ok(command), "{text}");
        }
    }

    #[test]
    fn bad_lines_are_rejected_with_a_reason() {
        assert_eq!(Command::parse(b""), Err(CommandError::Empty));
        assert_eq!(Command::parse(b"  \r"), Err(CommandError::Empty));
        assert_eq!(Command::parse(b"FROB 1"), Err(CommandError::Unknown("FROB")));
        assert_eq!(Command::parse(b"CLEAR"), Err(CommandError::MissingArgument("colour")));
        assert_eq!(Command::parse(b"CLEAR 256"), Err(CommandError::BadArgument("256")));
        assert_eq!(Command::parse(b"DUMP now"), Err(CommandError::ExtraArgument("now")));
        assert_eq!(Command::parse(b"POLY exact"), Err(CommandError::MissingArgument("polygon")));
        assert_eq!(Command::parse(b"FAULT nap"), Err(CommandError::BadArgument("nap")));
        assert_eq!(Command::parse(b"BENCH"), Err(CommandError::MissingArgument("scene")));
        assert_eq!(Command::parse(b"BENCH abrash38-1 0"), Err(CommandError::BadArgument("0")));
        let too_many = std::format!("{}", u16::from(BENCH_MAX_REPEATS) + 1);
        let line = std::format!("BENCH abrash38-1 {too_many}");
        assert_eq!(Command::parse(line.as_bytes()), Err(CommandError::BadArgument(&too_many)));
        assert_eq!(Command::parse(b"BENCH abrash38-1 -1"), Err(CommandError::BadArgument("-1")));
        assert_eq!(Command::parse(b"BENCH abrash38-1 3 4"), Err(CommandError::ExtraArgument("4")));
        assert_eq!(Command::parse(b"SHOW race"), Err(CommandError::MissingArgument("frame")));
        assert_eq!(Command::parse(b"SHOW race -1"), Err(CommandError::BadArgument("-1")));
        assert_eq!(Command::parse(b"SHOW race 1 exact 2"), Err(CommandError::ExtraArgument("2")));
        assert_eq!(Command::parse(b"SHOW race 1 exakt"), Err(CommandError::UnknownMethod("exakt")));
        assert_eq!(Command::parse(b"DEMO * exakt"), Err(CommandError::UnknownMethod("exakt")));
        assert_eq!(Command::parse(b"DEMO race exact 1"), Err(CommandError::ExtraArgument("1")));
        assert_eq!(Command::parse(b"DRAW abrash38-1 abrash"), Err(CommandError::UnknownMethod("abrash")));
        assert_eq!(Command::parse(b"POLY fast color=1 0,0 1,0 0,1"), Err(CommandError::UnknownMethod("fast")));
        assert_eq!(Command::parse(b"PI\xffNG"), Err(CommandError::NotAscii));
        assert_eq!(Command::parse(&[b'A'; MAX_LINE + 1]), Err(CommandError::TooLong));
    }

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
    fn an_unknown_method_is_answered_with_the_list_of_methods() {
        let error = Command::parse(b"DRAW abrash38-1 exakt").unwrap_err().to_string();
        assert!(error.starts_with("`exakt`: unknown method; the methods are abrash_float,"), "{error}");
        assert!(error.ends_with(", exact"), "{error}");
    }

    #[test]
    fn pongs_and_readies_round_trip_and_reject_garbage() {
        let losses = LineLosses { overruns: 2, dropped: 0 };
        let pong = Pong { losses };
        assert_eq!(pong.to_string(), "pong overruns=2 dropped=0");
        assert_eq!(Pong::parse(&pong.to_string()), Some(pong));
        assert_eq!(Pong::parse("pong"), None);
        assert_eq!(Pong::parse("pong dropped=0 overruns=2"), None);
        assert!(!losses.none() && LineLosses::default().none());

        let display = Some(PciId { vendor: 0x1013, device: 0x00b8 });
        let ready = Ready { display, vga_mismatches: 3, losses };
        assert_eq!(ready.to_string(), "display=1013:00b8 vga_mismatches=3 overruns=2 dropped=0");
        assert_eq!(Ready::parse(&ready.to_string()), Some(ready));
        let headless = Ready { display: None, ..ready };
        assert_eq!(Ready::parse(&headless.to_string()), Some(headless));
        for garbage in [
            "display=1013:b8 vga_mismatches=3 overruns=2 dropped=0",
            "display=1013:00b8 vga_mismatches=3 overruns=2",
            "display=1013:00b8 vga_mismatches=3 overruns=2 dropped=0 more=1",
            "vga: 0 mismatches",
        ] {
            assert_eq!(Ready::parse(garbage), None, "{garbage}");
        }
    }

    #[test]
    fn bench_repeats_default_when_absent() {
        assert_eq!(
            Command::parse(b"BENCH abrash38-2"),
            Ok(Command::Bench { scene: "abrash38-2", repeats: BENCH_DEFAULT_REPEATS })
        );
        assert!((1..=BENCH_MAX_REPEATS).contains(&BENCH_DEFAULT_REPEATS));
    }

    #[test]
    fn every_frame_kind_round_trips_through_its_name() {
        for kind in FrameKind::ALL {
            assert_eq!(FrameKind::from_name(kind.name()), Some(kind));
        }
    }

    #[test]
    fn headers_round_trip_and_check_their_payload() {
        let header = FrameHeader::for_payload(FrameKind::Ok, b"pong");
        let text = header.to_string();
        assert_eq!(text, std::format!("@OK 4 {:08x}", crc32fast::hash(b"pong")));
        assert_eq!(FrameHeader::parse(&text), Some(header));
        assert!(header.matches(b"pong"));
        assert!(!header.matches(b"pang"));
        assert_eq!(FrameHeader::parse("@OK 4"), None);
        assert_eq!(FrameHeader::parse("@NOPE 4 00000000"), None);
        assert_eq!(FrameHeader::parse("OK 4 00000000"), None);
    }
}
