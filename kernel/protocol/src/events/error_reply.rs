//! The `ERR` frame: why a command line was not run, or failed. The kernel
//! keeps serving after each.

use core::fmt;

use scenes::file::LineError;
use scenes::packed::UnpackError;

use crate::commands::CommandError;
use crate::replies::{writes, ClockSource, Expected, Malformed, Prose, VgaCheck};
use crate::sealed::Damaged;

/// An `ERR` frame's text.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ErrorReply<'a> {
    /// The line is no command ([`CommandError`]'s text).
    Command(CommandError<'a>),
    /// A sealed line whose seal does not check ([`Damaged`]'s text).
    Damaged,
    /// ``unknown scene `NAME` ``: `DRAW` or `BENCH` of a scene that is not
    /// built in.
    UnknownScene(&'a str),
    /// ``unknown show entry `NAME` ``: `SHOW` or `DEMO` of an entry the
    /// show does not have.
    UnknownShowEntry(&'a str),
    /// `POLY`'s polygon is no scene file `poly` line (the scene file's own
    /// error text, `scenes::file::LineError`).
    Polygon(LineError),
    /// `COMMAND refused: the machine is not identified as QEMU
    /// (machine=unknown)`: `EXIT` or `FAULT` where the kernel has not
    /// identified QEMU.
    NotQemu(&'a str),
    /// `CLOCK SOURCE`: no such timer counts on this machine.
    NoTimer(ClockSource),
    /// `VGACHECK` found registers that do not read back as written, or
    /// nothing that shows the frame.
    VgaCheck(VgaCheck),
    /// `UPLOAD` of BYTES packed bytes that unpack to MEMORY bytes, which
    /// together pass the kernel's budget: nothing is kept.
    OverBudget { bytes: usize, memory: usize, budget: usize },
    /// `UPLOAD` under the name of a built-in scene, which `DRAW` would
    /// find first.
    BuiltinName(&'a str),
    /// `CHUNK` with no upload under way.
    NoUpload,
    /// `CHUNK` of BYTES bytes at OFFSET past the bytes received so far, or
    /// past the upload's end.
    ChunkOutOfPlace { offset: usize, bytes: usize, received: usize, total: usize },
    /// `CHUNK` whose data is not base64.
    NotBase64,
    /// The whole upload arrived with another CRC-32 than `UPLOAD`
    /// declared: it is dropped.
    UploadDamaged { declared: u32, actual: u32 },
    /// The whole upload arrived and checked, but is no packed scene (or
    /// holds more than it declared): it is dropped.
    Unpack(UnpackError),
}

const NO_TIMER: &str = "no such timer counts on this machine: ";
const NO_UPLOAD: &str = "no upload under way: UPLOAD starts one";
const NOT_BASE64: &str = "chunk data is not base64";
const DROPPED: &str = "upload dropped: ";
const BUILTIN_NAME: &str = "` is a built-in scene's name";
const NOT_QEMU: &str = " refused: the machine is not identified as QEMU (machine=unknown)";

impl fmt::Display for ErrorReply<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ErrorReply::Command(error) => write!(f, "{error}"),
            ErrorReply::Damaged => write!(f, "{Damaged}"),
            ErrorReply::UnknownScene(name) => write!(f, "unknown scene `{name}`"),
            ErrorReply::UnknownShowEntry(name) => write!(f, "unknown show entry `{name}`"),
            ErrorReply::Polygon(error) => write!(f, "{error}"),
            ErrorReply::NotQemu(command) => write!(f, "{command}{NOT_QEMU}"),
            ErrorReply::NoTimer(source) => write!(f, "{NO_TIMER}{}", source.name()),
            ErrorReply::VgaCheck(check) => write!(f, "{check}"),
            ErrorReply::OverBudget { bytes, memory, budget } => write!(
                f,
                "upload refused: {bytes} packed bytes and {memory} unpacked pass the kernel's budget of {budget} \
                 bytes; nothing was kept"
            ),
            ErrorReply::BuiltinName(name) => write!(f, "upload refused: `{name}{BUILTIN_NAME}"),
            ErrorReply::NoUpload => write!(f, "{NO_UPLOAD}"),
            ErrorReply::ChunkOutOfPlace { offset, bytes, received, total } => {
                write!(
                    f,
                    "chunk of {bytes} bytes at offset {offset} does not fit: {received} of {total} bytes received"
                )
            }
            ErrorReply::NotBase64 => write!(f, "{NOT_BASE64}"),
            ErrorReply::UploadDamaged { declared, actual } => {
                write!(f, "{DROPPED}its CRC-32 is {actual:08x}, not the {declared:08x} declared")
            }
            ErrorReply::Unpack(error) => write!(f, "{DROPPED}{error}"),
        }
    }
}

impl<'a> ErrorReply<'a> {
    /// Parses the text written by `Display`.
    pub fn parse(text: &'a str) -> Result<Self, Malformed> {
        let mut prose = Prose::new("ERR", text);
        let builtin = text.strip_prefix("upload refused: `").and_then(|rest| rest.strip_suffix(BUILTIN_NAME));
        let reply = if let Some(name) = builtin {
            prose.rest();
            ErrorReply::BuiltinName(name)
        } else if prose.next_is("upload refused: ") {
            let bytes = prose.number("bytes")?;
            prose.expect(" packed bytes and ", "the packed bytes")?;
            let memory = prose.number("memory")?;
            prose.expect(" unpacked pass the kernel's budget of ", "the budget")?;
            let budget = prose.number("budget")?;
            prose.expect(" bytes; nothing was kept", "nothing was kept")?;
            ErrorReply::OverBudget { bytes, memory, budget }
        } else if prose.next_is("chunk of ") {
            let bytes = prose.number("bytes")?;
            prose.expect(" bytes at offset ", "the offset")?;
            let offset = prose.number("offset")?;
            prose.expect(" does not fit: ", "does not fit")?;
            let received = prose.number("received")?;
            prose.expect(" of ", "of")?;
            let total = prose.number("total")?;
            prose.expect(" bytes received", "bytes received")?;
            ErrorReply::ChunkOutOfPlace { offset, bytes, received, total }
        } else if prose.next_is(DROPPED) {
            let rest = prose.rest();
            match rest.strip_prefix("its CRC-32 is ") {
                Some(crcs) => {
                    let crc = |digits: &str| u32::from_str_radix(digits, 16).ok().filter(|_| digits.len() == 8);
                    let (actual, declared) = crcs
                        .strip_suffix(" declared")
                        .and_then(|crcs| crcs.split_once(", not the "))
                        .and_then(|(actual, declared)| Some((crc(actual)?, crc(declared)?)))
                        .ok_or(prose.malformed(Expected::Shape("two CRC-32s")))?;
                    ErrorReply::UploadDamaged { declared, actual }
                }
                None => ErrorReply::Unpack(
                    UnpackError::parse(rest)
                        .ok_or(prose.malformed(Expected::Shape("why the upload does not unpack")))?,
                ),
            }
        } else if prose.next_is(NO_UPLOAD) {
            ErrorReply::NoUpload
        } else if prose.next_is(NOT_BASE64) {
            ErrorReply::NotBase64
        } else if prose.next_is("unknown scene ") {
            ErrorReply::UnknownScene(prose.quoted("")?)
        } else if prose.next_is("unknown show entry ") {
            ErrorReply::UnknownShowEntry(prose.quoted("")?)
        } else if prose.next_is(NO_TIMER) {
            let source = ClockSource::from_name(prose.rest());
            ErrorReply::NoTimer(source.ok_or(prose.malformed(Expected::Value("timer")))?)
        } else if let Some(command) = text.strip_suffix(NOT_QEMU).filter(|word| !word.contains(' ')) {
            prose.rest();
            ErrorReply::NotQemu(command)
        } else if let Ok(check) = VgaCheck::parse(text) {
            prose.rest();
            ErrorReply::VgaCheck(check)
        } else if let Ok(error) = CommandError::parse(text) {
            prose.rest();
            ErrorReply::Command(error)
        } else if let Some(error) = LineError::parse(text) {
            prose.rest();
            ErrorReply::Polygon(error)
        } else {
            prose.rest();
            match writes(&Damaged, text) {
                true => ErrorReply::Damaged,
                false => return Err(prose.malformed(Expected::Shape("an ERR text"))),
            }
        };
        prose.written_by(reply)
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use crate::replies::{Mismatch, RegisterGroup};
    use std::string::{String, ToString};
    use std::vec;

    #[test]
    fn every_error_round_trips_through_its_text() {
        let errors = [
            ErrorReply::Command(CommandError::Empty),
            ErrorReply::Command(CommandError::NotAscii),
            ErrorReply::Command(CommandError::TooLong),
            ErrorReply::Command(CommandError::Unknown("FROB")),
            ErrorReply::Command(CommandError::Unknown("a`b")),
            ErrorReply::Command(CommandError::MissingArgument("colour")),
            ErrorReply::Command(CommandError::BadArgument("256")),
            ErrorReply::Command(CommandError::UnknownMethod("exakt")),
            ErrorReply::Command(CommandError::ExtraArgument("now")),
            ErrorReply::Damaged,
            ErrorReply::UnknownScene("no-such-scene"),
            ErrorReply::UnknownShowEntry("nope`"),
            ErrorReply::Polygon(LineError::BadColor(String::from("999"))),
            ErrorReply::Polygon(LineError::MissingColor),
            ErrorReply::Polygon(LineError::ControlCharacter('\u{7}')),
            ErrorReply::NotQemu("EXIT"),
            ErrorReply::NotQemu("FAULT"),
            ErrorReply::NoTimer(ClockSource::Hpet),
            ErrorReply::VgaCheck(VgaCheck::Nothing),
            ErrorReply::VgaCheck(VgaCheck::Vga {
                mismatches: vec![Mismatch { group: RegisterGroup::Misc, index: 0, expected: 0x63, actual: 0x62 }],
                window: None,
                pat: 0x0007040600070406,
            }),
            ErrorReply::OverBudget { bytes: 400_000, memory: 900_000, budget: 1 << 20 },
            ErrorReply::BuiltinName("abrash38-1"),
            ErrorReply::BuiltinName("a`b"),
            ErrorReply::NoUpload,
            ErrorReply::ChunkOutOfPlace { offset: 9000, bytes: 3000, received: 6000, total: 10_000 },
            ErrorReply::NotBase64,
            ErrorReply::UploadDamaged { declared: 0x0000_beef, actual: 0xdead_0000 },
            ErrorReply::Unpack(UnpackError::Truncated),
            ErrorReply::Unpack(UnpackError::BadOp(7)),
            ErrorReply::Unpack(UnpackError::OverBudget { budget: 4096 }),
        ];
        for error in errors {
            let text = error.to_string();
            assert_eq!(ErrorReply::parse(&text), Ok(error), "{text}");
        }
    }

    #[test]
    fn the_texts_are_the_ones_the_protocol_page_shows() {
        assert_eq!(ErrorReply::UnknownScene("x").to_string(), "unknown scene `x`");
        assert_eq!(ErrorReply::UnknownShowEntry("x").to_string(), "unknown show entry `x`");
        assert_eq!(
            ErrorReply::NotQemu("EXIT").to_string(),
            "EXIT refused: the machine is not identified as QEMU (machine=unknown)"
        );
        assert_eq!(
            ErrorReply::Damaged.to_string(),
            "damaged sealed line: its CRC-32 or sequence number does not check; nothing was run"
        );
    }

    #[test]
    fn texts_the_kernel_would_not_write_are_refused() {
        for garbage in [
            "",
            "unknown scene x",
            "unknown scene `x` now",
            "EXIT refused",
            "EXIT now refused: the machine is not identified as QEMU (machine=unknown)",
            "unknown command",
            "bad colour `999`",
            "vga: 2 mismatches",
            "upload refused: 1 packed bytes and 2 unpacked pass the kernel's budget of 3 bytes",
            "upload dropped: its CRC-32 is beef, not the 0000beef declared",
            "upload dropped: the dog ate it",
            "chunk of 1 bytes at offset 2 does not fit: 3 of 4 bytes",
        ] {
            assert!(ErrorReply::parse(garbage).is_err(), "{garbage:?}");
        }
    }
}
