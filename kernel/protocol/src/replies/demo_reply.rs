//! The `OK` text of `DEMO`: where the demo it starts plays from.

use core::fmt;

use raster::MethodId;

use super::fields::{Expected, Fields, Malformed};

/// What `DEMO` writes for the method when each entry keeps its own.
pub const OWN_METHOD: &str = "own";

/// The `OK` text of `DEMO`: `demo from=E stay=true|false method=M`, the
/// entry the demo starts from, whether it stays on it, and the method
/// every entry is drawn with ([`OWN_METHOD`] when each keeps its own).
/// The demo starts once the answer is sent.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DemoReply<'a> {
    pub from: &'a str,
    pub stay: bool,
    pub method: Option<MethodId>,
}

impl fmt::Display for DemoReply<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let method = self.method.map_or(OWN_METHOD, MethodId::name);
        write!(f, "demo from={} stay={} method={method}", self.from, self.stay)
    }
}

impl<'a> DemoReply<'a> {
    /// Parses the text written by `Display`.
    pub fn parse(text: &'a str) -> Result<Self, Malformed> {
        let shape = Malformed { reply: "DEMO", expected: Expected::Shape("`demo` and its fields") };
        let mut fields = Fields::new("DEMO", text.strip_prefix("demo ").ok_or(shape)?);
        let from = fields.text("from")?;
        let stay = fields.parsed("stay")?;
        let method = fields.read("method", |method| match method {
            OWN_METHOD => Some(None),
            name => name.parse().ok().map(Some),
        })?;
        fields.end()?;
        Ok(Self { from, stay, method })
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use std::string::ToString;

    #[test]
    fn demo_replies_round_trip_and_reject_garbage() {
        let own = DemoReply { from: "race", stay: true, method: None };
        assert_eq!(own.to_string(), "demo from=race stay=true method=own");
        let wgt = DemoReply { from: "abrash38-1", stay: false, method: Some(MethodId::Wgt) };
        assert_eq!(wgt.to_string(), "demo from=abrash38-1 stay=false method=wgt");
        for reply in [own, wgt] {
            assert_eq!(DemoReply::parse(&reply.to_string()), Ok(reply));
        }
        let malformed = |expected| Err(Malformed { reply: "DEMO", expected });
        for (garbage, expected) in [
            ("from=race stay=true method=own", Expected::Shape("`demo` and its fields")),
            ("demo from=race stay=yes method=own", Expected::Value("stay")),
            ("demo from=race stay=true method=fast", Expected::Value("method")),
            ("demo from=race method=own", Expected::Field("stay")),
            ("demo from=race stay=true method=own again", Expected::End),
        ] {
            assert_eq!(DemoReply::parse(garbage), malformed(expected), "{garbage}");
        }
    }
}
