//! The `OK` texts of the commands that draw on the screen and say no
//! more than what they drew: `DRAW` and `POLY` ([`DrawReply`]), `CLEAR`
//! ([`Cleared`]).

use core::fmt;

use super::fields::{Expected, Fields, Malformed};

/// The `OK` text of `DRAW` and `POLY`: `polygons=N refused=M`, then
/// ` strays=K` only if a method broke the sink contract (spans outside the
/// screen, dropped by the kernel).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct DrawReply {
    pub polygons: usize,
    /// Polygons the method declined.
    pub refused: usize,
    /// Spans the method emitted outside the screen (a method bug).
    pub strays: usize,
}

impl fmt::Display for DrawReply {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "polygons={} refused={}", self.polygons, self.refused)?;
        if self.strays > 0 {
            write!(f, " strays={}", self.strays)?;
        }
        Ok(())
    }
}

impl DrawReply {
    /// Parses the text written by `Display` (which never writes
    /// `strays=0`).
    pub fn parse(text: &str) -> Result<Self, Malformed> {
        let mut fields = Fields::new("DRAW", text);
        let polygons = fields.parsed("polygons")?;
        let refused = fields.parsed("refused")?;
        let strays = match fields.optional("strays")? {
            Some(0) => return Err(fields.malformed(Expected::Value("strays"))),
            strays => strays.unwrap_or(0),
        };
        fields.end()?;
        Ok(Self { polygons, refused, strays })
    }
}

/// The `OK` text of `CLEAR C`: `clear C`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Cleared {
    pub color: u8,
}

impl fmt::Display for Cleared {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "clear {}", self.color)
    }
}

impl Cleared {
    /// Parses the text written by `Display`.
    pub fn parse(text: &str) -> Result<Self, Malformed> {
        let color = text.strip_prefix("clear ").and_then(|color| color.parse().ok());
        let color =
            color.ok_or(Malformed { reply: "CLEAR", expected: Expected::Shape("`clear` and a colour 0-255") })?;
        Ok(Self { color })
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use std::string::ToString;

    #[test]
    fn draw_replies_round_trip_and_reject_garbage() {
        let clean = DrawReply { polygons: 7, refused: 1, strays: 0 };
        assert_eq!(clean.to_string(), "polygons=7 refused=1");
        let stray = DrawReply { strays: 3, ..clean };
        assert_eq!(stray.to_string(), "polygons=7 refused=1 strays=3");
        for reply in [clean, stray] {
            assert_eq!(DrawReply::parse(&reply.to_string()), Ok(reply));
        }
        let malformed = |expected| Err(Malformed { reply: "DRAW", expected });
        for (garbage, expected) in [
            ("polygons=7", Expected::Field("refused")),
            ("refused=1 polygons=7", Expected::Field("polygons")),
            ("polygons=7 refused=x", Expected::Value("refused")),
            ("polygons=7 refused=1 strays=0", Expected::Value("strays")),
            ("polygons=7 refused=1 strays=2 more=1", Expected::End),
        ] {
            assert_eq!(DrawReply::parse(garbage), malformed(expected), "{garbage}");
        }
    }

    #[test]
    fn clear_replies_round_trip_and_reject_garbage() {
        assert_eq!(Cleared { color: 9 }.to_string(), "clear 9");
        for color in [0, 9, 255] {
            assert_eq!(Cleared::parse(&Cleared { color }.to_string()), Ok(Cleared { color }));
        }
        for garbage in ["clear", "clear 256", "clear 9 9", "CLEAR 9", "clear -1"] {
            let error = Cleared::parse(garbage).unwrap_err().to_string();
            assert_eq!(error, "malformed CLEAR reply: expected `clear` and a colour 0-255", "{garbage}");
        }
    }
}
