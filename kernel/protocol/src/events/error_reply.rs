//! The `ERR` frame: why a command line was not run, or failed. The kernel
//! keeps serving after each.

use core::fmt;

use scenes::file::LineError;

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
}

const NO_TIMER: &str = "no such timer counts on this machine: ";
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
        }
    }
}

impl<'a> ErrorReply<'a> {
    /// Parses the text written by `Display`.
    pub fn parse(text: &'a str) -> Result<Self, Malformed> {
        let mut prose = Prose::new("ERR", text);
        let reply = if prose.next_is("unknown scene ") {
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
        ] {
            assert!(ErrorReply::parse(garbage).is_err(), "{garbage:?}");
        }
    }
}
