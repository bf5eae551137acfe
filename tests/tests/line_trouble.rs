//! What a real serial line does that a quiet one does not: a break and
//! stray bytes (a cable plugged in, a USB adapter powering up), and a UART
//! whose interrupt never reaches the CPU (a UEFI PC that does not route
//! IRQ 4, a Super I/O set to another line).
//!
//! QEMU's UART cannot make framing or parity errors, but its telnet
//! backend carries a break: IAC BRK (bytes 255 243) becomes a break on the
//! UART's receiving end, one 0 byte flagged in the line status. And COM1
//! can be wired to IRQ 3, which the kernel does not listen to.

use std::time::{Duration, Instant};

use anyhow::{bail, ensure, Result};
use harness::checks::{distinct_screens, dump_matches_host_render};
use harness::{Qemu, QemuOptions, Reply, SerialLine};
use protocol::{Cleared, LineErrors, LogEvent, PARTIAL_LINE_IDLE_SECONDS};
use scenes::builtin;

/// Telnet's "interpret as command" and "break".
const IAC: u8 = 255;
const BRK: u8 = 243;

/// How long the show is watched while a line is unfinished, and how often
/// its screen is taken: a still page of the show stays 3 s, so 8 s see at
/// least two entries.
const WATCH: Duration = Duration::from_secs(8);
const WATCH_EVERY: Duration = Duration::from_millis(500);
/// How long after the event the watch starts.
const SETTLE: Duration = Duration::from_secs(1);

/// A break, then stray bytes with no newline: the break's byte is dropped
/// and counted; the stray bytes start a line that stays unfinished, and
/// the show plays on meanwhile (only a complete line stops it); after
/// `PARTIAL_LINE_IDLE_SECONDS` the kernel drops the line and says so.
/// `PING` then answers, counting the break.
#[test]
fn after_a_break_and_stray_bytes_the_show_plays_on_and_ping_counts_the_break() -> Result<()> {
    let mut qemu = Qemu::boot(QemuOptions { serial: SerialLine::Telnet { port: 0 }, ..QemuOptions::default() })?;
    std::thread::sleep(Duration::from_secs(1));
    qemu.console.send_bytes(&[IAC, BRK])?;
    // Time for the break to reach the UART on its own, ahead of the bytes.
    std::thread::sleep(Duration::from_millis(500));
    qemu.console.send_bytes(b"\x01~x\x7fq\r")?;
    let sent = Instant::now();
    // Whatever it does to the screen at once (the old kernel cleared it)
    // is over by then: the watch is of what follows.
    std::thread::sleep(SETTLE);
    let screens = distinct_screens(&mut qemu, WATCH, WATCH_EVERY)?;
    ensure!(
        screens >= 2,
        "with an unfinished line pending, QEMU showed {screens} screen(s) in {} s: the show stands still",
        WATCH.as_secs()
    );
    let dropped_by = Duration::from_secs(PARTIAL_LINE_IDLE_SECONDS + 2);
    std::thread::sleep(dropped_by.saturating_sub(sent.elapsed()));
    let losses = qemu.console.ping()?;
    let one_break = LineErrors { breaks: 1, ..LineErrors::default() };
    ensure!(losses.errors == Some(one_break), "PING counts {losses}, expected the one break and nothing else");
    ensure!(losses.overruns == 0 && losses.dropped == 0, "PING says the serial line lost bytes: {losses}");
    // The six bytes after the break, its 0 byte dropped.
    let dropped = LogEvent::LineDropped { overlong: false, kept: 6, idle_seconds: PARTIAL_LINE_IDLE_SECONDS };
    let dropped = qemu.console.logs().contains(&dropped);
    ensure!(dropped, "no LOG says the unfinished line was dropped: {:?}", qemu.console.logs());
    Ok(())
}

/// Commands in the burst sent to a kernel that receives by polling alone.
const BURST: u32 = 40;

/// COM1 wired to IRQ 3: the kernel's test at boot finds its interrupt
/// does not arrive and says so, then receives by polling alone: `READY`,
/// commands, a page and its 64 KB `DUMP`, and a burst of commands in one
/// write, all answered in order, nothing lost.
#[test]
fn with_com1_on_irq_3_the_kernel_hears_every_command_by_polling() -> Result<()> {
    let mut qemu = Qemu::boot(QemuOptions { com1_irq: Some(3), ..QemuOptions::default() })?;
    let page = builtin::ABRASH40_2;
    dump_matches_host_render(&mut qemu.console, page.name, page.method)?;
    let burst: String = (0..BURST).map(|i| format!("CLEAR {i}\n")).collect();
    qemu.console.send_bytes(burst.as_bytes())?;
    for i in 0..BURST {
        let expected = Cleared { color: u8::try_from(i)? };
        match qemu.console.reply()? {
            Reply::Ok(text) if Cleared::parse(&text)? == expected => {}
            other => bail!("reply {i} of the burst is {other:?}, expected OK {expected:?}"),
        }
    }
    let losses = qemu.console.ping()?;
    ensure!(losses.none(), "PING says the serial line lost bytes: {losses}");
    ensure!(qemu.console.logs().contains(&LogEvent::Com1Polling), "no LOG says so: {:?}", qemu.console.logs());
    Ok(())
}
