//! A kernel's answer to a command, decoded from its frame: the texts
//! `protocol` reads back, and the `DUMP` payload as a picture.

use std::time::Duration;

use anyhow::{bail, ensure, Context, Result};
use protocol::{BenchReply, BenchRow, ErrorReply, FatalReport, FrameKind, Listing, DUMP_LEN, FRAMEBUFFER_LEN};
use raster::SCREEN;
use scenes::palette::ENTRIES;

use super::frame_reader::Frame;
use crate::picture::Image;

/// Longest wait for the answer to one command (a dump is 64 KB through an
/// emulated UART).
pub const REPLY_TIMEOUT: Duration = Duration::from_secs(60);

/// A kernel's answer to a command, decoded.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Reply {
    Ready(String),
    Ok(String),
    /// An `ERR` frame's text, which [`ErrorReply::parse`] reads (checked
    /// when the frame was decoded).
    Err(String),
    List(Listing),
    Dump(Box<Dump>),
    /// The answer to `BENCH`: a row per method, in order.
    Bench(Vec<BenchRow>),
    /// A `FATAL` frame's text, which [`FatalReport::parse`] reads (checked when
    /// the frame was decoded).
    Fatal(String),
}

impl Reply {
    pub(crate) fn decode(frame: Frame) -> Result<Self> {
        Ok(match frame.kind {
            FrameKind::Ready => Reply::Ready(frame.text()),
            FrameKind::Ok => Reply::Ok(frame.text()),
            FrameKind::Err => {
                let text = frame.text();
                ErrorReply::parse(&text).with_context(|| format!("ERR \"{text}\""))?;
                Reply::Err(text)
            }
            FrameKind::List => {
                let text = frame.text();
                Reply::List(Listing::parse(&text).with_context(|| format!("LIST {text:?}"))?)
            }
            FrameKind::Dump => Reply::Dump(Box::new(Dump::parse(&frame.payload)?)),
            FrameKind::Bench => {
                let text = frame.text();
                Reply::Bench(BenchReply::parse(&text).with_context(|| format!("BENCH {text:?}"))?.rows)
            }
            FrameKind::Fatal => {
                let text = frame.text();
                FatalReport::parse(&text).with_context(|| format!("FATAL \"{text}\""))?;
                Reply::Fatal(text)
            }
            FrameKind::Log => bail!("a LOG frame is not a reply"),
        })
    }

    /// One line for error messages; never the bytes of a dump.
    pub(crate) fn describe(&self) -> String {
        match self {
            Reply::Ready(text) => format!("READY \"{text}\""),
            Reply::Ok(text) => format!("OK \"{text}\""),
            Reply::Err(text) => format!("ERR \"{text}\""),
            Reply::List(listing) => {
                let (scenes, shows, methods) = (listing.scenes.len(), listing.shows.len(), listing.methods.len());
                format!("LIST of {scenes} scenes, {shows} show entries and {methods} methods")
            }
            Reply::Dump(_) => "a DUMP".to_string(),
            Reply::Bench(rows) => format!("BENCH of {} methods", rows.len()),
            Reply::Fatal(text) => format!("FATAL \"{text}\""),
        }
    }
}

/// The answer to `DUMP`: the framebuffer and the DAC, both read back.
#[derive(Clone, PartialEq, Eq)]
pub struct Dump {
    /// 320x200 bytes read back from 0xA0000.
    pub pixels: Vec<u8>,
    /// The 256 DAC entries read back, 6-bit red, green, blue.
    pub palette: [[u8; 3]; ENTRIES],
}

impl std::fmt::Debug for Dump {
    /// A summary: a derived Debug would print 64,000 numbers.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Dump {{ {} pixels, {} palette entries }}", self.pixels.len(), self.palette.len())
    }
}

impl Dump {
    pub fn parse(payload: &[u8]) -> Result<Self> {
        ensure!(payload.len() == DUMP_LEN, "a dump has {DUMP_LEN} bytes, this one {}", payload.len());
        let (pixels, dac) = payload.split_at(FRAMEBUFFER_LEN);
        let mut palette = [[0; 3]; ENTRIES];
        for (entry, rgb) in palette.iter_mut().zip(dac.as_chunks::<3>().0) {
            *entry = *rgb;
        }
        Ok(Self { pixels: pixels.to_vec(), palette })
    }

    /// The framebuffer as an indexed image whose palette is the read-back
    /// DAC: the picture the screen shows, with the raw bytes kept.
    pub fn image(&self) -> Image {
        Image::from_dac(SCREEN.width as u32, SCREEN.height as u32, self.pixels.clone(), &self.palette)
            .expect("a dump holds width x height pixels")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_short_dump_is_refused() {
        let error = Dump::parse(&[0; 10]).unwrap_err().to_string();
        assert_eq!(error, format!("a dump has {DUMP_LEN} bytes, this one 10"));
    }
}
