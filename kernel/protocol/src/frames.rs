//! Kernel to host: the frame every answer travels in, a header line
//! `@KIND LEN CRC32` (with ` #SEQ` after it when it answers a sealed
//! command) and the payload it announces.

use core::fmt::{self, Write};

use crate::sealed::{Crc32Writer, SEAL_MARK};
use crate::FRAME_MARK;

/// What a frame carries.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FrameKind {
    /// Sent once at boot when the server is ready; payload: a [`Ready`](crate::Ready).
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
    /// The payload's CRC-32, continued over the sequence word (`#SEQ`)
    /// when there is one: a damaged sequence number fails the check like a
    /// damaged payload, so a reply cannot pass for the answer to another
    /// line.
    pub crc: u32,
    /// The sequence number of the sealed command line this frame answers
    /// (`crate::sealed`); `None` for a plain line's answer and for the
    /// frames nobody asked for (`READY` at boot, `LOG`, `FATAL`).
    pub seq: Option<u32>,
}

impl FrameHeader {
    /// The header for `payload`, answering no sealed line.
    pub fn for_payload(kind: FrameKind, payload: &[u8]) -> Self {
        Self::for_reply(kind, payload, None)
    }

    /// The header for `payload` answering the sealed line numbered `seq`
    /// (or a plain line, for `None`).
    pub fn for_reply(kind: FrameKind, payload: &[u8], seq: Option<u32>) -> Self {
        Self { kind, len: payload.len(), crc: checksum(payload, seq), seq }
    }

    /// Parses a header line (without `\n`); `None` if it is not one.
    pub fn parse(line: &str) -> Option<Self> {
        let rest = line.strip_prefix(FRAME_MARK as char)?;
        let mut words = rest.split(' ');
        let kind = FrameKind::from_name(words.next()?)?;
        let len = words.next()?.parse().ok()?;
        let crc = words.next().filter(|w| w.len() == 8)?;
        let crc = u32::from_str_radix(crc, 16).ok()?;
        let seq = match words.next() {
            None => None,
            Some(word) => {
                let digits = word.strip_prefix(SEAL_MARK as char)?;
                if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
                    return None;
                }
                Some(digits.parse().ok()?)
            }
        };
        words.next().is_none().then_some(Self { kind, len, crc, seq })
    }

    /// Whether `payload` is the one this header announced.
    pub fn matches(&self, payload: &[u8]) -> bool {
        payload.len() == self.len && checksum(payload, self.seq) == self.crc
    }
}

/// The CRC-32 of `payload`, then of the sequence word `#SEQ` if any.
fn checksum(payload: &[u8], seq: Option<u32>) -> u32 {
    let mut crc = Crc32Writer(crc32fast::Hasher::new());
    crc.0.update(payload);
    if let Some(seq) = seq {
        // Writing to a hasher cannot fail.
        let _ = write!(crc, "{}{seq}", SEAL_MARK as char);
    }
    crc.0.finalize()
}

impl fmt::Display for FrameHeader {
    /// The header line without its `\n`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "@{} {} {:08x}", self.kind.name(), self.len, self.crc)?;
        match self.seq {
            Some(seq) => write!(f, " {}{seq}", SEAL_MARK as char),
            None => Ok(()),
        }
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

    #[test]
    fn a_reply_header_echoes_its_sequence_number_under_the_crc() {
        let header = FrameHeader::for_reply(FrameKind::Ok, b"pong", Some(41));
        let text = header.to_string();
        let mut covered = b"pong".to_vec();
        covered.extend_from_slice(b"#41");
        assert_eq!(text, std::format!("@OK 4 {:08x} #41", crc32fast::hash(&covered)));
        assert_eq!(FrameHeader::parse(&text), Some(header));
        assert!(header.matches(b"pong"));
        // The same payload under another sequence number does not check:
        // a late reply cannot pass for the answer to a later line.
        let other = FrameHeader { seq: Some(42), ..header };
        assert!(!other.matches(b"pong"));
        assert!(!FrameHeader::for_payload(FrameKind::Ok, b"pong").matches(b"pang"));
        for garbage in ["@OK 4 00000000 41", "@OK 4 00000000 #", "@OK 4 00000000 #4x", "@OK 4 00000000 #1 #2"] {
            assert_eq!(FrameHeader::parse(garbage), None, "{garbage}");
        }
    }
}
