//! The serial line in: the kernel receives COM1 by interrupt into a ring
//! buffer, so a host may send many commands at once, while the demo is
//! still playing, and every one is answered, in order.
//!
//! QEMU's UART holds bytes back while its FIFO is full, so it never
//! overruns as a real one can: this proves the receive path (interrupt,
//! ring, console) keeps every byte in order, and that PING reports no loss;
//! it cannot provoke an overrun.

use std::time::Duration;

use anyhow::{bail, ensure, Context, Result};
use harness::{Qemu, QemuOptions, Reply};
use protocol::{Cleared, Pong};

/// Commands in the burst: 160 lines of 7 to 9 bytes, some 1.3 KB, 80
/// times the UART's 16-byte FIFO.
const BURST: u32 = 160;

/// `CLEAR C` answers `OK clear C`: the colours go round in a scrambled
/// order, so a reply out of place or missing shows.
fn colour(i: u32) -> u32 {
    (i * 97 + 31) % 256
}

#[test]
fn a_burst_of_commands_sent_while_the_demo_plays_is_answered_in_full_in_order() -> Result<()> {
    let mut qemu = Qemu::boot(QemuOptions::default())?;
    // Let the demo play a moment: the burst arrives in the middle of it.
    std::thread::sleep(Duration::from_millis(500));
    let burst: String = (0..BURST).map(|i| format!("CLEAR {}\n", colour(i))).collect();
    qemu.console.send_bytes(format!("{burst}PING\n").as_bytes())?;
    for i in 0..BURST {
        let expected = Cleared { color: colour(i) as u8 };
        match qemu.console.reply()? {
            Reply::Ok(text) if Cleared::parse(&text)? == expected => {}
            other => bail!("reply {i} of the burst is {other:?}, expected OK {expected:?}"),
        }
    }
    let Pong { losses, .. } = match qemu.console.reply()? {
        Reply::Ok(text) => Pong::parse(&text).context("the burst's closing PING")?,
        other => bail!("the burst's closing PING answered {other:?}"),
    };
    ensure!(losses.none(), "after the burst PING says the serial line lost bytes: {losses}");
    Ok(())
}
