//! Host to kernel: the command lines, how they parse, and why one is
//! rejected.

use core::fmt;

use raster::MethodId;

use crate::replies::{ClockSource, Malformed, Prose};
use crate::{BENCH_DEFAULT_REPEATS, BENCH_MAX_REPEATS, EVERY_ENTRY, MAX_LINE};

/// Which CPU fault the test-only `FAULT` command provokes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FaultKind {
    /// `#DE`, vector 0: a division by zero.
    DivideError,
    /// `#UD`, vector 6: `ud2`, the instruction made to be undefined.
    InvalidOpcode,
    Breakpoint,
    PageFault,
    DoubleFault,
    Panic,
    /// An interrupt on a vector (0x20 to 0xFF; [`STRAY_VECTOR`] unless
    /// the line names another, `FAULT strayinterrupt 0x21`) raised as a
    /// device would raise it, through the local APIC where there is one.
    /// The stray kinds are the ones the kernel survives, answering `OK`.
    StrayInterrupt(u8),
    /// The RTC's IRQ 8, let through the two 8259s for one periodic
    /// interrupt: a device's IRQ on the 8259 path (vector 0x28).
    StrayIrq,
    /// The RTC's IRQ 8 routed through the I/O APIC as a level-triggered
    /// interrupt on [`STORM_VECTOR`], its line left high: it comes again
    /// after every end of interrupt, as a level-triggered source the
    /// firmware left unmasked does, until the kernel masks it.
    InterruptStorm,
}

/// The vector `FAULT strayinterrupt` raises when the line names none: in
/// the local APIC's priority class 9, which nothing on a PC is set up to
/// use while the kernel runs.
pub const STRAY_VECTOR: u8 = 0x99;
/// The vector `FAULT interruptstorm` routes the RTC's IRQ to.
pub const STORM_VECTOR: u8 = 0x9a;
/// The lowest vector a stray interrupt may have: below are the CPU's
/// exceptions.
pub const FIRST_INTERRUPT_VECTOR: u8 = 0x20;

impl FaultKind {
    /// Every kind, a stray interrupt on [`STRAY_VECTOR`].
    pub const ALL: [FaultKind; 9] = [
        FaultKind::DivideError,
        FaultKind::InvalidOpcode,
        FaultKind::Breakpoint,
        FaultKind::PageFault,
        FaultKind::DoubleFault,
        FaultKind::Panic,
        FaultKind::StrayInterrupt(STRAY_VECTOR),
        FaultKind::StrayIrq,
        FaultKind::InterruptStorm,
    ];

    pub const fn name(self) -> &'static str {
        match self {
            FaultKind::DivideError => "divideerror",
            FaultKind::InvalidOpcode => "invalidopcode",
            FaultKind::Breakpoint => "breakpoint",
            FaultKind::PageFault => "pagefault",
            FaultKind::DoubleFault => "doublefault",
            FaultKind::Panic => "panic",
            FaultKind::StrayInterrupt(_) => "strayinterrupt",
            FaultKind::StrayIrq => "strayirq",
            FaultKind::InterruptStorm => "interruptstorm",
        }
    }
}

/// A host request.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Command<'a> {
    /// `PING`: answers `OK` with a [`Pong`](crate::Pong), `pong overruns=N dropped=M`.
    Ping,
    /// `LIST`: answers a `LIST` frame, lines `scene NAME`, `show NAME FRAMES`
    /// and `method NAME`.
    List,
    /// `DRAW SCENE [METHOD]`: draws a built-in scene; answers `OK`.
    Draw { scene: &'a str, method: Option<MethodId> },
    /// `SHOW ENTRY FRAME [METHOD]`: draws frame FRAME of a show entry
    /// (`scenes::show`) exactly as the demo shows it, labels included, in
    /// the show's palette; answers `OK` with [`ShowReply`](crate::ShowReply)'s fields.
    Show { entry: &'a str, frame: u32, method: Option<MethodId> },
    /// `CLEAR C`: fills the screen with colour C.
    Clear(u8),
    /// `POLY METHOD <poly line>`: fills one polygon written as a scene-file
    /// `poly` line without the keyword, e.g. `POLY exact color=4 0,0 9,0 0,9`.
    Poly { method: MethodId, spec: &'a str },
    /// `UPLOAD NAME BYTES MEMORY CRC32`: starts the upload of a packed
    /// scene (`scenes::packed`) of BYTES bytes, whose CRC-32 is CRC32 (8
    /// lowercase hex digits) and which unpacks to at most MEMORY bytes,
    /// to be drawn by `DRAW NAME` and timed by `BENCH NAME`; drops the
    /// scene uploaded before. Answers `OK` with an
    /// [`UploadReply`](crate::UploadReply), or `ERR` if BYTES and MEMORY
    /// together pass [`UPLOAD_BUDGET`](crate::UPLOAD_BUDGET).
    Upload { name: &'a str, bytes: usize, memory: usize, crc: u32 },
    /// `CHUNK OFFSET DATA`: packed bytes of the upload under way, DATA in
    /// base64 (the host sends [`CHUNK_BYTES`](crate::CHUNK_BYTES) a chunk), at byte
    /// OFFSET, which must not pass the bytes received so far: a chunk sent
    /// again writes the same bytes again. Answers `OK` with a
    /// [`ChunkReply`](crate::ChunkReply).
    Chunk { offset: usize, data: &'a str },
    /// `DUMP`: answers a `DUMP` frame of [`DUMP_LEN`](crate::DUMP_LEN) bytes.
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
    /// `EXIT CODE`: leaves QEMU through isa-debug-exit with CODE (0-255);
    /// answered `ERR`, with nothing touched, on a machine the kernel has
    /// not identified as QEMU.
    Exit(u8),
    /// `FAULT KIND`: test only; provokes a fault, which must be reported
    /// (a stray interrupt, which must be survived and answered `OK`).
    /// Answered `ERR` on a machine the kernel has not identified as QEMU.
    Fault(FaultKind),
    /// `READY`: answers a `READY` frame as at boot, its line losses as of
    /// now: how a host that connects after the kernel booted learns what
    /// machine it talks to.
    Ready,
    /// `CLOCK`: answers `OK` with the time-stamp counter's rate and how the
    /// kernel measured it ([`TscRate`](crate::TscRate)), the unit of every
    /// rdtsc figure it reports.
    Clock,
    /// `CLOCK pit|pmtimer|hpet [stalled]`: test only, and only on QEMU as
    /// for `FAULT`: measures the TSC against that timer alone and makes it
    /// the kernel's clock, answering as `CLOCK` does (`ERR` if no such
    /// timer counts); `stalled`, with the kernel stalling itself inside
    /// the measurement as a system management interrupt would, to prove
    /// its defences.
    ForceClock { source: ClockSource, stalled: bool },
}

/// Why a command line was rejected.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CommandError<'a> {
    Empty,
    NotAscii,
    TooLong,
    Unknown(&'a str),
    /// What the line lacks, in words (`colour`, `fault kind`).
    MissingArgument(&'a str),
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

impl<'a> CommandError<'a> {
    /// Parses the text written by `Display`.
    pub fn parse(text: &'a str) -> Result<Self, Malformed> {
        let mut prose = Prose::new("ERR", text);
        let sentences = [
            ("empty command", CommandError::Empty),
            ("command is not printable ASCII", CommandError::NotAscii),
            ("command longer than ", CommandError::TooLong),
        ];
        let error = if let Some((_, error)) = sentences.into_iter().find(|(words, _)| prose.next_is(words)) {
            if error == CommandError::TooLong {
                prose.rest();
            }
            error
        } else if prose.next_is("unknown command ") {
            CommandError::Unknown(prose.quoted("")?)
        } else if prose.next_is("missing argument: ") {
            CommandError::MissingArgument(prose.rest())
        } else if prose.next_is("bad argument ") {
            CommandError::BadArgument(prose.quoted("")?)
        } else if prose.next_is("unexpected argument ") {
            CommandError::ExtraArgument(prose.quoted("")?)
        } else {
            let word = prose.quoted(": ")?;
            prose.rest();
            CommandError::UnknownMethod(word)
        };
        prose.written_by(error)
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
            "UPLOAD" => {
                let name = words.next().ok_or(CommandError::MissingArgument("name"))?;
                let bytes = parse_usize(words.next().ok_or(CommandError::MissingArgument("bytes"))?)?;
                let memory = parse_usize(words.next().ok_or(CommandError::MissingArgument("memory"))?)?;
                let crc = words.next().ok_or(CommandError::MissingArgument("CRC-32"))?;
                let crc = Some(crc)
                    .filter(|crc| crc.len() == 8 && crc.bytes().all(|b| matches!(b, b'0'..=b'9' | b'a'..=b'f')))
                    .and_then(|crc| u32::from_str_radix(crc, 16).ok())
                    .ok_or(CommandError::BadArgument(crc))?;
                Command::Upload { name, bytes, memory, crc }
            }
            "CHUNK" => Command::Chunk {
                offset: parse_usize(words.next().ok_or(CommandError::MissingArgument("offset"))?)?,
                data: words.next().ok_or(CommandError::MissingArgument("data"))?,
            },
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
            "READY" => Command::Ready,
            "CLOCK" => match words.next() {
                None => Command::Clock,
                Some(name) => {
                    let measurable = [ClockSource::Pit, ClockSource::PmTimer, ClockSource::Hpet];
                    let source = measurable.into_iter().find(|source| source.name() == name);
                    let source = source.ok_or(CommandError::BadArgument(name))?;
                    let stalled = match words.next() {
                        None => false,
                        Some("stalled") => true,
                        Some(word) => return Err(CommandError::BadArgument(word)),
                    };
                    Command::ForceClock { source, stalled }
                }
            },
            "DEMO" => Command::Demo {
                entry: words.next().filter(|&entry| entry != EVERY_ENTRY),
                method: words.next().map(parse_method).transpose()?,
            },
            "EXIT" => Command::Exit(parse_u8(words.next().ok_or(CommandError::MissingArgument("code"))?)?),
            "FAULT" => {
                let kind = words.next().ok_or(CommandError::MissingArgument("fault kind"))?;
                let fault =
                    FaultKind::ALL.into_iter().find(|k| k.name() == kind).ok_or(CommandError::BadArgument(kind))?;
                match (fault, words.next()) {
                    (FaultKind::StrayInterrupt(_), Some(word)) => {
                        let vector = word
                            .strip_prefix("0x")
                            .filter(|digits| digits.len() == 2)
                            .and_then(|digits| u8::from_str_radix(digits, 16).ok())
                            .filter(|&vector| {
                                vector >= FIRST_INTERRUPT_VECTOR && !word[2..].contains(char::is_uppercase)
                            })
                            .ok_or(CommandError::BadArgument(word))?;
                        Command::Fault(FaultKind::StrayInterrupt(vector))
                    }
                    (_, Some(extra)) => return Err(CommandError::ExtraArgument(extra)),
                    (fault, None) => Command::Fault(fault),
                }
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

/// A count written in decimal digits alone (no sign), so that a line
/// reads back as it was written.
fn parse_usize(word: &str) -> Result<usize, CommandError<'_>> {
    match word.bytes().all(|b| b.is_ascii_digit()) {
        true => word.parse().map_err(|_| CommandError::BadArgument(word)),
        false => Err(CommandError::BadArgument(word)),
    }
}

fn parse_method(word: &str) -> Result<MethodId, CommandError<'_>> {
    word.parse().map_err(|_| CommandError::UnknownMethod(word))
}

impl Command<'_> {
    /// The command's name, the first word of its line.
    pub fn name(&self) -> &'static str {
        match self {
            Command::Ping => "PING",
            Command::List => "LIST",
            Command::Draw { .. } => "DRAW",
            Command::Show { .. } => "SHOW",
            Command::Clear(_) => "CLEAR",
            Command::Poly { .. } => "POLY",
            Command::Upload { .. } => "UPLOAD",
            Command::Chunk { .. } => "CHUNK",
            Command::Dump => "DUMP",
            Command::VgaCheck => "VGACHECK",
            Command::Demo { .. } => "DEMO",
            Command::Bench { .. } => "BENCH",
            Command::Exit(_) => "EXIT",
            Command::Fault(_) => "FAULT",
            Command::Ready => "READY",
            Command::Clock | Command::ForceClock { .. } => "CLOCK",
        }
    }
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
            Command::Upload { name, bytes, memory, crc } => write!(f, "UPLOAD {name} {bytes} {memory} {crc:08x}"),
            Command::Chunk { offset, data } => write!(f, "CHUNK {offset} {data}"),
            Command::Dump => write!(f, "DUMP"),
            Command::Bench { scene, repeats } => write!(f, "BENCH {scene} {repeats}"),
            Command::VgaCheck => write!(f, "VGACHECK"),
            Command::Demo { entry: None, method: None } => write!(f, "DEMO"),
            Command::Demo { entry, method: None } => write!(f, "DEMO {}", entry.unwrap_or(EVERY_ENTRY)),
            Command::Demo { entry, method: Some(method) } => {
                write!(f, "DEMO {} {method}", entry.unwrap_or(EVERY_ENTRY))
            }
            Command::Exit(code) => write!(f, "EXIT {code}"),
            Command::Fault(FaultKind::StrayInterrupt(vector)) if *vector != STRAY_VECTOR => {
                write!(f, "FAULT strayinterrupt {vector:#04x}")
            }
            Command::Fault(kind) => write!(f, "FAULT {}", kind.name()),
            Command::Ready => write!(f, "READY"),
            Command::Clock => write!(f, "CLOCK"),
            Command::ForceClock { source, stalled: false } => write!(f, "CLOCK {}", source.name()),
            Command::ForceClock { source, stalled: true } => write!(f, "CLOCK {} stalled", source.name()),
        }
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
            Command::Upload { name: "map", bytes: 123_456, memory: 800_000, crc: 0x0012_abcd },
            Command::Chunk { offset: 0, data: "UExTMQ==" },
            Command::Chunk { offset: 6000, data: "AAEC" },
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
            Command::Fault(FaultKind::DivideError),
            Command::Fault(FaultKind::InvalidOpcode),
            Command::Fault(FaultKind::StrayInterrupt(STRAY_VECTOR)),
            Command::Fault(FaultKind::StrayInterrupt(0x20)),
            Command::Fault(FaultKind::StrayInterrupt(0xff)),
            Command::Fault(FaultKind::StrayIrq),
            Command::Fault(FaultKind::InterruptStorm),
            Command::Ready,
            Command::Clock,
            Command::ForceClock { source: ClockSource::Hpet, stalled: false },
            Command::ForceClock { source: ClockSource::Pit, stalled: true },
            Command::ForceClock { source: ClockSource::PmTimer, stalled: false },
        ];
        for command in commands {
            let text = command.to_string();
            assert_eq!(Command::parse(text.as_bytes()), Ok(command), "{text}");
            assert_eq!(text.split(' ').next(), Some(command.name()), "{text}");
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
        assert_eq!(Command::parse(b"CLOCK cpuid"), Err(CommandError::BadArgument("cpuid")));
        assert_eq!(Command::parse(b"CLOCK pit slow"), Err(CommandError::BadArgument("slow")));
        assert_eq!(Command::parse(b"CLOCK pit stalled now"), Err(CommandError::ExtraArgument("now")));
        assert_eq!(Command::parse(b"POLY exact"), Err(CommandError::MissingArgument("polygon")));
        assert_eq!(Command::parse(b"FAULT nap"), Err(CommandError::BadArgument("nap")));
        assert_eq!(Command::parse(b"FAULT strayinterrupt"), Ok(Command::Fault(FaultKind::StrayInterrupt(0x99))));
        assert_eq!(Command::parse(b"FAULT strayinterrupt 0x99"), Ok(Command::Fault(FaultKind::StrayInterrupt(0x99))));
        for vector in ["0x1f", "0x100", "0xFF", "255", "0x", "0x9"] {
            let line = std::format!("FAULT strayinterrupt {vector}");
            assert_eq!(Command::parse(line.as_bytes()), Err(CommandError::BadArgument(vector)), "{line}");
        }
        assert_eq!(Command::parse(b"FAULT strayirq 0x28"), Err(CommandError::ExtraArgument("0x28")));
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
        assert_eq!(Command::parse(b"UPLOAD map"), Err(CommandError::MissingArgument("bytes")));
        assert_eq!(Command::parse(b"UPLOAD map 10 20"), Err(CommandError::MissingArgument("CRC-32")));
        assert_eq!(Command::parse(b"UPLOAD map +10 20 0000abcd"), Err(CommandError::BadArgument("+10")));
        for crc in ["0000ABCD", "abcd", "0000abcd0", "xyzxyzxy"] {
            let line = std::format!("UPLOAD map 10 20 {crc}");
            assert_eq!(Command::parse(line.as_bytes()), Err(CommandError::BadArgument(crc)), "{line}");
        }
        assert_eq!(Command::parse(b"UPLOAD map 10 20 0000abcd x"), Err(CommandError::ExtraArgument("x")));
        assert_eq!(Command::parse(b"CHUNK 10"), Err(CommandError::MissingArgument("data")));
        assert_eq!(Command::parse(b"CHUNK -1 AAAA"), Err(CommandError::BadArgument("-1")));
        assert_eq!(Command::parse(b"CHUNK 0 AAAA BBBB"), Err(CommandError::ExtraArgument("BBBB")));
        assert_eq!(Command::parse(b"PI\xffNG"), Err(CommandError::NotAscii));
        assert_eq!(Command::parse(&[b'A'; MAX_LINE + 1]), Err(CommandError::TooLong));
    }

    #[test]
    fn an_unknown_method_is_answered_with_the_list_of_methods() {
        let error = Command::parse(b"DRAW abrash38-1 exakt").unwrap_err().to_string();
        assert!(error.starts_with("`exakt`: unknown method; the methods are abrash_float,"), "{error}");
        assert!(error.ends_with(", exact"), "{error}");
    }

    #[test]
    fn bench_repeats_default_when_absent() {
        assert_eq!(
            Command::parse(b"BENCH abrash38-2"),
            Ok(Command::Bench { scene: "abrash38-2", repeats: BENCH_DEFAULT_REPEATS })
        );
        assert!((1..=BENCH_MAX_REPEATS).contains(&BENCH_DEFAULT_REPEATS));
    }
}
