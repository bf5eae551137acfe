//! The `OK` texts of an upload: `UPLOAD`'s ([`UploadReply`]), which
//! states the kernel's budget, and each `CHUNK`'s ([`ChunkReply`]), which
//! says how far the upload has come.

use core::fmt;

use super::fields::{Expected, Fields, Malformed};

/// The `OK` text of `UPLOAD NAME BYTES MEMORY CRC32`:
/// `upload name=NAME bytes=B memory=M budget=U`, the upload the kernel now
/// waits for and the budget it was held to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct UploadReply<'a> {
    pub name: &'a str,
    /// Packed bytes to come.
    pub bytes: usize,
    /// Bytes of memory the unpacked scene will hold, as declared.
    pub memory: usize,
    /// The kernel's budget for both ([`crate::UPLOAD_BUDGET`]).
    pub budget: usize,
}

impl fmt::Display for UploadReply<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let UploadReply { name, bytes, memory, budget } = self;
        write!(f, "upload name={name} bytes={bytes} memory={memory} budget={budget}")
    }
}

impl<'a> UploadReply<'a> {
    /// Parses the text written by `Display`.
    pub fn parse(text: &'a str) -> Result<Self, Malformed> {
        let shape = Malformed { reply: "UPLOAD", expected: Expected::Shape("`upload` and its fields") };
        let mut fields = Fields::new("UPLOAD", text.strip_prefix("upload ").ok_or(shape)?);
        let name = fields.text("name")?;
        if name.is_empty() {
            return Err(fields.malformed(Expected::Value("name")));
        }
        let bytes = fields.parsed("bytes")?;
        let memory = fields.parsed("memory")?;
        let budget = fields.parsed("budget")?;
        fields.end()?;
        Ok(Self { name, bytes, memory, budget })
    }
}

/// The `OK` text of `CHUNK OFFSET DATA`: `chunk received=R total=T`, the
/// packed bytes received from the start without a gap, of the upload's
/// total. The chunk that brings `received` to `total` is answered once the
/// upload has checked and unpacked: the scene is then drawable by its
/// name.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ChunkReply {
    pub received: usize,
    pub total: usize,
}

impl ChunkReply {
    /// Whether the whole upload has arrived (and unpacked).
    pub fn complete(&self) -> bool {
        self.received == self.total
    }

    /// Parses the text written by `Display`.
    pub fn parse(text: &str) -> Result<Self, Malformed> {
        let shape = Malformed { reply: "CHUNK", expected: Expected::Shape("`chunk` and its fields") };
        let mut fields = Fields::new("CHUNK", text.strip_prefix("chunk ").ok_or(shape)?);
        let received = fields.parsed("received")?;
        let total = fields.parsed("total")?;
        fields.end()?;
        Ok(Self { received, total })
    }
}

impl fmt::Display for ChunkReply {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "chunk received={} total={}", self.received, self.total)
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use std::string::ToString;

    #[test]
    fn upload_replies_round_trip_and_reject_garbage() {
        let reply = UploadReply { name: "map", bytes: 1200, memory: 4096, budget: 1 << 20 };
        assert_eq!(reply.to_string(), "upload name=map bytes=1200 memory=4096 budget=1048576");
        assert_eq!(UploadReply::parse(&reply.to_string()), Ok(reply));
        let malformed = |expected| Err(Malformed { reply: "UPLOAD", expected });
        for (garbage, expected) in [
            ("upload name= bytes=1 memory=2 budget=3", Expected::Value("name")),
            ("name=map bytes=1 memory=2 budget=3", Expected::Shape("`upload` and its fields")),
            ("upload name=map bytes=x memory=2 budget=3", Expected::Value("bytes")),
            ("upload name=map bytes=1 memory=2", Expected::Field("budget")),
            ("upload name=map bytes=1 memory=2 budget=3 more=4", Expected::End),
        ] {
            assert_eq!(UploadReply::parse(garbage), malformed(expected), "{garbage}");
        }
    }

    #[test]
    fn chunk_replies_round_trip_and_say_when_the_upload_is_whole() {
        let partial = ChunkReply { received: 3000, total: 7000 };
        assert_eq!(partial.to_string(), "chunk received=3000 total=7000");
        assert!(!partial.complete());
        let whole = ChunkReply { received: 7000, total: 7000 };
        assert!(whole.complete());
        for reply in [partial, whole] {
            assert_eq!(ChunkReply::parse(&reply.to_string()), Ok(reply));
        }
        for garbage in ["chunk received=1", "received=1 total=2", "chunk received=1 total=2 x=3"] {
            assert!(ChunkReply::parse(garbage).is_err(), "{garbage}");
        }
    }
}
