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

/// One checked frame.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Frame {
    pub kind: FrameKind,
    pub payload: Vec<u8>,
}

impl Frame {
    /// The payload as text, for the kinds that carry text.
    pub fn text(&self) -> String {
        String::from_utf8_lossy(&self.payload).into_owned()
    }
}

/// Starts a thread that forwards everything `source` yields into the
/// returned channel; the channel closes when `source` ends.
pub fn forward_bytes(mut source: impl Read + Send + 'static) -> Receiver<Vec<u8>> {
    let (sender, receiver) = mpsc::channel();
    std::thread::spawn(move || {
        let mut chunk = vec![0; 64 * 1024];
        while let Ok(n @ 1..) = source.read(&mut chunk) {
            if sender.send(chunk[..n].to_vec()).is_err() {
                break;
            }
        }
    });
    receiver
}

/// Finds frames in the bytes coming over a channel.
pub struct FrameReader {
    source: Receiver<Vec<u8>>,
    /// Received, not yet consumed.
    pending: Vec<u8>,
    /// The last [`TAIL_LEN`] bytes received, for error messages.
    tail: VecDeque<u8>,
    closed: bool,
}

impl FrameReader {
    pub fn new(source: Receiver<Vec<u8>>) -> Self {
        Self { source, pending: Vec::new(), tail: VecDeque::with_capacity(TAIL_LEN), closed: false }
    }

    /// The next frame, skipping noise. Fails on a frame whose CRC or length
    /// does not check, when the stream closes, and after `timeout`; every
    /// error shows the last bytes received.
    pub fn next_frame(&mut self, timeout: Duration) -> Result<Frame> {
        let deadline = Instant::now() + timeout;
        loop {
            if let Some(frame) = self.take_frame()? {
                return Ok(frame);
            }
            if self.closed {
                bail!("the serial stream ended (QEMU exited?) before a complete frame; {}", self.last_bytes());
            }
            let remaining = deadline.saturating_duration_since(Instant::now());
            match self.source.recv_timeout(remaining) {
                Ok(chunk) => self.receive(&chunk),
                Err(RecvTimeoutError::Timeout) => {
                    bail!("no complete frame within {:.1} s; {}", timeout.as_secs_f64(), self.last_bytes())
                }
                Err(RecvTimeoutError::Disconnected) => self.closed = true,
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

    fn receive(&mut self, chunk: &[u8]) {
        self.pending.extend_from_slice(chunk);
        let keep = chunk.len().min(TAIL_LEN);
        if self.tail.len() + keep > TAIL_LEN {
            self.tail.drain(..self.tail.len() + keep - TAIL_LEN);
        }
        self.tail.extend(&chunk[chunk.len() - keep..]);
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
                bail!(
                    "garbage frame header `{header}`: no frame carries more than {MAX_PAYLOAD} bytes; {}",
                    self.last_bytes()
                );
            }
            let payload_start = line_len + 1;
            let frame_end = payload_start + header.len + 1;
            if self.pending.len() < frame_end {
                return Ok(None);
            }
            let frame: Vec<u8> = self.pending.drain(..frame_end).collect();
            let payload = &frame[payload_start..frame_end - 1];
            if !header.matches(payload) {
                bail!(
                    "{} frame of {} bytes fails its CRC32 check (header says {:08x}, payload hashes to {:08x}); {}",
                    header.kind.name(),
                    header.len,
                    header.crc,
                    crc32fast::hash(payload),
                    self.last_bytes()
                );
            }
            if frame[frame_end - 1] != b'\n' {
                bail!(
                    "{} frame of {} bytes is not followed by a newline; {}",
                    header.kind.name(),
                    header.len,
                    self.last_bytes()
                );
            }
            return Ok(Some(Frame { kind: header.kind, payload: payload.to_vec() }));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::mpsc::Sender;

    const SHORT: Duration = Duration::from_millis(50);

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
        Frame { kind, payload: payload.to_vec() }
    }

    #[test]
    fn a_frame_split_across_chunks_is_reassembled() {
        let bytes = frame_bytes(FrameKind::Ok, b"pong");
        let chunks: Vec<&[u8]> = bytes.chunks(3).collect();
        let (mut reader, _sender) = open_reader(&chunks);
        assert_eq!(reader.next_frame(SHORT).unwrap(), frame(FrameKind::Ok, b"pong"));
    }

    #[test]
    fn noise_between_frames_is_skipped() {
        let mut stream = b"SeaBIOS noise\r\n@ stray at\n@OK 4\n@NOPE 1 00000000\nx\n".to_vec();
        stream.extend(frame_bytes(FrameKind::Ready, b"vga: 0 mismatches"));
        stream.extend(b"more noise @@");
        stream.extend(frame_bytes(FrameKind::Err, b"unknown command `FROB`\n@OK 0 00000000\n"));
        let (mut reader, _sender) = open_reader(&[&stream]);
        assert_eq!(reader.next_frame(SHORT).unwrap(), frame(FrameKind::Ready, b"vga: 0 mismatches"));
        assert_eq!(
            reader.next_frame(SHORT).unwrap(),
            frame(FrameKind::Err, b"unknown command `FROB`\n@OK 0 00000000\n")
        );
    }

    #[test]
    fn binary_payloads_with_newlines_and_marks_survive() {
        let payload: Vec<u8> = (0..=255u8).cycle().take(DUMP_LEN).collect();
        let (mut reader, _sender) = open_reader(&[&frame_bytes(FrameKind::Dump, &payload)]);
        assert_eq!(reader.next_frame(SHORT).unwrap(), frame(FrameKind::Dump, &payload));
    }

    #[test]
    fn a_bad_crc_is_an_error_naming_the_frame_and_reading_goes_on() {
        let mut corrupt = frame_bytes(FrameKind::Ok, b"pong");
        let last = corrupt.len() - 2;
        corrupt[last] = b'G';
        corrupt.extend(frame_bytes(FrameKind::Ok, b"again"));
        let (mut reader, _sender) = open_reader(&[&corrupt]);
        let error = reader.next_frame(SHORT).unwrap_err().to_string();
        assert!(error.starts_with("OK frame of 4 bytes fails its CRC32 check"), "{error}");
        assert!(error.contains("ponG"), "{error}");
        assert_eq!(reader.next_frame(SHORT).unwrap(), frame(FrameKind::Ok, b"again"));
    }

    #[test]
    fn a_missing_terminator_is_an_error() {
        let mut bytes = frame_bytes(FrameKind::Ok, b"pong");
        *bytes.last_mut().unwrap() = b'X';
        let (mut reader, _sender) = open_reader(&[&bytes]);
        let error = reader.next_frame(SHORT).unwrap_err().to_string();
        assert!(error.contains("not followed by a newline"), "{error}");
    }

    #[test]
    fn an_absurd_length_is_garbage() {
        let (mut reader, _sender) = open_reader(&[b"@DUMP 999999999 00000000\n"]);
        let error = reader.next_frame(SHORT).unwrap_err().to_string();
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
        let error = reader.next_frame(Duration::from_secs(10)).unwrap_err().to_string();
        assert!(error.starts_with("the serial stream ended"), "{error}");
        assert!(started.elapsed() < Duration::from_secs(1));
    }

    #[test]
    fn text_is_found_across_chunks_and_what_came_before_is_returned() {
        let (mut reader, _sender) =
            open_reader(&[b"\x1b[01;01HVerification fai", b"led: (0x1A) Security Violation\r\n@RE"]);
        let seen = reader.skip_to_first(&["@READY", "Verification failed"], SHORT).unwrap();
        assert_eq!(seen, (1, "\x1b[01;01HVerification failed".to_string()));
        let violation = reader.skip_to_first(&["Violation", "Security"], SHORT).unwrap();
        assert_eq!(violation, (1, ": (0x1A) Security".to_string()), "the first to end wins");
        let error = reader.skip_to_first(&["READY", "MokManager"], SHORT).unwrap_err().to_string();
        assert!(error.starts_with("no `READY` or `MokManager` within "), "{error}");
    }

    #[test]
    fn forwarded_bytes_arrive_and_the_channel_closes_at_the_end() {
        let mut reader = FrameReader::new(forward_bytes(std::io::Cursor::new(frame_bytes(FrameKind::Ok, b""))));
        assert_eq!(reader.next_frame(SHORT).unwrap(), frame(FrameKind::Ok, b""));
        assert!(reader.next_frame(SHORT).unwrap_err().to_string().starts_with("the serial stream ended"));
    }
}
