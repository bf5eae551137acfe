//! A serial device as the protocol's line: `/dev/ttyUSB0`, `/dev/ttyS0`,
//! or a pseudo-terminal such as QEMU's `-serial pty`, opened through the
//! `serialport` crate raw at 115200 baud, 8 data bits, no parity, one stop
//! bit, no flow control (the kernel's COM1 settings, `kernel/src/wire/serial.rs`).

use std::io::{ErrorKind, Read};
use std::os::unix::fs::FileTypeExt;
use std::path::Path;
use std::sync::mpsc::{self, Receiver};
use std::time::Duration;

use anyhow::{bail, Context, Result};
use serialport::{DataBits, FlowControl, Parity, SerialPort, StopBits, TTYPort};

use crate::client::{gather_after, Console, FrameReader, BAUD};

/// How long one read waits before the reader thread looks whether anyone
/// still listens.
pub(super) const READ_POLL: Duration = Duration::from_millis(200);
/// Longest wait for room to send a command: the kernel takes bytes as they
/// come, but under QEMU the UART holds them back while its FIFO is full.
const WRITE_TIMEOUT: Duration = Duration::from_secs(10);

/// Opens `device` as the kernel's line and returns a console on it that
/// seals its commands and retries a damaged step up to `retries` times.
/// Fails saying what to do when the device is missing, not a tty, not
/// ours to open, or taken.
pub fn open_console(device: &Path, retries: u32) -> Result<Console> {
    let port = open_port(device)?;
    let mut writer = port.try_clone_native().with_context(|| format!("cannot use {} twice", device.display()))?;
    writer.set_timeout(WRITE_TIMEOUT)?;
    Ok(Console::sealed(writer, FrameReader::new(forward_tty(port)), retries))
}

/// Opens `device` raw at [`BAUD`] 8N1 without flow control, for this
/// process alone.
pub(super) fn open_port(device: &Path) -> Result<TTYPort> {
    let name = device.display();
    let metadata = match std::fs::metadata(device) {
        Ok(metadata) => metadata,
        Err(error) if error.kind() == ErrorKind::NotFound => bail!(
            "no such device {name}: is the USB serial adapter plugged in, or is the port called otherwise? \
             (`ls /dev/ttyUSB* /dev/ttyS*` lists the candidates; `dmesg | tail` names an adapter just plugged in)"
        ),
        Err(error) => return Err(error).with_context(|| format!("cannot look at {name}")),
    };
    if !metadata.file_type().is_char_device() {
        bail!("{name} is not a serial port (not a character device); give the tty the cable is on, e.g. /dev/ttyUSB0");
    }
    let builder = serialport::new(device.to_string_lossy(), BAUD)
        .data_bits(DataBits::Eight)
        .parity(Parity::None)
        .stop_bits(StopBits::One)
        .flow_control(FlowControl::None)
        .timeout(READ_POLL);
    builder.open_native().map_err(|error| explain_open_error(device, error))
}

/// What to do about a failure to open `device`.
fn explain_open_error(device: &Path, error: serialport::Error) -> anyhow::Error {
    let name = device.display();
    let advice = match error.kind() {
        serialport::ErrorKind::Io(ErrorKind::PermissionDenied) => format!(
            "permission denied: serial ports belong to the `dialout` group; add yourself with \
             `sudo usermod -aG dialout $USER`, then log in again (or check `ls -l {name}`)"
        ),
        serialport::ErrorKind::Io(ErrorKind::NotFound) => "no such device (unplugged?)".to_string(),
        serialport::ErrorKind::NoDevice => {
            "the device is busy: another program has it open (a terminal such as minicom, screen or picocom, \
             or another check); close it and try again"
                .to_string()
        }
        _ => format!("{error} (is it a serial port? `stty -F {name}` should print its settings)"),
    };
    anyhow::anyhow!("cannot open {name}: {advice}")
}

/// Starts a thread that forwards what `port` receives into the returned
/// channel. A read that times out sends an empty chunk, so the thread
/// notices within [`READ_POLL`] that the console is gone and closes the
/// port; the channel closes when the device goes away (a pseudo-terminal
/// whose other side closed, an adapter unplugged).
fn forward_tty(mut port: TTYPort) -> Receiver<Vec<u8>> {
    let (sender, receiver) = mpsc::channel();
    std::thread::spawn(move || {
        let mut chunk = vec![0; 64 * 1024];
        loop {
            let received = match port.read(&mut chunk) {
                Ok(0) => break,
                Ok(n) => chunk[..n].to_vec(),
                Err(error) if matches!(error.kind(), ErrorKind::TimedOut | ErrorKind::Interrupted) => Vec::new(),
                Err(_) => break,
            };
            let n = received.len();
            if sender.send(received).is_err() {
                break;
            }
            gather_after(n);
        }
    });
    receiver
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_missing_device_is_named_with_what_to_check() {
        let error = open_port(Path::new("/dev/ttyNOPE9")).unwrap_err().to_string();
        assert!(error.starts_with("no such device /dev/ttyNOPE9: is the USB serial adapter plugged in"), "{error}");
    }

    #[test]
    fn a_file_that_is_no_tty_is_refused() {
        let error = open_port(Path::new("Cargo.toml")).unwrap_err().to_string();
        assert!(error.starts_with("Cargo.toml is not a serial port"), "{error}");
    }

    #[test]
    fn a_character_device_that_is_no_tty_is_refused_saying_so() {
        let error = open_port(Path::new("/dev/null")).unwrap_err().to_string();
        assert!(error.starts_with("cannot open /dev/null: "), "{error}");
        assert!(error.contains("is it a serial port?"), "{error}");
    }

    /// Both ends of a pseudo-terminal pair: what one writes the console on
    /// the other reads as frames, and a second open of a device in use is
    /// refused as busy.
    #[test]
    fn a_pseudo_terminal_carries_frames_and_is_ours_alone() {
        let (mut master, slave) = TTYPort::pair().unwrap();
        let path = slave.name().unwrap();
        drop(slave);
        let mut console = open_console(Path::new(&path), 0).unwrap();
        let payload = b"pong overruns=0 dropped=0 heap_used=1 heap_free_largest=2";
        let header = protocol::FrameHeader::for_payload(protocol::FrameKind::Ok, payload);
        std::io::Write::write_all(&mut master, format!("{header}\n").as_bytes()).unwrap();
        std::io::Write::write_all(&mut master, payload).unwrap();
        std::io::Write::write_all(&mut master, b"\n").unwrap();
        assert_eq!(console.channel.frames.next_frame(Duration::from_secs(5)).unwrap().payload, payload);
        let error = open_port(Path::new(&path)).unwrap_err().to_string();
        assert!(error.contains("the device is busy"), "{error}");
    }
}
