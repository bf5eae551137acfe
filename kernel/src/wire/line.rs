//! A command line as its bytes arrive, for the show and the server
//! alike: the show keeps playing while a line is incomplete (bytes
//! accumulate between its frames, `demo.rs`), and only a complete line
//! stops it. A line is kept up to `protocol::MAX_LINE` bytes; an overlong
//! one is thrown away up to its newline; one left unfinished, no byte
//! arriving, for `PARTIAL_LINE_IDLE_SECONDS` is dropped, with a `LOG`
//! frame saying so, so that a stray byte on the line (a cable plugged in,
//! an adapter powering up) never holds anything up for good.

use alloc::vec::Vec;

use protocol::{LogEvent, MAX_LINE, PARTIAL_LINE_IDLE_SECONDS};

use crate::time::clock::Deadline;
use crate::wire::serial;

/// What ended a line.
pub enum Complete {
    /// A line, without its `\n`.
    Line(Vec<u8>),
    /// A line longer than `MAX_LINE`, thrown away.
    TooLong,
}

/// The line being received.
pub struct PendingLine {
    /// The line so far, without its `\n`; never longer than `MAX_LINE`.
    bytes: Vec<u8>,
    /// The current line outgrew `MAX_LINE`: drop bytes up to its `\n`.
    overlong: bool,
    /// When the line is given up if no byte comes: none between lines.
    give_up: Option<Deadline>,
}

impl PendingLine {
    pub fn new() -> Self {
        Self { bytes: Vec::with_capacity(MAX_LINE), overlong: false, give_up: None }
    }

    /// Takes `byte`; the line if it ended it.
    pub fn push(&mut self, byte: u8) -> Option<Complete> {
        let complete = match byte {
            b'\n' if self.overlong => {
                self.overlong = false;
                Some(Complete::TooLong)
            }
            b'\n' => Some(Complete::Line(core::mem::take(&mut self.bytes))),
            _ if self.overlong => None,
            _ if self.bytes.len() == MAX_LINE => {
                self.overlong = true;
                self.bytes.clear();
                None
            }
            _ => {
                self.bytes.push(byte);
                None
            }
        };
        let started = !self.bytes.is_empty() || self.overlong;
        self.give_up = started.then(|| Deadline::after_micros(PARTIAL_LINE_IDLE_SECONDS * 1_000_000));
        complete
    }

    /// Takes back a completed line's buffer (cleared), to receive the next
    /// line in without allocating, if none has started meanwhile.
    pub fn recycle(&mut self, mut buffer: Vec<u8>) {
        if self.bytes.is_empty() && self.bytes.capacity() < buffer.capacity() {
            buffer.clear();
            self.bytes = buffer;
        }
    }

    /// When the line being received is given up if no byte comes: `None`
    /// between lines.
    pub fn give_up(&self) -> Option<Deadline> {
        self.give_up
    }

    /// Drops the unfinished line if it has been idle for its bound,
    /// saying so in a `LOG` frame; whether it did.
    pub fn drop_if_idle(&mut self) -> bool {
        if !self.give_up.is_some_and(Deadline::passed) {
            return false;
        }
        serial::send_log(LogEvent::LineDropped {
            overlong: self.overlong,
            kept: self.bytes.len(),
            idle_seconds: PARTIAL_LINE_IDLE_SECONDS,
        });
        self.bytes.clear();
        self.overlong = false;
        self.give_up = None;
        true
    }
}
