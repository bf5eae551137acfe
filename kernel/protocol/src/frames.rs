//! Kernel to host: the frame every answer travels in, a header line
//! `@KIND LEN CRC32` and the payload it announces.

use core::fmt;

use crate::FRAME_MARK;

/// What a frame carries.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FrameKind {
    /// Sent once at boot when the console is ready; payload: a [`Ready`](crate::Ready).
    Ready,
    /// A command succeeded; payload: a short text.
    Ok,
    /// A command failed; payload: what was wrong. The kernel keeps serving.
    Err,
    /// Answer to `LIST`.
    List,
    /// Answer to `DUMP`: [`DUMP_LEN`](crate::DUMP_LEN) bytes.
    Dump,
    /// Answer to `BENCH`: [`BENCH_UNIT_LINE`](crate::BENCH_UNIT_LINE), then a `METHOD CYCLES
    /// REFUSED [REFUSAL]` line per method, in [`MethodId::ALL`](raster::MethodId::ALL) order,
    /// each ending in `\n`: the polygons of the scene it declined, and the
    /// first one's reason (`raster::Refusal::name`).
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
