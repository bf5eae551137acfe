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

use crate::qemu::console::{Console, Reply, REPLY_TIMEOUT};
use crate::qemu::serial::{ReadError, ReadErrorKind};

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

/// How long `bytes` take at `baud`, 8N1.
pub fn transfer_time(bytes: u64, baud: u32) -> Duration {
    Duration::from_secs_f64((bytes * BITS_PER_BYTE) as f64 / f64::from(baud))
}

impl Console {
    /// The line's counts, if the console seals its commands.
    pub fn line_stats(&self) -> Option<&LineStats> {
        self.sealing.as_ref().map(|sealing| &sealing.stats)
    }

    /// Sets how long a sealing console waits for a reply that takes the
    /// kernel no work (10 s by default; a dump's and a `BENCH`'s waits
    /// grow from it).
    pub fn set_answer_timeout(&mut self, timeout: Duration) {
        if let Some(sealing) = self.sealing.as_mut() {
            sealing.answer_timeout = timeout;
        }
    }

    /// Most retries of one step (0 for a console that does not seal).
    pub fn retries_allowed(&self) -> u32 {
        self.sealing.as_ref().map_or(0, |sealing| sealing.retries)
    }

    /// Bytes received so far, frames and noise.
    pub fn bytes_received(&self) -> u64 {
        self.frames.received()
    }

    /// Sends `command` sealed and returns the reply that echoes its
    /// sequence number, skipping replies to earlier lines. What the line did
    /// instead is a [`Trouble`] (counted); the stream's end, a `FATAL` or
    /// the kernel booting again are errors of their own.
    pub(crate) fn request_sealed(&mut self, command: &Command) -> Result<Reply> {
        let answer = self.sealing.as_ref().map_or(ANSWER_TIMEOUT, |sealing| sealing.answer_timeout);
        self.request_sealed_within(command, reply_timeout(command, crate::line::BAUD, answer))
    }

    /// [`Console::request_sealed`] with a reply deadline of `timeout`.
    fn request_sealed_within(&mut self, command: &Command, timeout: Duration) -> Result<Reply> {
        let sealing = self.sealing.as_mut().expect("called for a sealing console");
        let seq = sealing.next_seq;
        sealing.next_seq = seq.wrapping_add(1);
        let line = format!("{}\n", Sealed { seq, command });
        sealing.stats.commands += 1;
        sealing.stats.bytes_sent += line.len() as u64;
        self.send_bytes(line.as_bytes()).with_context(|| format!("failed to send `{command}`"))?;
        let deadline = Instant::now() + timeout;
        loop {
            let frame = match self.frames.next_frame_until(deadline, Some(STALL)) {
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
                (FrameKind::Log, _) => self.logs.push(frame.text()),
                (_, Some(echoed)) if echoed == seq => {
                    return Reply::decode(frame).with_context(|| format!("the reply to `{command}`"))
                }
                (_, Some(_)) => self.sealing_stats().stale_replies += 1,
                (FrameKind::Err, None) => {
                    let detail = format!("`{command}` answered ERR \"{}\"", frame.text());
                    return Err(self.trouble(TroubleKind::Refused, command, &detail));
                }
                (FrameKind::Fatal, None) => bail!("the kernel failed: FATAL \"{}\"", frame.text()),
                (FrameKind::Ready, None) => {
                    return Err(anyhow::Error::new(Booted(frame.text())).context(format!("while `{command}` was asked")))
                }
                // The answer to a plain line nobody here sent: noise that
                // happens to parse.
                (_, None) => self.sealing_stats().stale_replies += 1,
            }
        }
    }

    fn sealing_stats(&mut self) -> &mut LineStats {
        &mut self.sealing.as_mut().expect("called for a sealing console").stats
    }

    /// Counts a trouble with `command` and makes it an error.
    fn trouble(&mut self, kind: TroubleKind, command: &Command, detail: &str) -> anyhow::Error {
        let stats = self.sealing_stats();
        stats.troubles[kind as usize] += 1;
        stats.log.push(format!("`{command}`: {}", kind.describe()));
        Trouble { kind, detail: detail.to_string() }.into()
    }

    /// Runs `step`, and while it fails for what the line did (a
    /// [`Trouble`]) runs it again, up to the console's retry bound, after
    /// letting the line settle. Any other failure, and a console that does
    /// not seal, fail at once.
    pub fn retrying<T>(&mut self, mut step: impl FnMut(&mut Console) -> Result<T>) -> Result<T> {
        let mut retried = 0;
        loop {
            let error = match step(self) {
                Ok(value) => return Ok(value),
                Err(error) => error,
            };
            let Some(sealing) = self.sealing.as_mut() else { return Err(error) };
            if error.downcast_ref::<Trouble>().is_none() {
                return Err(error);
            }
            if retried == sealing.retries {
                return Err(match retried {
                    0 => error.context("the line damaged a step, and retries are off"),
                    _ => error.context(format!("the line damaged the same step {} times", retried + 1)),
                });
            }
            retried += 1;
            sealing.stats.retries += 1;
            self.frames.discard_until_quiet(SETTLE, STALL);
        }
    }

    /// Finds the kernel: sends `READY` every [`ASK_EVERY`] until it
    /// answers (or sends its `READY` at boot), within `bound`. Returns the `READY`
    /// text and whether it came at boot. A `LOG` frame on the way is kept.
    /// Fails with what to check when nothing answers.
    pub fn wait_for_kernel(&mut self, bound: Duration, device: &str) -> Result<(String, bool)> {
        let give_up = Instant::now() + bound;
        // Silence while the PC boots is no fault of the line's.
        let troubles_before = self.line_stats().map(|stats| (stats.troubles, stats.log.len()));
        let forget_troubles = |console: &mut Console| {
            if let (Some(sealing), Some((troubles, logged))) = (console.sealing.as_mut(), troubles_before) {
                sealing.stats.troubles = troubles;
                sealing.stats.log.truncate(logged);
            }
            console.frames.discard_until_quiet(SETTLE, STALL);
        };
        while let Some(left) = give_up.checked_duration_since(Instant::now()).filter(|left| !left.is_zero()) {
            match self.request_sealed_within(&Command::Ready, left.min(ASK_EVERY)) {
                Ok(Reply::Ready(text)) => {
                    forget_troubles(self);
                    return Ok((text, false));
                }
                Ok(other) => bail!("`READY` answered {}", other.describe()),
                Err(error) => {
                    // The READY the kernel sends once at boot answers too.
                    if let Some(Booted(text)) = error.downcast_ref::<Booted>() {
                        let text = text.clone();
                        forget_troubles(self);
                        return Ok((text, true));
                    }
                    if error.downcast_ref::<Trouble>().is_none() {
                        return Err(error);
                    }
                }
            }
        }
        let heard = match self.frames.received() {
            0 => "nothing at all arrived".to_string(),
            n => format!("{n} bytes arrived, none of them a frame (a wrong baud rate garbles every byte)"),
        };
        bail!(
            "no answer from the kernel on {device} within {} s: {heard}. Check that the PC is booted from the \
             polylab stick, that the cable is a null-modem cable on its COM1, that {device} is the port the cable \
             is on, and that the line runs at {} baud 8N1",
            bound.as_secs(),
            crate::line::BAUD
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::qemu::serial::FrameReader;
    use protocol::FrameHeader;
    use std::io::Write;
    use std::sync::mpsc::{self, Sender};
    use std::sync::{Arc, Mutex};

    /// What the stand-in kernel answers a line: the bytes it sends back
    /// for a sequence number and command.
    type Answer = dyn FnMut(u32, &str) -> Vec<u8> + Send;

    /// A kernel stand-in: answers each sealed line the console writes with
    /// the frames `answer` makes of its sequence number and command.
    #[derive(Clone)]
    struct Kernel {
        frames: Sender<Vec<u8>>,
        answer: Arc<Mutex<Answer>>,
        lines: Arc<Mutex<Vec<String>>>,
    }

    impl Write for Kernel {
        fn write(&mut self, bytes: &[u8]) -> std::io::Result<usize> {
            let line = String::from_utf8(bytes.to_vec()).unwrap();
            let (seq, command) = protocol::unseal(line.trim_end().as_bytes()).unwrap();
            let command = std::str::from_utf8(command).unwrap();
            self.lines.lock().unwrap().push(command.to_string());
            let reply = (self.answer.lock().unwrap())(seq.unwrap(), command);
            let _ = self.frames.send(reply);
            Ok(bytes.len())
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }

    fn frame(kind: FrameKind, payload: &[u8], seq: Option<u32>) -> Vec<u8> {
        let mut bytes = format!("{}\n", FrameHeader::for_reply(kind, payload, seq)).into_bytes();
        bytes.extend_from_slice(payload);
        bytes.push(b'\n');
        bytes
    }

    fn console(retries: u32, answer: impl FnMut(u32, &str) -> Vec<u8> + Send + 'static) -> (Console, Kernel) {
        let (sender, receiver) = mpsc::channel();
        let kernel =
            Kernel { frames: sender, answer: Arc::new(Mutex::new(answer)), lines: Arc::new(Mutex::new(Vec::new())) };
        (Console::sealed(kernel.clone(), FrameReader::new(receiver), retries), kernel)
    }

    #[test]
    fn a_reply_is_taken_only_with_the_sequence_number_of_the_line_just_sent() {
        let (mut console, kernel) = console(0, |seq, _| {
            // A late reply to the line before, then the reply to this one.
            let mut bytes = frame(FrameKind::Ok, b"clear 1", Some(seq.wrapping_sub(1)));
            bytes.extend(frame(FrameKind::Ok, b"clear 7", Some(seq)));
            bytes
        });
        assert_eq!(console.ok(&Command::Clear(7)).unwrap(), "clear 7");
        assert_eq!(console.line_stats().unwrap().stale_replies, 1);
        assert_eq!(*kernel.lines.lock().unwrap(), ["CLEAR 7"]);
    }

    #[test]
    fn a_damaged_reply_is_retried_as_a_whole_step_and_counted() {
        let mut calls = 0;
        let (mut console, kernel) = console(2, move |seq, command| {
            calls += 1;
            let mut bytes = frame(FrameKind::Ok, command.as_bytes(), Some(seq));
            if calls == 2 {
                // The second line's reply has a bit flipped in its payload.
                let at = bytes.len() - 2;
                bytes[at] ^= 0x04;
            }
            bytes
        });
        let answers =
            console.retrying(|console| Ok((console.ok(&Command::Clear(0))?, console.ok(&Command::Ping)?))).unwrap();
        assert_eq!(answers, ("CLEAR 0".to_string(), "PING".to_string()));
        assert_eq!(*kernel.lines.lock().unwrap(), ["CLEAR 0", "PING", "CLEAR 0", "PING"]);
        let stats = console.line_stats().unwrap();
        assert_eq!((stats.retries, stats.count(TroubleKind::DamagedReply)), (1, 1));
        assert_eq!(stats.log, ["`PING`: a reply failed its CRC-32"]);
    }

    #[test]
    fn an_err_without_a_sequence_number_is_a_refused_line() {
        let mut calls = 0;
        let (mut console, _) = console(1, move |seq, _| {
            calls += 1;
            match calls {
                1 => frame(FrameKind::Err, protocol::Damaged.to_string().as_bytes(), None),
                _ => frame(FrameKind::Ok, b"clear 3", Some(seq)),
            }
        });
        assert_eq!(console.retrying(|console| console.ok(&Command::Clear(3))).unwrap(), "clear 3");
        assert_eq!(console.line_stats().unwrap().count(TroubleKind::Refused), 1);
    }

    #[test]
    fn with_retries_off_the_first_trouble_fails_the_step() {
        let (mut console, _) = console(0, |_, _| frame(FrameKind::Err, protocol::Damaged.to_string().as_bytes(), None));
        let error = console.retrying(|console| console.ok(&Command::Ping)).unwrap_err();
        assert_eq!(error.to_string(), "the line damaged a step, and retries are off");
        assert!(format!("{error:#}").contains("the kernel refused a damaged command"), "{error:#}");
    }

    #[test]
    fn a_genuine_err_and_a_fatal_are_not_retried() {
        let (mut console, kernel) = console(3, |seq, command| match command {
            "PING" => frame(FrameKind::Fatal, b"panic", None),
            _ => frame(FrameKind::Err, b"unknown scene `x`", Some(seq)),
        });
        let error = console.retrying(|console| console.ok(&Command::Draw { scene: "x", method: None }));
        assert_eq!(error.unwrap_err().to_string(), "`DRAW x` answered ERR \"unknown scene `x`\"");
        let error = console.retrying(|console| console.ok(&Command::Ping)).unwrap_err();
        assert_eq!(error.to_string(), "the kernel failed: FATAL \"panic\"");
        assert_eq!(kernel.lines.lock().unwrap().len(), 2);
        assert_eq!(console.line_stats().unwrap().retries, 0);
    }

    #[test]
    fn a_silent_line_is_an_error_saying_what_to_check() {
        let (sender, receiver) = mpsc::channel::<Vec<u8>>();
        let mut console = Console::sealed(std::io::sink(), FrameReader::new(receiver), 3);
        let error = console.wait_for_kernel(Duration::from_millis(300), "/dev/ttyS0").unwrap_err().to_string();
        assert!(
            error.starts_with("no answer from the kernel on /dev/ttyS0 within 0 s: nothing at all arrived."),
            "{error}"
        );
        assert!(error.contains("null-modem cable on its COM1"), "{error}");
        sender.send(b"\xff\xfe garbage at the wrong baud rate".to_vec()).unwrap();
        let error = console.wait_for_kernel(Duration::from_millis(300), "/dev/ttyS0").unwrap_err().to_string();
        assert!(error.contains("33 bytes arrived, none of them a frame (a wrong baud rate"), "{error}");
    }

    #[test]
    fn the_ready_of_boot_or_the_answer_to_ready_finds_the_kernel() {
        let ready = b"firmware=bios display=none video=none overruns=0 dropped=0";
        let (mut asked, _) = console(0, |seq, _| frame(FrameKind::Ready, ready, Some(seq)));
        let found = asked.wait_for_kernel(Duration::from_secs(5), "/dev/ttyS0").unwrap();
        assert_eq!(found, (String::from_utf8(ready.to_vec()).unwrap(), false));
        let (mut booted, _) = console(0, |_, _| frame(FrameKind::Ready, ready, None));
        assert!(booted.wait_for_kernel(Duration::from_secs(5), "/dev/ttyS0").unwrap().1, "READY at boot");
    }

    #[test]
    fn a_dump_may_take_twice_its_bytes_at_the_baud_rate() {
        let dump = reply_timeout(&Command::Dump, 115_200, ANSWER_TIMEOUT);
        // 64,768 bytes of 10 bits at 115200 baud: 5.62 s, twice.
        assert_eq!(dump.as_millis(), ANSWER_TIMEOUT.as_millis() + 11_244);
        assert_eq!(reply_timeout(&Command::Ping, 115_200, ANSWER_TIMEOUT), ANSWER_TIMEOUT);
    }
}
