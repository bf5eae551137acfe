//! Asking over a line that can damage, drop, add or hold back bytes.
//!
//! Every command goes out sealed with a sequence number of its own
//! (`protocol::Sealed`); the kernel runs only an intact line and echoes its
//! number in the reply's header, under the reply's CRC. A reply is taken
//! only if it carries the number of the line just sent: a late reply to an
//! earlier line, or to an earlier try of the same one, is skipped. What the
//! line can do to a command then shows as one of the [`TroubleKind`]s.
//!
//! A retry runs a whole step again (for a picture: clear, draw, dump), not
//! just the command that failed: a lost line may have left the kernel in
//! another state (a partial line it gave up on, the show started again), and
//! every step the check runs sets the state it needs from scratch, so it is
//! safe to run twice. Which commands are safe to send twice, and why, is in
//! docs/protocol.md.

use std::fmt;
use std::time::{Duration, Instant, SystemTime};

use anyhow::{bail, Context, Result};
use protocol::{Command, FrameKind, Sealed, DUMP_LEN};

use super::channel::{log_event, Channel};
use super::frame_reader::{ReadError, ReadErrorKind};
use super::reply::{Reply, REPLY_TIMEOUT};

/// Longest wait for a reply that takes the kernel no time to speak of, by
/// default. Generous: under TCG on a loaded 2-core machine a draw can take
/// seconds.
const ANSWER_TIMEOUT: Duration = Duration::from_secs(10);
/// Longest silence inside a frame before the rest of it is taken as lost:
/// longer than any pause the line may make without losing anything (the
/// fault relay pauses for a second).
const STALL: Duration = Duration::from_secs(3);
/// Quiet on the line that ends the clean-up before a step runs again: the
/// rest of a damaged reply, or the `ERR` for the second half of a line
/// split by a damaged byte, arrives within it.
const SETTLE: Duration = Duration::from_millis(300);
/// How often the host asks `READY` while it waits for the kernel.
const ASK_EVERY: Duration = Duration::from_secs(3);
/// The kernel's line speed.
pub const BAUD: u32 = 115_200;
/// Bits per byte on the line: 8N1 is a start bit, 8 data bits, a stop bit.
const BITS_PER_BYTE: u64 = 10;

/// What the line did to a step, each a reason to run it again.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum TroubleKind {
    /// No reply in time: the command or its reply was lost whole (a
    /// dropped newline, a damaged header).
    NoReply,
    /// A reply stopped half way: a byte of it was dropped.
    Stalled,
    /// A reply failed its CRC or was not a well-formed frame.
    DamagedReply,
    /// The kernel answered `ERR` to a line it could not trust: the command
    /// was damaged on the way in, and nothing was run.
    Refused,
}

impl TroubleKind {
    pub const ALL: [TroubleKind; 4] =
        [TroubleKind::NoReply, TroubleKind::Stalled, TroubleKind::DamagedReply, TroubleKind::Refused];

    /// Its name in reports.
    pub fn name(self) -> &'static str {
        match self {
            TroubleKind::NoReply => "no_reply",
            TroubleKind::Stalled => "stalled_reply",
            TroubleKind::DamagedReply => "damaged_reply",
            TroubleKind::Refused => "refused_command",
        }
    }

    /// What it means, for a person.
    pub fn describe(self) -> &'static str {
        match self {
            TroubleKind::NoReply => "no reply in time (the command or its reply lost)",
            TroubleKind::Stalled => "a reply stopped half way (a byte of it lost)",
            TroubleKind::DamagedReply => "a reply failed its CRC-32",
            TroubleKind::Refused => "the kernel refused a damaged command (ERR, nothing run)",
        }
    }
}

/// A step the line damaged: the error a retry is for.
#[derive(Debug)]
pub struct Trouble {
    pub kind: TroubleKind,
    detail: String,
}

impl fmt::Display for Trouble {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.kind.describe(), self.detail)
    }
}

impl std::error::Error for Trouble {}

/// The kernel sent its `READY` of boot: it (re)started. Its text.
#[derive(Debug)]
struct Booted(String);

impl fmt::Display for Booted {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "the kernel booted (READY \"{}\")", self.0)
    }
}

impl std::error::Error for Booted {}

/// What went over the line and what it did, counted.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct LineStats {
    /// Sealed command lines sent, every try counted.
    pub commands: u64,
    /// Bytes of those lines.
    pub bytes_sent: u64,
    /// Steps run again.
    pub retries: u64,
    /// Each [`TroubleKind`] as often as it happened, in `TroubleKind::ALL` order.
    pub troubles: [u64; 4],
    /// Replies to earlier lines, skipped.
    pub stale_replies: u64,
    /// Each trouble as it happened: the command and what went wrong.
    pub log: Vec<String>,
}

impl LineStats {
    /// How often `kind` happened.
    pub fn count(&self, kind: TroubleKind) -> u64 {
        self.troubles[kind as usize]
    }
}

/// How a console seals its commands: the next sequence number, the retry
/// bound, the counts.
#[derive(Clone, Debug)]
pub struct Sealing {
    next_seq: u32,
    /// Most retries of one step; 0 makes the first trouble an error.
    retries: u32,
    /// The wait for a reply that takes no work, and the base of every
    /// other wait ([`reply_timeout`]).
    answer_timeout: Duration,
    pub stats: LineStats,
}

/// How long the answer to `command` may take at `baud`, `answer` being the
/// wait for one that takes no work: that, plus a dump's bytes twice over (a
/// stale one may be on the line ahead of it), or `BENCH`'s draws.
fn reply_timeout(command: &Command, baud: u32, answer: Duration) -> Duration {
    match command {
        Command::Dump => answer + 2 * transfer_time(DUMP_LEN as u64, baud),
        Command::Bench { .. } => answer.max(REPLY_TIMEOUT),
        _ => answer,
    }
}

/// `command` as a report names it: its line, but a chunk's data only
/// counted (a chunk's line is over a thousand characters of base64).
fn in_brief(command: &Command) -> String {
    match command {
        Command::Chunk { offset, data } => format!("CHUNK {offset} <{} characters of base64>", data.len()),
        _ => command.to_string(),
    }
}

/// How long `bytes` take at `baud`, 8N1.
pub fn transfer_time(bytes: u64, baud: u32) -> Duration {
    Duration::from_secs_f64((bytes * BITS_PER_BYTE) as f64 / f64::from(baud))
}

impl Sealing {
    pub fn new(retries: u32) -> Self {
        // Start where a session before this one is unlikely to have been,
        // so that a reply it left on the line matches none of ours.
        let clock = SystemTime::now().duration_since(SystemTime::UNIX_EPOCH).map_or(0, |t| t.subsec_nanos());
        Self {
            next_seq: clock ^ std::process::id(),
            retries,
            answer_timeout: ANSWER_TIMEOUT,
            stats: LineStats::default(),
        }
    }

    /// Most retries of one step.
    pub fn retries(&self) -> u32 {
        self.retries
    }

    /// Sets the wait for a reply that takes the kernel no work.
    pub fn set_answer_timeout(&mut self, timeout: Duration) {
        self.answer_timeout = timeout;
    }

    /// Sends `command` sealed on `channel` and returns the reply that
    /// echoes its sequence number, skipping replies to earlier lines. What
    /// the line did instead is a [`Trouble`] (counted); the stream's end, a
    /// `FATAL` or the kernel booting again are errors of their own.
    pub(crate) fn request(&mut self, channel: &mut Channel, command: &Command) -> Result<Reply> {
        let timeout = reply_timeout(command, BAUD, self.answer_timeout);
        self.request_within(channel, command, timeout)
    }

    /// [`Sealing::request`] with a reply deadline of `timeout`.
    fn request_within(&mut self, channel: &mut Channel, command: &Command, timeout: Duration) -> Result<Reply> {
        let seq = self.next_seq;
        self.next_seq = seq.wrapping_add(1);
        let line = format!("{}\n", Sealed { seq, command });
        self.stats.commands += 1;
        self.stats.bytes_sent += line.len() as u64;
        channel.send_bytes(line.as_bytes()).with_context(|| format!("failed to send `{command}`"))?;
        let deadline = Instant::now() + timeout;
        loop {
            let frame = match channel.frames.next_frame_until(deadline, Some(STALL)) {
                Ok(frame) => frame,
                Err(error) => {
                    let kind = match error.downcast_ref::<ReadError>().map(|error| error.kind) {
                        Some(ReadErrorKind::Silent) => TroubleKind::NoReply,
                        Some(ReadErrorKind::Stalled) => TroubleKind::Stalled,
                        Some(ReadErrorKind::Damaged) => TroubleKind::DamagedReply,
                        Some(ReadErrorKind::Closed) | None => {
                            return Err(error.context(format!("waiting for the reply to `{command}`")))
                        }
                    };
                    return Err(self.trouble(kind, command, &error.to_string()));
                }
            };
            match (frame.kind, frame.seq) {
                (FrameKind::Log, _) => channel.logs.push(log_event(&frame.text())?),
                (_, Some(echoed)) if echoed == seq => {
                    return Reply::decode(frame).with_context(|| format!("the reply to `{command}`"))
                }
                (_, Some(_)) => self.stats.stale_replies += 1,
                (FrameKind::Err, None) => {
                    let detail = format!("`{}` answered ERR \"{}\"", in_brief(command), frame.text());
                    return Err(self.trouble(TroubleKind::Refused, command, &detail));
                }
                (FrameKind::Fatal, None) => bail!("the kernel failed: FATAL \"{}\"", frame.text()),
                (FrameKind::Ready, None) => {
                    return Err(anyhow::Error::new(Booted(frame.text())).context(format!("while `{command}` was asked")))
                }
                // The answer to a plain line nobody here sent: noise that
                // happens to parse.
                (_, None) => self.stats.stale_replies += 1,
            }
        }
    }

    /// Counts a trouble with `command` and makes it an error.
    fn trouble(&mut self, kind: TroubleKind, command: &Command, detail: &str) -> anyhow::Error {
        self.stats.troubles[kind as usize] += 1;
        self.stats.log.push(format!("`{}`: {}", in_brief(command), kind.describe()));
        Trouble { kind, detail: detail.to_string() }.into()
    }

    /// After a step failed with `error`, having been run again `retried`
    /// times: `Ok` if it is to run again (the line damaged it, a
    /// [`Trouble`], and the bound is not reached), once the line has
    /// settled; else the error to fail with.
    pub(crate) fn retry_after(&mut self, channel: &mut Channel, error: anyhow::Error, retried: u32) -> Result<()> {
        if error.downcast_ref::<Trouble>().is_none() {
            return Err(error);
        }
        if retried == self.retries {
            return Err(match retried {
                0 => error.context("the line damaged a step, and retries are off"),
                _ => error.context(format!("the line damaged the same step {} times", retried + 1)),
            });
        }
        self.stats.retries += 1;
        channel.frames.discard_until_quiet(SETTLE, STALL);
        Ok(())
    }

    /// Finds the kernel: sends `READY` every [`ASK_EVERY`] until it
    /// answers (or sends its `READY` at boot), within `bound`. Returns the `READY`
    /// text and whether it came at boot. A `LOG` frame on the way is kept.
    /// Fails with what to check when nothing answers.
    pub(crate) fn wait_for_kernel(
        &mut self,
        channel: &mut Channel,
        bound: Duration,
        device: &str,
    ) -> Result<(String, bool)> {
        let give_up = Instant::now() + bound;
        // Silence while the PC boots is no fault of the line's.
        let (troubles, logged) = (self.stats.troubles, self.stats.log.len());
        let forget_troubles = |sealing: &mut Sealing, channel: &mut Channel| {
            sealing.stats.troubles = troubles;
            sealing.stats.log.truncate(logged);
            channel.frames.discard_until_quiet(SETTLE, STALL);
        };
        while let Some(left) = give_up.checked_duration_since(Instant::now()).filter(|left| !left.is_zero()) {
            match self.request_within(channel, &Command::Ready, left.min(ASK_EVERY)) {
                Ok(Reply::Ready(text)) => {
                    forget_troubles(self, channel);
                    return Ok((text, false));
                }
                Ok(other) => bail!("`READY` answered {}", other.describe()),
                Err(error) => {
                    // The READY the kernel sends once at boot answers too.
                    if let Some(Booted(text)) = error.downcast_ref::<Booted>() {
                        let text = text.clone();
                        forget_troubles(self, channel);
                        return Ok((text, true));
                    }
                    if error.downcast_ref::<Trouble>().is_none() {
                        return Err(error);
                    }
                }
            }
        }
        let heard = match channel.frames.received() {
            0 => "nothing at all arrived".to_string(),
            n => format!("{n} bytes arrived, none of them a frame (a wrong baud rate garbles every byte)"),
        };
        bail!(
            "no answer from the kernel on {device} within {} s: {heard}. Check that the PC is booted from the \
             polylab stick, that the cable is a null-modem cable on its COM1, that {device} is the port the cable \
             is on, and that the line runs at {BAUD} baud 8N1",
            bound.as_secs(),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_chunk_is_named_without_its_data() {
        let chunk = Command::Chunk { offset: 2048, data: "QUJD" };
        assert_eq!(in_brief(&chunk), "CHUNK 2048 <4 characters of base64>");
        assert_eq!(in_brief(&Command::Clear(3)), "CLEAR 3");
    }

    #[test]
    fn a_dump_may_take_twice_its_bytes_at_the_baud_rate() {
        let dump = reply_timeout(&Command::Dump, 115_200, ANSWER_TIMEOUT);
        // 64,768 bytes of 10 bits at 115200 baud: 5.62 s, twice.
        assert_eq!(dump.as_millis(), ANSWER_TIMEOUT.as_millis() + 11_244);
        assert_eq!(reply_timeout(&Command::Ping, 115_200, ANSWER_TIMEOUT), ANSWER_TIMEOUT);
    }
}
