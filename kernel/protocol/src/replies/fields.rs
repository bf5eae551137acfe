//! What the `key=value` replies share: the reader of their fields, and
//! the error every reply's `parse` gives for a text its `Display` did not
//! write.

use core::fmt;
use core::iter::Peekable;
use core::str::{FromStr, Split};

/// A reply text its type's `Display` does not write: which reply, and
/// what was expected where the text went wrong.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Malformed {
    /// The reply, as the command it answers is named (`PING`, `SHOW`, ...).
    pub reply: &'static str,
    pub expected: Expected,
}

/// What a reply's text should have had where it went wrong.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Expected {
    /// The field `KEY=VALUE` with this key, next.
    Field(&'static str),
    /// A value of this field (or word) that reads as its type.
    Value(&'static str),
    /// Nothing more: the text goes on after its last field or line.
    End,
    /// The shape of the text at that point, in words.
    Shape(&'static str),
}

impl fmt::Display for Malformed {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "malformed {} reply: expected ", self.reply)?;
        match self.expected {
            Expected::Field(key) => write!(f, "the field `{key}=` next"),
            Expected::Value(key) => write!(f, "a valid value of `{key}`"),
            Expected::End => write!(f, "nothing more"),
            Expected::Shape(shape) => write!(f, "{shape}"),
        }
    }
}

impl core::error::Error for Malformed {}

/// Space-separated `key=value` fields read in a fixed order, as the
/// `READY`, `PING`, `CLOCK`, `SHOW`, `DRAW` and `DEMO` texts are written.
/// A field a kernel gained later is read with [`Fields::optional`] (or
/// looked for with [`Fields::next_is`]), so that a host still reads what
/// an older image says.
pub(crate) struct Fields<'a> {
    reply: &'static str,
    fields: Peekable<Split<'a, char>>,
}

impl<'a> Fields<'a> {
    /// The fields of `text`, the text of `reply` (named in errors).
    pub(crate) fn new(reply: &'static str, text: &'a str) -> Self {
        Self { reply, fields: text.split(' ').peekable() }
    }

    /// The error for this reply's text, `expected` missing.
    pub(crate) fn malformed(&self, expected: Expected) -> Malformed {
        Malformed { reply: self.reply, expected }
    }

    /// The value of the next field, which must be called `key`.
    pub(crate) fn text(&mut self, key: &'static str) -> Result<&'a str, Malformed> {
        let field = self.fields.next().and_then(|field| field.split_once('='));
        match field {
            Some((k, value)) if k == key => Ok(value),
            _ => Err(self.malformed(Expected::Field(key))),
        }
    }

    /// The next field's value, which must be called `key`, read by `read`.
    pub(crate) fn read<T>(&mut self, key: &'static str, read: impl FnOnce(&str) -> Option<T>) -> Result<T, Malformed> {
        let value = self.text(key)?;
        read(value).ok_or(self.malformed(Expected::Value(key)))
    }

    /// The next field's value, which must be called `key`, parsed.
    pub(crate) fn parsed<T: FromStr>(&mut self, key: &'static str) -> Result<T, Malformed> {
        self.read(key, |value| value.parse().ok())
    }

    /// Whether the next field is called `key` (it is then read as usual).
    pub(crate) fn next_is(&mut self, key: &str) -> bool {
        self.fields.peek().and_then(|field| field.split_once('=')).is_some_and(|(k, _)| k == key)
    }

    /// The next field's value parsed if it is called `key`; `None` if the
    /// next field is another (or there is none): a field an older kernel
    /// did not write, or one written only where it applies.
    pub(crate) fn optional<T: FromStr>(&mut self, key: &'static str) -> Result<Option<T>, Malformed> {
        match self.next_is(key) {
            true => self.parsed(key).map(Some),
            false => Ok(None),
        }
    }

    /// Succeeds if every field has been read.
    pub(crate) fn end(mut self) -> Result<(), Malformed> {
        match self.fields.next() {
            None => Ok(()),
            Some(_) => Err(self.malformed(Expected::End)),
        }
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use std::string::ToString;

    #[test]
    fn each_kind_of_malformed_text_says_what_was_expected() {
        let mut fields = Fields::new("SHOW", "frame=x cycles=9 extra");
        assert_eq!(
            fields.parsed::<u32>("entry").unwrap_err().to_string(),
            "malformed SHOW reply: expected the field `entry=` next"
        );
        let mut fields = Fields::new("SHOW", "frame=x cycles=9 extra");
        let error = fields.parsed::<u32>("frame").unwrap_err();
        assert_eq!(error, Malformed { reply: "SHOW", expected: Expected::Value("frame") });
        assert_eq!(error.to_string(), "malformed SHOW reply: expected a valid value of `frame`");
        assert_eq!(fields.optional::<u64>("allocs"), Ok(None));
        assert_eq!(fields.optional::<u64>("cycles"), Ok(Some(9)));
        assert_eq!(fields.end().unwrap_err().to_string(), "malformed SHOW reply: expected nothing more");
    }
}
