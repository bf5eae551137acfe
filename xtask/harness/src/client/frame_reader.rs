//! The kernel-to-host direction of the serial protocol: frames found in a
//! byte stream, checked against their CRC32, with a deadline on every wait.
//!
//! The bytes arrive from a reader thread over a channel (a pipe read cannot
//! time out; a channel receive can). Anything between frames is noise and is
//! skipped (see `protocol`'s crate docs).

use std::collections::VecDeque;
use std::io::Read;
use std::sync::mpsc::{self, Receiver, RecvTimeoutError};
use std::time::{Duration, Instant};

use anyhow::{bail, Result};
use protocol::{FrameHeader, FrameKind, DUMP_LEN, FRAME_MARK};

/// Longest header line, `@FATAL 18446744073709551615 xxxxxxxx` with room
/// to spare: a `@` not followed by `\n` within this many bytes is noise.
const MAX_HEADER_LINE: usize = 64;
/// Largest payload any frame carries; a header announcing more is garbage.
const MAX_PAYLOAD: usize = DUMP_LEN;
/// How many of the last received bytes an error shows.
const TAIL_LEN: usize = 160;

/// Why no frame came: what a host on a line that can damage bytes
/// retries for ([`ReadError::kind`]), or the end of the stream, which it
/// does not.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ReadErrorKind {
    /// The stream ended: the other side closed it.
    Closed,
    /// No complete frame before the deadline.
    Silent,
    /// A frame stopped half way and stayed stopped.
    Stalled,
    /// A frame failed its CRC, announced an impossible length, or was not
    /// ended by its newline.
    Damaged,
}

/// A failure to read a frame: its kind and a message that ends with the
/// last bytes received.
#[derive(Debug)]
pub struct ReadError {
    pub kind: ReadErrorKind,
    message: String,
}

impl std::fmt::Display for ReadError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for ReadError {}

/// One checked frame.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Frame {
    pub kind: FrameKind,
    pub payload: Vec<u8>,
    /// The sequence number of the sealed command it answers, if any.
    pub seq: Option<u32>,
}

impl Frame {
    /// The payload as text, for the kinds that carry text.
    pub fn text(&self) -> String {
        String::from_utf8_lossy(&self.payload).into_owned()
    }
}

/// Starts a thread that forwards everything `source` yields into the
/// returned channel; the channel closes when `source` ends (a read of 0
/// bytes or an error).
pub fn forward_bytes(mut source: impl Read + Send + 'static) -> Receiver<Vec<u8>> {
    let (sender, receiver) = mpsc::channel();
    std::thread::spawn(move || {
        let mut chunk = vec![0; 64 * 1024];
        while let Ok(n @ 1..) = source.read(&mut chunk) {
            if sender.send(chunk[..n].to_vec()).is_err() {
                break;
            }
            gather_after(n);
        }
    });
    receiver
}

/// A read of fewer bytes than this is followed by a nap of [`GATHER`].
const SHORT_READ: usize = 4096;
/// How long a forwarding thread lets bytes gather after a short read.
/// QEMU writes every byte the guest's UART sends with a write of its own,
/// so a reader always waiting takes them one read (and one wake-up of
/// each side) per byte. A millisecond's nap lets a pipe or terminal
/// buffer gather what arrives meanwhile, and a reply waits at most that
/// much longer: the adapter matrix took 106 CPU-seconds instead of 140,
/// `serial_check` (a pseudo-terminal and the line-noise relay) 58
/// instead of 101.
const GATHER: Duration = Duration::from_millis(1);

/// Naps [`GATHER`] after a read of `n` bytes if it was short.
pub(crate) fn gather_after(n: usize) {
    if n < SHORT_READ {
        std::thread::sleep(GATHER);
    }
}

/// Finds frames in the bytes coming over a channel.
pub struct FrameReader {
    source: Receiver<Vec<u8>>,
    /// Received, not yet consumed.
    pending: Vec<u8>,
    /// The last [`TAIL_LEN`] bytes received, for error messages.
    tail: VecDeque<u8>,
    closed: bool,
    /// Bytes received so far, noise included.
    received: u64,
    /// When the last byte arrived.
    last_byte: Instant,
}

impl FrameReader {
    pub fn new(source: Receiver<Vec<u8>>) -> Self {
        Self {
            source,
            pending: Vec::new(),
            tail: VecDeque::with_capacity(TAIL_LEN),
            closed: false,
            received: 0,
            last_byte: Instant::now(),
        }
    }

    /// The next frame, skipping noise. Fails on a frame whose CRC or length
    /// does not check, when the stream closes, and after `timeout`; every
    /// error shows the last bytes received.
    pub fn next_frame(&mut self, timeout: Duration) -> Result<Frame> {
        self.next_frame_until(Instant::now() + timeout, None)
    }

    /// [`FrameReader::next_frame`] with a `deadline`, and if `stall` is
    /// given a bound on the silence inside a frame: once a frame has begun,
    /// no byte for `stall` means the rest of it is lost (the kernel sends a
    /// frame's bytes one after the other; a dropped byte leaves its header
    /// waiting for one more than will ever come).
    pub fn next_frame_until(&mut self, deadline: Instant, stall: Option<Duration>) -> Result<Frame> {
        let started = Instant::now();
        loop {
            if let Some(frame) = self.take_frame()? {
                return Ok(frame);
            }
            if self.closed {
                return Err(
                    self.error(ReadErrorKind::Closed, "the serial stream ended (QEMU exited?) before a complete frame")
                );
            }
            let now = Instant::now();
            // After `take_frame`, bytes left pending are a frame begun.
            let stalls_at = stall.filter(|_| !self.pending.is_empty()).map(|stall| (stall, self.last_byte + stall));
            if let Some((stall, _)) = stalls_at.filter(|&(_, at)| at <= now) {
                let what = format!(
                    "a frame stopped half way: no byte for {:.1} s after {} bytes of it",
                    stall.as_secs_f64(),
                    self.pending.len()
                );
                return Err(self.error(ReadErrorKind::Stalled, &what));
            }
            if deadline <= now {
                let what = format!("no complete frame within {:.1} s", (now - started).as_secs_f64());
                return Err(self.error(ReadErrorKind::Silent, &what));
            }
            let wake = stalls_at.map_or(deadline, |(_, at)| at.min(deadline));
            match self.source.recv_timeout(wake - now) {
                Ok(chunk) => self.receive(&chunk),
                Err(RecvTimeoutError::Timeout) => {}
                Err(RecvTimeoutError::Disconnected) => self.closed = true,
            }
        }
    }

    /// Throws away what is pending and whatever arrives until the line has
    /// been quiet for `quiet` (at most `limit` in all): the rest of a
    /// damaged or stale reply, before a command is sent again.
    pub fn discard_until_quiet(&mut self, quiet: Duration, limit: Duration) {
        let give_up = Instant::now() + limit;
        self.pending.clear();
        // Quiet since the last byte, or since now if none comes: an empty
        // chunk (a reader's sign of life) is not a byte.
        let mut quiet_since = Instant::now();
        loop {
            let now = Instant::now();
            let until = (quiet_since + quiet).min(give_up);
            if now >= until {
                return;
            }
            match self.source.recv_timeout(until - now) {
                Ok(chunk) if !chunk.is_empty() => {
                    self.note_received(&chunk);
                    quiet_since = Instant::now();
                }
                Ok(_) | Err(RecvTimeoutError::Timeout) => {}
                Err(RecvTimeoutError::Disconnected) => {
                    self.closed = true;
                    return;
                }
            }
        }
    }

    /// Waits until one of `texts` arrives, as text rather than in a frame
    /// (a firmware's, shim's or a boot manager's console, which OVMF copies
    /// to COM1), and returns which (the first to end in the stream) and
    /// everything received up to its end, which is consumed. Fails when the
    /// stream closes and after `timeout`, showing the last bytes received.
    pub fn skip_to_first(&mut self, texts: &[&str], timeout: Duration) -> Result<(usize, String)> {
        let deadline = Instant::now() + timeout;
        loop {
            let found = texts
                .iter()
                .enumerate()
                .filter(|(_, text)| !text.is_empty())
                .filter_map(|(i, text)| {
                    let at = self.pending.windows(text.len()).position(|window| window == text.as_bytes())?;
                    Some((at + text.len(), i))
                })
                .min();
            if let Some((end, i)) = found {
                let seen: Vec<u8> = self.pending.drain(..end).collect();
                return Ok((i, String::from_utf8_lossy(&seen).into_owned()));
            }
            let wanted = texts.iter().map(|text| format!("`{text}`")).collect::<Vec<_>>().join(" or ");
            if self.closed {
                bail!("the serial stream ended (QEMU exited?) before {wanted}; {}", self.last_bytes());
            }
            let remaining = deadline.saturating_duration_since(Instant::now());
            match self.source.recv_timeout(remaining) {
                Ok(chunk) => self.receive(&chunk),
                Err(RecvTimeoutError::Timeout) => {
                    bail!("no {wanted} within {:.1} s; {}", timeout.as_secs_f64(), self.last_bytes())
                }
                Err(RecvTimeoutError::Disconnected) => self.closed = true,
            }
        }
    }

    /// Whether the stream has ended (the other side closed it).
    pub fn closed(&self) -> bool {
        self.closed
    }

    /// Bytes received so far, frames and noise.
    pub fn received(&self) -> u64 {
        self.received
    }

    fn receive(&mut self, chunk: &[u8]) {
        if chunk.is_empty() {
            return;
        }
        self.note_received(chunk);
        self.pending.extend_from_slice(chunk);
    }

    /// Counts `chunk` and keeps its end for error messages.
    fn note_received(&mut self, chunk: &[u8]) {
        self.received += chunk.len() as u64;
        self.last_byte = Instant::now();
        let keep = chunk.len().min(TAIL_LEN);
        if self.tail.len() + keep > TAIL_LEN {
            self.tail.drain(..self.tail.len() + keep - TAIL_LEN);
        }
        self.tail.extend(&chunk[chunk.len() - keep..]);
    }

    /// A [`ReadError`] of `kind` saying `what`, with the last bytes received.
    fn error(&self, kind: ReadErrorKind, what: &str) -> anyhow::Error {
        ReadError { kind, message: format!("{what}; {}", self.last_bytes()) }.into()
    }

    fn last_bytes(&self) -> String {
        let tail: Vec<u8> = self.tail.iter().copied().collect();
        format!("last {} bytes received: \"{}\"", tail.len(), tail.escape_ascii())
    }

    /// Consumes and returns the first whole frame in `pending`, dropping
    /// the noise before it; `None` when more bytes are needed.
    fn take_frame(&mut self) -> Result<Option<Frame>> {
        loop {
            let Some(start) = self.pending.iter().position(|&b| b == FRAME_MARK) else {
                self.pending.clear();
                return Ok(None);
            };
            self.pending.drain(..start);
            let Some(line_len) = self.pending.iter().take(MAX_HEADER_LINE).position(|&b| b == b'\n') else {
                if self.pending.len() < MAX_HEADER_LINE && !self.closed {
                    return Ok(None);
                }
                self.pending.drain(..1);
                continue;
            };
            let header = std::str::from_utf8(&self.pending[..line_len]).ok().and_then(FrameHeader::parse);
            let Some(header) = header else {
                self.pending.drain(..1);
                continue;
            };
            if header.len > MAX_PAYLOAD {
                self.pending.drain(..=line_len);
                let what = format!("garbage frame header `{header}`: no frame carries more than {MAX_PAYLOAD} bytes");
                return Err(self.error(ReadErrorKind::Damaged, &what));
            }
            let payload_start = line_len + 1;
            let frame_end = payload_start + header.len + 1;
            if self.pending.len() < frame_end {
                return Ok(None);
            }
            let frame: Vec<u8> = self.pending.drain(..frame_end).collect();
            let payload = &frame[payload_start..frame_end - 1];
            if !header.matches(payload) {
                let what = format!(
                    "{} frame of {} bytes fails its CRC32 check (header says {:08x}, payload hashes to {:08x})",
                    header.kind.name(),
                    header.len,
                    header.crc,
                    FrameHeader::for_reply(header.kind, payload, header.seq).crc
                );
                return Err(self.error(ReadErrorKind::Damaged, &what));
            }
            if frame[frame_end - 1] != b'\n' {
                let what = format!("{} frame of {} bytes is not followed by a newline", header.kind.name(), header.len);
                return Err(self.error(ReadErrorKind::Damaged, &what));
            }
            return Ok(Some(Frame { kind: header.kind, payload: payload.to_vec(), seq: header.seq }));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::{AtomicBool, Ordering};
    use std::sync::mpsc::Sender;
    use std::sync::Arc;

    /// For a wait that must end for want of bytes: those it looks at were
    /// all sent before.
    const SHORT: Duration = Duration::from_millis(50);
    /// For a wait that must end with what the bytes sent make (a frame, an
    /// error), or sooner than its deadline: only a reader that hangs, or
    /// lost the bytes, takes this long.
    const PATIENCE: Duration = Duration::from_secs(30);

    fn frame_bytes(kind: FrameKind, payload: &[u8]) -> Vec<u8> {
        let mut bytes = format!("{}\n", FrameHeader::for_payload(kind, payload)).into_bytes();
        bytes.extend_from_slice(payload);
        bytes.push(b'\n');
        bytes
    }

    /// A reader over `chunks`, with the sending side kept open (so running
    /// out of bytes is a timeout, as with a live QEMU).
    fn open_reader(chunks: &[&[u8]]) -> (FrameReader, Sender<Vec<u8>>) {
        let (sender, receiver) = mpsc::channel();
        for chunk in chunks {
            sender.send(chunk.to_vec()).unwrap();
        }
        (FrameReader::new(receiver), sender)
    }

    fn frame(kind: FrameKind, payload: &[u8]) -> Frame {
        Frame { kind, payload: payload.to_vec(), seq: None }
    }

    #[test]
    fn a_frame_split_across_chunks_is_reassembled() {
        let bytes = frame_bytes(FrameKind::Ok, b"pong");
        let chunks: Vec<&[u8]> = bytes.chunks(3).collect();
        let (mut reader, _sender) = open_reader(&chunks);
        assert_eq!(reader.next_frame(PATIENCE).unwrap(), frame(FrameKind::Ok, b"pong"));
    }

    #[test]
    fn noise_between_frames_is_skipped() {
        let mut stream = b"SeaBIOS noise\r\n@ stray at\n@OK 4\n@NOPE 1 00000000\nx\n".to_vec();
        stream.extend(frame_bytes(FrameKind::Ready, b"vga: 0 mismatches"));
        stream.extend(b"more noise @@");
        stream.extend(frame_bytes(FrameKind::Err, b"unknown command `FROB`\n@OK 0 00000000\n"));
        let (mut reader, _sender) = open_reader(&[&stream]);
        assert_eq!(reader.next_frame(PATIENCE).unwrap(), frame(FrameKind::Ready, b"vga: 0 mismatches"));
        assert_eq!(
            reader.next_frame(PATIENCE).unwrap(),
            frame(FrameKind::Err, b"unknown command `FROB`\n@OK 0 00000000\n")
        );
    }

    #[test]
    fn binary_payloads_with_newlines_and_marks_survive() {
        let payload: Vec<u8> = (0..=255u8).cycle().take(DUMP_LEN).collect();
        let (mut reader, _sender) = open_reader(&[&frame_bytes(FrameKind::Dump, &payload)]);
        assert_eq!(reader.next_frame(PATIENCE).unwrap(), frame(FrameKind::Dump, &payload));
    }

    #[test]
    fn a_bad_crc_is_an_error_naming_the_frame_and_reading_goes_on() {
        let mut corrupt = frame_bytes(FrameKind::Ok, b"pong");
        let last = corrupt.len() - 2;
        corrupt[last] = b'G';
        corrupt.extend(frame_bytes(FrameKind::Ok, b"again"));
        let (mut reader, _sender) = open_reader(&[&corrupt]);
        let error = reader.next_frame(PATIENCE).unwrap_err().to_string();
        assert!(error.starts_with("OK frame of 4 bytes fails its CRC32 check"), "{error}");
        assert!(error.contains("ponG"), "{error}");
        assert_eq!(reader.next_frame(PATIENCE).unwrap(), frame(FrameKind::Ok, b"again"));
    }

    #[test]
    fn a_missing_terminator_is_an_error() {
        let mut bytes = frame_bytes(FrameKind::Ok, b"pong");
        *bytes.last_mut().unwrap() = b'X';
        let (mut reader, _sender) = open_reader(&[&bytes]);
        let error = reader.next_frame(PATIENCE).unwrap_err().to_string();
        assert!(error.contains("not followed by a newline"), "{error}");
    }

    #[test]
    fn an_absurd_length_is_garbage() {
        let (mut reader, _sender) = open_reader(&[b"@DUMP 999999999 00000000\n"]);
        let error = reader.next_frame(PATIENCE).unwrap_err().to_string();
        assert!(error.starts_with("garbage frame header `@DUMP 999999999 00000000`"), "{error}");
    }

    #[test]
    fn a_timeout_shows_the_last_bytes_seen() {
        let noise = [b"x".repeat(500), b"partial \x01@OK 4 ".to_vec()].concat();
        let (mut reader, _sender) = open_reader(&[&noise]);
        let error = reader.next_frame(SHORT).unwrap_err().to_string();
        assert!(error.starts_with("no complete frame within "), "{error}");
        assert!(error.contains(&format!("last {TAIL_LEN} bytes received: \"")), "{error}");
        assert!(error.ends_with("partial \\x01@OK 4 \""), "{error}");
    }

    #[test]
    fn a_closed_stream_is_an_error_not_a_wait() {
        let (mut reader, sender) = open_reader(&[b"@OK 4 0"]);
        drop(sender);
        let started = Instant::now();
        let error = reader.next_frame(PATIENCE).unwrap_err().to_string();
        assert!(error.starts_with("the serial stream ended"), "{error}");
        assert!(started.elapsed() < PATIENCE / 2, "{:?}", started.elapsed());
    }

    #[test]
    fn a_frame_that_stops_half_way_is_given_up_after_the_stall_bound() {
        let bytes = frame_bytes(FrameKind::Dump, &[7; 100]);
        let (mut reader, _sender) = open_reader(&[&bytes[..60]]);
        let started = Instant::now();
        let error = reader.next_frame_until(started + PATIENCE, Some(SHORT)).unwrap_err();
        assert!(started.elapsed() < PATIENCE / 2, "the stall bound, not the deadline, ended the wait");
        assert_eq!(error.downcast_ref::<ReadError>().map(|error| error.kind), Some(ReadErrorKind::Stalled));
        assert!(error.to_string().starts_with("a frame stopped half way: no byte for 0.1 s after 60 bytes of it"));
    }

    #[test]
    fn the_line_is_quiet_when_no_byte_comes_whatever_empty_chunks_do() {
        let (sender, receiver) = mpsc::channel();
        let mut reader = FrameReader::new(receiver);
        sender.send(b"rest of a damaged reply".to_vec()).unwrap();
        // Empty chunks every 10 ms until the wait is over: were they taken
        // for bytes, it would last until its limit.
        let over = Arc::new(AtomicBool::new(false));
        let ticker = {
            let over = Arc::clone(&over);
            std::thread::spawn(move || {
                while !over.load(Ordering::Relaxed) && sender.send(Vec::new()).is_ok() {
                    std::thread::sleep(Duration::from_millis(10));
                }
            })
        };
        let started = Instant::now();
        reader.discard_until_quiet(Duration::from_millis(100), PATIENCE);
        let waited = started.elapsed();
        over.store(true, Ordering::Relaxed);
        ticker.join().unwrap();
        assert!(waited < PATIENCE / 2, "{waited:?}");
        assert_eq!(reader.received(), 23);
    }

    #[test]
    fn text_is_found_across_chunks_and_what_came_before_is_returned() {
        let (mut reader, _sender) =
            open_reader(&[b"\x1b[01;01HVerification fai", b"led: (0x1A) Security Violation\r\n@RE"]);
        let seen = reader.skip_to_first(&["@READY", "Verification failed"], PATIENCE).unwrap();
        assert_eq!(seen, (1, "\x1b[01;01HVerification failed".to_string()));
        let violation = reader.skip_to_first(&["Violation", "Security"], PATIENCE).unwrap();
        assert_eq!(violation, (1, ": (0x1A) Security".to_string()), "the first to end wins");
        let error = reader.skip_to_first(&["READY", "MokManager"], SHORT).unwrap_err().to_string();
        assert!(error.starts_with("no `READY` or `MokManager` within "), "{error}");
    }

    #[test]
    fn forwarded_bytes_arrive_and_the_channel_closes_at_the_end() {
        let mut reader = FrameReader::new(forward_bytes(std::io::Cursor::new(frame_bytes(FrameKind::Ok, b""))));
        assert_eq!(reader.next_frame(PATIENCE).unwrap(), frame(FrameKind::Ok, b""));
        assert!(reader.next_frame(PATIENCE).unwrap_err().to_string().starts_with("the serial stream ended"));
    }
}
