//! A running QEMU: the child process (killed on drop, every wait
//! bounded), its channels (COM1 on its stdin and stdout or a TCP port, QMP
//! on a unix socket), and what QMP asks of it.

use std::net::{TcpListener, TcpStream};
use std::path::{Path, PathBuf};
use std::process::{Command, ExitStatus, Stdio};
use std::sync::mpsc::Receiver;
use std::time::{Duration, Instant};

use anyhow::{anyhow, bail, Context, Result};
use boot_image::build_image;
use install::command_line;
use protocol::{Firmware, Ready};

use super::arguments::{qemu_arguments, qmp_socket, uefi_variables, CARD_BEHIND_ID};
use super::board::{hpet_table_body, madt_body, AHEAD_ID, HPET_TABLE_FILE, MADT_FILE};
use super::options::{QemuOptions, SerialLine};
use super::qmp::{Qmp, QMP_TIMEOUT};
use crate::client::{forward_bytes, Console, FrameReader};
use crate::picture::Image;
use crate::supervisor::Supervised;
use install::ensure_all;
use install::{ovmf_microsoft_vars, ovmf_vars, QEMU};

/// Longest wait for QEMU to exit after QMP `quit`.
const QUIT_TIMEOUT: Duration = Duration::from_secs(30);

/// A TCP port of 127.0.0.1 free a moment ago.
fn free_port() -> Result<u16> {
    let listener = TcpListener::bind("127.0.0.1:0").context("failed to find a free TCP port")?;
    Ok(listener.local_addr()?.port())
}

/// A connection to QEMU's server on 127.0.0.1:`port`, retried until QEMU
/// listens there, within `timeout`.
fn connect_within(port: u16, timeout: Duration) -> Result<TcpStream> {
    let deadline = Instant::now() + timeout;
    loop {
        match TcpStream::connect(("127.0.0.1", port)) {
            Ok(stream) => return Ok(stream),
            Err(_) if Instant::now() < deadline => std::thread::sleep(Duration::from_millis(20)),
            Err(error) => return Err(error).with_context(|| format!("failed to connect to COM1 on port {port}")),
        }
    }
}

/// A running QEMU. Dropping it kills the process and removes its run
/// folder (its watchdog does both if the harness dies first).
pub struct Qemu {
    process: Supervised,
    /// The protocol session on COM1.
    pub console: Console,
    /// What the kernel's READY frame said, once booted.
    pub ready: Ready,
    qmp: Option<Qmp>,
    stderr: Receiver<Vec<u8>>,
    stderr_seen: Vec<u8>,
    /// The QEMU id of the display screendumps are taken of; `None`: the
    /// first one.
    screen: Option<&'static str>,
}

impl Qemu {
    /// Builds (or reuses) the image, starts QEMU and waits for the kernel's
    /// READY frame.
    pub fn boot(options: QemuOptions) -> Result<Self> {
        let mut qemu = Self::spawn(&build_image()?, options)?;
        qemu.ready = match qemu.console.wait_ready() {
            Ok(ready) => ready,
            Err(error) => return Err(qemu.explain(error)),
        };
        Ok(qemu)
    }

    /// Starts QEMU on `image`, printing its command line. Does not wait for
    /// the kernel.
    pub fn spawn(image: &Path, options: QemuOptions) -> Result<Self> {
        let variables = if options.secure_boot { ovmf_microsoft_vars() } else { ovmf_vars() };
        Self::spawn_with_variables(image, options, &variables)
    }

    /// [`Qemu::spawn`] under UEFI with a copy of `variables` as the
    /// firmware's variable store (the Secure Boot tests' MOK lists), once
    /// what the options need is installed ([`QemuOptions::needs`]).
    pub fn spawn_with_variables(image: &Path, options: QemuOptions, variables: &Path) -> Result<Self> {
        ensure_all(&options.needs())?;
        let options = match options.serial {
            SerialLine::Telnet { port: 0 } => {
                QemuOptions { serial: SerialLine::Telnet { port: free_port()? }, ..options }
            }
            _ => options,
        };
        let mut process = Supervised::with_folder("qemu")?;
        let run_dir = process.folder().to_path_buf();
        if options.firmware == Firmware::Uefi {
            std::fs::copy(variables, uefi_variables(&run_dir))
                .with_context(|| format!("failed to copy {} into {}", variables.display(), run_dir.display()))?;
        }
        if let Some(address) = options.hpet_table_at {
            let table = run_dir.join(HPET_TABLE_FILE);
            std::fs::write(&table, hpet_table_body(address))
                .with_context(|| format!("failed to write {}", table.display()))?;
        }
        if let Some(address) = options.io_apic_table_at {
            let table = run_dir.join(MADT_FILE);
            std::fs::write(&table, madt_body(address))
                .with_context(|| format!("failed to write {}", table.display()))?;
        }
        let mut command = Command::new(QEMU);
        command.args(qemu_arguments(image, &run_dir, options));
        command.stdin(Stdio::piped()).stdout(Stdio::piped()).stderr(Stdio::piped());
        eprintln!("harness: running {}", command_line(&command));
        let child = process.spawn(&mut command)?;
        let (Some(input), Some(output), Some(stderr)) = (child.stdin.take(), child.stdout.take(), child.stderr.take())
        else {
            unreachable!("all three streams are piped");
        };
        let console = Console::new(input, FrameReader::new(forward_bytes(output)));
        let mut qemu = Self {
            process,
            console,
            ready: Ready::default(),
            qmp: None,
            stderr: forward_bytes(stderr),
            stderr_seen: Vec::new(),
            screen: options.adapter.pci_device().and(options.display_ahead).map(|_| CARD_BEHIND_ID),
        };
        if let SerialLine::Telnet { port } = options.serial {
            let stream = match connect_within(port, QMP_TIMEOUT) {
                Ok(stream) => stream,
                Err(error) => return Err(qemu.explain(error)),
            };
            qemu.console = Console::new(stream.try_clone()?, FrameReader::new(forward_bytes(stream)));
        }
        Ok(qemu)
    }

    /// QEMU's process id (its process group's too).
    pub fn pid(&self) -> u32 {
        self.process.pid()
    }

    /// `error` with what QEMU printed on its standard error, if anything.
    fn explain(&mut self, error: anyhow::Error) -> anyhow::Error {
        // QEMU's last words may trail the serial stream's end by a moment.
        while let Ok(chunk) = self.stderr.recv_timeout(Duration::from_millis(200)) {
            self.stderr_seen.extend(chunk);
        }
        if self.stderr_seen.is_empty() {
            return error;
        }
        let stderr = String::from_utf8_lossy(&self.stderr_seen).trim().to_string();
        error.context(format!("QEMU's standard error says: {stderr}"))
    }

    /// The QMP session, connected on first use. Gives up as soon as QEMU
    /// has exited, with what it printed on its standard error.
    pub fn qmp(&mut self) -> Result<&mut Qmp> {
        if self.qmp.is_none() {
            let socket = qmp_socket(self.process.folder());
            let child = self.process.child();
            let running = || match child.try_wait().context("failed to poll QEMU")? {
                Some(status) => bail!("QEMU exited ({status}) before its QMP socket answered"),
                None => Ok(()),
            };
            match Qmp::connect(&socket, running) {
                Ok(qmp) => self.qmp = Some(qmp),
                Err(error) => return Err(self.explain(error)),
            }
        }
        Ok(self.qmp.as_mut().expect("connected above"))
    }

    /// The pseudo-terminal COM1 is on, with [`SerialLine::Pty`].
    pub fn pty(&mut self) -> Result<PathBuf> {
        let filename = self.with_qmp(|qmp| qmp.chardev_filename("serial0"))?;
        let path = filename.strip_prefix("pty:").with_context(|| format!("COM1 is on {filename}, not a pty"))?;
        Ok(PathBuf::from(path))
    }

    /// Runs `work` on the QMP session; a failure carries what QEMU printed
    /// on its standard error (why it went away, if it did).
    fn with_qmp<T>(&mut self, work: impl FnOnce(&mut Qmp) -> Result<T>) -> Result<T> {
        let done = work(self.qmp()?);
        done.map_err(|error| self.explain(error))
    }

    /// QEMU's screendump of the display now (of the card, with
    /// `QemuOptions::display_ahead`).
    pub fn screendump(&mut self) -> Result<Image> {
        let scratch = self.process.folder().join("screen.ppm");
        let screen = self.screen;
        self.with_qmp(|qmp| qmp.screendump(&scratch, screen))
    }

    /// QEMU's screendump of the display ahead of the card
    /// (`QemuOptions::display_ahead`).
    pub fn screendump_ahead(&mut self) -> Result<Image> {
        let scratch = self.process.folder().join("screen.ppm");
        self.with_qmp(|qmp| qmp.screendump(&scratch, Some(AHEAD_ID)))
    }

    /// Raises a non-maskable interrupt on the CPU, as a chipset does to
    /// report a hardware error (QMP `inject-nmi`).
    pub fn inject_nmi(&mut self) -> Result<()> {
        self.with_qmp(|qmp| qmp.inject_nmi())
    }

    /// Presses and releases the key QEMU names `qcode` on the PS/2 keyboard,
    /// through QMP: nothing goes over the serial line, so the kernel's demo
    /// keeps playing.
    pub fn send_key(&mut self, qcode: &str) -> Result<()> {
        self.with_qmp(|qmp| qmp.send_key(qcode))
    }

    /// Asks QEMU to quit through QMP and waits (at most [`QUIT_TIMEOUT`])
    /// for it to go.
    pub fn quit(mut self) -> Result<ExitStatus> {
        self.qmp()?;
        let quit = self.qmp.take().expect("connected above").quit();
        if let Err(error) = quit {
            // QMP closed under the command: say whether QEMU had gone, and
            // how, rather than only that the socket broke.
            let error = match self.process.child().try_wait() {
                Ok(Some(status)) => error.context(format!("QEMU had already exited ({status}) when asked to quit")),
                _ => error,
            };
            return Err(self.explain(error));
        }
        self.wait_exit(QUIT_TIMEOUT)
    }

    /// Whether QEMU is still running.
    pub fn is_running(&mut self) -> Result<bool> {
        Ok(self.process.child().try_wait().context("failed to poll QEMU")?.is_none())
    }

    /// Waits at most `timeout` for QEMU to exit by itself (after `EXIT`, a
    /// fault, or `quit`) and returns its exit status.
    pub fn wait_exit(&mut self, timeout: Duration) -> Result<ExitStatus> {
        let deadline = Instant::now() + timeout;
        loop {
            if let Some(status) = self.process.child().try_wait().context("failed to poll QEMU")? {
                return Ok(status);
            }
            if Instant::now() >= deadline {
                let error = anyhow!("QEMU did not exit within {} s", timeout.as_secs_f64());
                return Err(self.explain(error));
            }
            std::thread::sleep(Duration::from_millis(20));
        }
    }

    /// Waits, with no time limit, until the user closes QEMU's window. Only
    /// for interactive runs: a person is the timeout. Fails (with QEMU's
    /// complaint) unless QEMU exits successfully, as closing the window does.
    pub fn wait_until_closed(&mut self) -> Result<()> {
        let status = self.process.child().wait().context("failed to wait for QEMU")?;
        if !status.success() {
            return Err(self.explain(anyhow!("QEMU exited with {status}")));
        }
        Ok(())
    }
}
