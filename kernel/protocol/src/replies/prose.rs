//! The reader of the texts written as sentences for people (`VGACHECK`,
//! `ERR`, `LOG`, `FATAL`, the `OK` of `FAULT strayinterrupt`): each is
//! read left to right, word by word as its `Display` writes it, and then
//! held to that `Display` ([`Prose::written_by`]), so that a text the
//! kernel would not write is refused however close it comes.

use alloc::vec::Vec;
use core::fmt::{self, Write};
use core::str::FromStr;

use super::fields::{Expected, Malformed};

/// A text being read, from the left.
pub(crate) struct Prose<'a> {
    reply: &'static str,
    text: &'a str,
    rest: &'a str,
}

impl<'a> Prose<'a> {
    /// `text`, the text of `reply` (named in errors).
    pub(crate) fn new(reply: &'static str, text: &'a str) -> Self {
        Self { reply, text, rest: text }
    }

    /// The error for this text, `expected` where it went wrong.
    pub(crate) fn malformed(&self, expected: Expected) -> Malformed {
        Malformed { reply: self.reply, expected }
    }

    /// Whether the text goes on with `words`; if so they are read.
    pub(crate) fn next_is(&mut self, words: &str) -> bool {
        match self.rest.strip_prefix(words) {
            Some(rest) => {
                self.rest = rest;
                true
            }
            None => false,
        }
    }

    /// Reads `words`, which must come next (`shape` says what was
    /// expected there, for the error).
    pub(crate) fn expect(&mut self, words: &str, shape: &'static str) -> Result<(), Malformed> {
        match self.next_is(words) {
            true => Ok(()),
            false => Err(self.malformed(Expected::Shape(shape))),
        }
    }

    /// The text up to the first `end` (which is read too).
    pub(crate) fn until(&mut self, end: &str, shape: &'static str) -> Result<&'a str, Malformed> {
        let (before, after) = self.rest.split_once(end).ok_or(self.malformed(Expected::Shape(shape)))?;
        self.rest = after;
        Ok(before)
    }

    /// The rest of the text, all of it read.
    pub(crate) fn rest(&mut self) -> &'a str {
        core::mem::take(&mut self.rest)
    }

    /// A decimal number, `what` in errors.
    pub(crate) fn number<T: FromStr>(&mut self, what: &'static str) -> Result<T, Malformed> {
        let digits = self.rest.bytes().take_while(u8::is_ascii_digit).count();
        let (number, rest) = self.rest.split_at(digits);
        let value = number.parse().map_err(|_| self.malformed(Expected::Value(what)))?;
        self.rest = rest;
        Ok(value)
    }

    /// A number in hex after `0x`, `what` in errors.
    pub(crate) fn hex(&mut self, what: &'static str) -> Result<u64, Malformed> {
        let rest = self.rest.strip_prefix("0x").ok_or(self.malformed(Expected::Value(what)))?;
        let digits = rest.bytes().take_while(u8::is_ascii_hexdigit).count();
        let value = u64::from_str_radix(&rest[..digits], 16).map_err(|_| self.malformed(Expected::Value(what)))?;
        self.rest = &rest[digits..];
        Ok(value)
    }

    /// A number in hex after `0x` that fits `T`, `what` in errors.
    pub(crate) fn hex_of<T: TryFrom<u64>>(&mut self, what: &'static str) -> Result<T, Malformed> {
        let value = self.hex(what)?;
        T::try_from(value).map_err(|_| self.malformed(Expected::Value(what)))
    }

    /// A word between backticks (it may hold backticks itself: the last
    /// one before `after` closes it), and then `after`.
    pub(crate) fn quoted(&mut self, after: &str) -> Result<&'a str, Malformed> {
        let shape = "a word between backticks";
        let rest = self.rest.strip_prefix('`').ok_or(self.malformed(Expected::Shape(shape)))?;
        // A command's words hold no spaces, and every `after` does: the
        // first backtick followed by `after` closes the word.
        let close = match after {
            "" => rest.len().checked_sub(1),
            _ => rest.match_indices(after).map(|(at, _)| at).find(|&at| rest[..at].ends_with('`')).map(|at| at - 1),
        };
        let close = close.filter(|&at| rest[at..].starts_with('`')).ok_or(self.malformed(Expected::Shape(shape)))?;
        self.rest = &rest[close + 1 + after.len()..];
        Ok(&rest[..close])
    }

    /// Bytes written by `escape_ascii` up to the `"` that ends them
    /// (which is read too): `\t`, `\r`, `\n`, `\\`, `\'`, `\"` and
    /// `\xNN` undone.
    pub(crate) fn escaped(&mut self, what: &'static str) -> Result<Vec<u8>, Malformed> {
        let malformed = self.malformed(Expected::Value(what));
        let mut bytes = Vec::new();
        let mut rest = self.rest.bytes();
        loop {
            let byte = match rest.next().ok_or(malformed)? {
                b'"' => break,
                b'\\' => match rest.next().ok_or(malformed)? {
                    b't' => b'\t',
                    b'r' => b'\r',
                    b'n' => b'\n',
                    b'x' => {
                        let digits = [rest.next().ok_or(malformed)?, rest.next().ok_or(malformed)?];
                        let digits = core::str::from_utf8(&digits).map_err(|_| malformed)?;
                        u8::from_str_radix(digits, 16).map_err(|_| malformed)?
                    }
                    quoted @ (b'\\' | b'\'' | b'"') => quoted,
                    _ => return Err(malformed),
                },
                byte => byte,
            };
            bytes.push(byte);
        }
        self.rest = &self.rest[self.rest.len() - rest.len()..];
        Ok(bytes)
    }

    /// Succeeds if the whole text was read and `value`'s `Display` writes
    /// it byte for byte (the same numbers in the same digits, the same
    /// words), then gives `value`.
    pub(crate) fn written_by<T: fmt::Display>(self, value: T) -> Result<T, Malformed> {
        if !self.rest.is_empty() {
            return Err(self.malformed(Expected::End));
        }
        match writes(&value, self.text) {
            true => Ok(value),
            false => Err(self.malformed(Expected::Shape("the text as the kernel writes it"))),
        }
    }
}

/// Whether `value`'s `Display` writes exactly `text` (compared as it is
/// written: nothing is allocated).
pub(crate) fn writes(value: &impl fmt::Display, text: &str) -> bool {
    struct Compare<'a>(&'a str);
    impl Write for Compare<'_> {
        fn write_str(&mut self, written: &str) -> fmt::Result {
            self.0 = self.0.strip_prefix(written).ok_or(fmt::Error)?;
            Ok(())
        }
    }
    let mut compare = Compare(text);
    write!(compare, "{value}").is_ok() && compare.0.is_empty()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_text_is_read_word_by_word_and_held_to_its_display() {
        let mut prose = Prose::new("LOG", "vector 0x99, 12 so far, `a`b`; done");
        prose.expect("vector ", "`vector`").unwrap();
        assert_eq!(prose.hex_of::<u8>("vector"), Ok(0x99));
        prose.expect(", ", "a comma").unwrap();
        assert_eq!(prose.number::<u32>("count"), Ok(12));
        assert!(prose.next_is(" so far, "));
        assert_eq!(prose.quoted("; "), Ok("a`b"));
        assert_eq!(prose.rest(), "done");
        assert!(writes(&"abc", "abc"));
        assert!(!writes(&"abc", "abcd"));
        assert!(!writes(&"abc", "ab"));
        let prose = Prose::new("LOG", "0x0e");
        assert!(prose.written_by(format_args!("0x0e")).is_err(), "the text was not read");
        let mut prose = Prose::new("LOG", "0xe");
        let value = prose.hex("x").unwrap();
        let error = prose.written_by(alloc::format!("{value:#04x}")).unwrap_err();
        assert_eq!(error.expected, Expected::Shape("the text as the kernel writes it"));
    }
}
