//! A sealing console against a stand-in kernel: each reply matched to
//! the line it answers, a step the line damaged run again and counted, a
//! genuine `ERR` or a `FATAL` not retried, and a silent line explained
//! (`harness::client`'s sealed requests; no QEMU).

use std::time::Duration;

use harness::client::{FrameReader, TroubleKind};
use harness::Console;
use protocol::FrameHeader;
use protocol::{Command, FrameKind};
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
