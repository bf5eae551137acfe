//! Bad input gets errors, never a crash or a hang, and the kernel keeps
//! serving afterwards.

use anyhow::{bail, ensure, Result};
use harness::{Qemu, QemuOptions, Reply};
use protocol::{Command, CommandError, ErrorReply, MAX_LINE};
use scenes::file::LineError;

/// Sends PING and expects a pong that counts no lost bytes: the proof the
/// kernel still serves.
fn still_serving(qemu: &mut Qemu) -> Result<()> {
    let losses = qemu.console.ping()?;
    ensure!(losses.none(), "PING says the serial line lost bytes: {losses}");
    Ok(())
}

#[test]
fn malformed_commands_get_errors_naming_the_problem_and_the_kernel_keeps_serving() -> Result<()> {
    let overlong = "A".repeat(MAX_LINE + 100);
    let command = ErrorReply::Command;
    let cases: [(&[u8], ErrorReply); 12] = [
        (b"", command(CommandError::Empty)),
        (b"FROB 1", command(CommandError::Unknown("FROB"))),
        (b"CLEAR", command(CommandError::MissingArgument("colour"))),
        (b"CLEAR 256", command(CommandError::BadArgument("256"))),
        (b"DUMP now", command(CommandError::ExtraArgument("now"))),
        (b"POLY exact", command(CommandError::MissingArgument("polygon"))),
        (b"FAULT nap", command(CommandError::BadArgument("nap"))),
        (b"DRAW no-such-scene", ErrorReply::UnknownScene("no-such-scene")),
        (b"DRAW abrash38-1 no-such-method", command(CommandError::UnknownMethod("no-such-method"))),
        (b"POLY abrash_float color=999 0,0 9,0 0,9", ErrorReply::Polygon(LineError::BadColor("999".into()))),
        (b"PI\xffNG", command(CommandError::NotAscii)),
        (overlong.as_bytes(), command(CommandError::TooLong)),
    ];
    let mut qemu = Qemu::boot(QemuOptions::default())?;
    for (line, expected) in cases {
        qemu.console.send_bytes(&[line, b"\n"].concat())?;
        let shown = String::from_utf8_lossy(&line[..line.len().min(40)]).into_owned();
        match qemu.console.reply()? {
            Reply::Err(text) if ErrorReply::parse(&text)? == expected => {}
            other => bail!("`{shown}` answered {other:?}, expected ERR {expected:?}"),
        }
    }
    still_serving(&mut qemu)
}

/// xorshift64*: a fixed sequence with no dependency, so a failure replays.
fn seeded_bytes(mut state: u64, len: usize) -> Vec<u8> {
    (0..len)
        .map(|_| {
            state ^= state >> 12;
            state ^= state << 25;
            state ^= state >> 27;
            (state.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 56) as u8
        })
        .collect()
}

#[test]
fn random_bytes_get_one_error_per_line_and_the_kernel_keeps_serving() -> Result<()> {
    let mut noise = seeded_bytes(0x5eed_0f90_1ab5, 20 * 1024);
    noise.push(b'\n');
    // Every line, the last one ended by the `\n` just pushed.
    let lines: Vec<&[u8]> = noise[..noise.len() - 1].split(|&b| b == b'\n').collect();
    for line in &lines {
        ensure!(Command::parse(line).is_err(), "the seeded noise contains a valid command: {:?}", line.escape_ascii());
    }
    let mut qemu = Qemu::boot(QemuOptions::default())?;
    qemu.console.send_bytes(&noise)?;
    for n in 1..=lines.len() {
        match qemu.console.reply()? {
            Reply::Err(_) => {}
            other => bail!("line {n} of {} of random bytes answered {other:?}, expected ERR", lines.len()),
        }
    }
    still_serving(&mut qemu)
}
