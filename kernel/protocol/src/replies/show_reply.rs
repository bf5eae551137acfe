//! The `OK` text of `SHOW`: what was drawn and what it cost.

use core::fmt;

use raster::MethodId;

use super::fields::{Fields, Malformed};

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
    /// Parses the text written by `Display`; every field must be there,
    /// once, in its order.
    pub fn parse(text: &'a str) -> Result<Self, Malformed> {
        let mut fields = Fields::new("SHOW", text);
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
        fields.end()?;
        Ok(reply)
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use crate::replies::fields::Expected;
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
        assert_eq!(text, "entry=race frame=3 method=wgt cycles=12345 allocs=0 polygons=9 refused=1 strays=0");
        assert_eq!(ShowReply::parse(&text), Ok(reply));
        let malformed = |expected| Err(Malformed { reply: "SHOW", expected });
        assert_eq!(ShowReply::parse("entry=race frame=3"), malformed(Expected::Field("method")));
        assert_eq!(ShowReply::parse(&text.replace("cycles=12345", "cycles=x")), malformed(Expected::Value("cycles")));
        assert_eq!(ShowReply::parse(&std::format!("{text} extra=1")), malformed(Expected::End));
        assert_eq!(ShowReply::parse(&text.replace("method=wgt", "method=wgt2")), malformed(Expected::Value("method")));
    }
}
