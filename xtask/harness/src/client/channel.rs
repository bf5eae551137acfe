//! The line to the kernel as a console uses it: command bytes out,
//! frames in, the `LOG` frames on the way kept.

use std::io::Write;
use std::time::{Duration, Instant};

use anyhow::{bail, Context, Result};
use protocol::{FrameKind, LogEvent};

use super::frame_reader::FrameReader;
use super::reply::Reply;

/// Bytes out to the kernel, frames in from it, and the `LOG` frames
/// received so far.
pub(crate) struct Channel {
    pub(crate) frames: FrameReader,
    input: Box<dyn Write + Send>,
    pub(crate) logs: Vec<LogEvent>,
}

impl Channel {
    pub(crate) fn new(input: impl Write + Send + 'static, frames: FrameReader) -> Self {
        Self { frames, input: Box::new(input), logs: Vec::new() }
    }

    /// Sends raw bytes, valid or not.
    pub(crate) fn send_bytes(&mut self, bytes: &[u8]) -> Result<()> {
        self.input.write_all(bytes)?;
        self.input.flush()?;
        Ok(())
    }

    /// The next reply within `timeout`: one deadline for the whole wait,
    /// which LOG frames on the way do not extend (a kernel that keeps
    /// logging and never answers still times out).
    pub(crate) fn reply_within(&mut self, timeout: Duration) -> Result<Reply> {
        let deadline = Instant::now() + timeout;
        let logs_before = self.logs.len();
        let late = |logs: usize| {
            format!("no reply within {:.1} s, only {} LOG frames", timeout.as_secs_f64(), logs - logs_before)
        };
        loop {
            let remaining = deadline.saturating_duration_since(Instant::now());
            if remaining.is_zero() {
                bail!(late(self.logs.len()));
            }
            let frame = match self.frames.next_frame(remaining) {
                Ok(frame) => frame,
                Err(error) if logs_before < self.logs.len() && Instant::now() >= deadline => {
                    return Err(error.context(late(self.logs.len())));
                }
                Err(error) => return Err(error),
            };
            if frame.kind == FrameKind::Log {
                self.logs.push(log_event(&frame.text())?);
                continue;
            }
            return Reply::decode(frame);
        }
    }
}

/// The event a `LOG` frame's `text` tells; an error for a text the
/// protocol does not write.
pub(crate) fn log_event(text: &str) -> Result<LogEvent> {
    LogEvent::parse(text).with_context(|| format!("LOG \"{text}\""))
}
