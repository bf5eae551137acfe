//! The QEMU Machine Protocol client: JSON lines over a unix socket, used to
//! take screendumps (QEMU's own view of the VGA card), to press keys and
//! to quit.

use std::io::{BufRead, BufReader, ErrorKind, Write};
use std::os::unix::net::UnixStream;
use std::path::Path;
use std::time::{Duration, Instant};

use anyhow::{bail, Context, Result};
use serde_json::{json, Value};

use crate::picture::ppm::parse_ppm;
use crate::picture::Image;

/// Longest wait for QEMU to create the socket, and for any one answer.
pub const QMP_TIMEOUT: Duration = Duration::from_secs(30);

/// A QMP session in command mode.
pub struct Qmp {
    reader: BufReader<UnixStream>,
    writer: UnixStream,
}

impl Qmp {
    /// Connects to `socket` (retrying until QEMU has created it, within
    /// [`QMP_TIMEOUT`]), reads the greeting and leaves capabilities
    /// negotiation mode. `running` is asked between tries and fails when
    /// QEMU has gone: its error ends the wait at once.
    pub fn connect(socket: &Path, mut running: impl FnMut() -> Result<()>) -> Result<Self> {
        let deadline = Instant::now() + QMP_TIMEOUT;
        let stream = loop {
            match UnixStream::connect(socket) {
                Ok(stream) => break stream,
                Err(_) if Instant::now() < deadline => {
                    running()?;
                    std::thread::sleep(Duration::from_millis(20));
                }
                Err(error) => {
                    return Err(error).with_context(|| format!("failed to connect to QMP socket {}", socket.display()))
                }
            }
        };
        stream.set_read_timeout(Some(QMP_TIMEOUT))?;
        stream.set_write_timeout(Some(QMP_TIMEOUT))?;
        let mut qmp = Self { reader: BufReader::new(stream.try_clone()?), writer: stream };
        let greeting = qmp.read_message()?.context("QMP closed before its greeting")?;
        if greeting.get("QMP").is_none() {
            bail!("QMP greeting expected, got {greeting}");
        }
        qmp.execute("qmp_capabilities", json!({}))?;
        Ok(qmp)
    }

    /// The next JSON message, or `None` when QEMU closed the socket.
    fn read_message(&mut self) -> Result<Option<Value>> {
        let mut line = String::new();
        match self.reader.read_line(&mut line) {
            Ok(0) => Ok(None),
            Err(error) if error.kind() == ErrorKind::ConnectionReset => Ok(None),
            Ok(_) => Ok(Some(
                serde_json::from_str(&line)
                    .with_context(|| format!("QMP sent something that is not JSON: {line:?}"))?,
            )),
            Err(error) if matches!(error.kind(), ErrorKind::WouldBlock | ErrorKind::TimedOut) => {
                bail!("QMP sent nothing within {} s", QMP_TIMEOUT.as_secs())
            }
            Err(error) => Err(error).context("failed to read from QMP"),
        }
    }

    /// Runs one command and returns its `return` value, skipping the
    /// asynchronous events QEMU sends in between. `None` if QEMU closed the
    /// socket first (as it may after `quit`).
    fn execute_allowing_close(&mut self, command: &str, arguments: Value) -> Result<Option<Value>> {
        let request = json!({ "execute": command, "arguments": arguments });
        writeln!(self.writer, "{request}").with_context(|| format!("failed to send QMP `{command}`"))?;
        loop {
            let Some(message) = self.read_message().with_context(|| format!("waiting for QMP `{command}`"))? else {
                return Ok(None);
            };
            if let Some(value) = message.get("return") {
                return Ok(Some(value.clone()));
            }
            if let Some(error) = message.get("error") {
                bail!("QMP `{command}` failed: {error}");
            }
        }
    }

    fn execute(&mut self, command: &str, arguments: Value) -> Result<Value> {
        self.execute_allowing_close(command, arguments)?
            .with_context(|| format!("QMP closed before answering `{command}`"))
    }

    /// What the emulated display shows now, as QEMU renders it: for mode
    /// 13h a 640x400 picture. `device`: the QEMU id of the display, `None`
    /// for the first. QEMU writes a PPM to `scratch`, which is read back
    /// and parsed.
    pub fn screendump(&mut self, scratch: &Path, device: Option<&str>) -> Result<Image> {
        let filename = scratch.to_str().context("screendump path is not UTF-8")?;
        let arguments = match device {
            Some(device) => json!({ "filename": filename, "device": device }),
            None => json!({ "filename": filename }),
        };
        self.execute("screendump", arguments)?;
        let bytes = std::fs::read(scratch).with_context(|| format!("failed to read the screendump {filename}"))?;
        parse_ppm(&bytes).with_context(|| format!("bad screendump {filename}"))
    }

    /// Presses and releases the key QEMU names `qcode` (`spc`, `ret`, `esc`,
    /// `5`, ...) on the emulated keyboard (QMP `send-key`, which releases
    /// it after QEMU's default hold time of 100 ms). Returns once QEMU has
    /// queued the key, not once the guest has read it.
    pub fn send_key(&mut self, qcode: &str) -> Result<()> {
        self.execute("send-key", json!({ "keys": [{ "type": "qcode", "data": qcode }] }))
            .with_context(|| format!("failed to press the key `{qcode}`"))?;
        Ok(())
    }

    /// The host file behind QEMU's character device `label` (`serial0` is
    /// COM1), as `query-chardev` names it: `pty:/dev/pts/3` for a
    /// pseudo-terminal.
    pub fn chardev_filename(&mut self, label: &str) -> Result<String> {
        let devices = self.execute("query-chardev", json!({}))?;
        let device = devices
            .as_array()
            .and_then(|devices| devices.iter().find(|device| device["label"] == label))
            .with_context(|| format!("QEMU has no character device `{label}`: {devices}"))?;
        device["filename"].as_str().map(str::to_string).with_context(|| format!("`{label}` has no file: {device}"))
    }

    /// Raises a non-maskable interrupt on every CPU.
    pub fn inject_nmi(&mut self) -> Result<()> {
        self.execute("inject-nmi", json!({})).context("failed to inject an NMI")?;
        Ok(())
    }

    /// Asks QEMU to exit.
    pub fn quit(mut self) -> Result<()> {
        self.execute_allowing_close("quit", json!({}))?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn connecting_gives_up_as_soon_as_qemu_is_gone() {
        let socket = Path::new("/nonexistent/qmp.sock");
        let mut asked = 0;
        let gone = || {
            asked += 1;
            bail!("QEMU exited (exit status: 1) before its QMP socket answered")
        };
        let error = Qmp::connect(socket, gone).err().expect("no QMP there");
        assert_eq!(error.to_string(), "QEMU exited (exit status: 1) before its QMP socket answered");
        assert_eq!(asked, 1, "the connection was retried after QEMU had gone");
    }
}
