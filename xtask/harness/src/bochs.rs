//! Running the image in Bochs 2.7, a second emulator independent of QEMU,
//! with its own BIOS, its own VGA BIOS and its own Cirrus card: the same
//! image, and the same protocol on COM1, which Bochs connects to a TCP
//! socket of ours. Bochs has no screendump the harness could read, so it
//! judges the kernel by its answers: READY, the dumps against the host
//! render, the register read-back.
//!
//! Debian's Bochs has its debugger built in, which stops before the first
//! instruction: the run starts it with `c` (continue) on its standard
//! input. Its display is the terminal one (`term`, Debian's bochs-term):
//! with the debugger built in, Bochs opens a new pseudo-terminal for it
//! that nothing reads, so the screen goes nowhere. Debian's build has no
//! `nogui` library, and its VNC one (`rfb`) listens on every interface
//! (ports 5900-5949) with no password: anyone on the network could watch
//! and type into the machine for as long as a test ran.

use std::fs::File;
use std::net::{TcpListener, TcpStream};
use std::path::Path;
use std::process::{ChildStdin, Command, Stdio};
use std::time::{Duration, Instant};

use anyhow::{bail, Context, Result};
use boot_image::build_image;
use install::command_line;
use install::system_file;
use protocol::Ready;

use crate::client::{forward_bytes, Console, FrameReader};
use crate::supervisor::Supervised;
use install::{ensure_bochs, BOCHS, BOCHS_BIOS, BOCHS_BIOS_ENV, BOCHS_CIRRUS_VGA_BIOS, BOCHS_CIRRUS_VGA_BIOS_ENV};

/// Longest wait for Bochs to connect COM1 to the harness.
const CONNECT_TIMEOUT: Duration = Duration::from_secs(30);

/// Bochs's configuration for booting `image` with COM1 connected to
/// 127.0.0.1:`port`, each line saying why.
pub fn bochsrc(image: &Path, port: u16) -> String {
    let image = image.display();
    let bios = system_file(BOCHS_BIOS_ENV, BOCHS_BIOS);
    let vga_bios = system_file(BOCHS_CIRRUS_VGA_BIOS_ENV, BOCHS_CIRRUS_VGA_BIOS);
    let (bios, vga_bios) = (bios.display(), vga_bios.display());
    format!(
        "# Enough for the bootloader and the kernel's heap, as under QEMU.\n\
         megs: 128\n\
         # Bochs's own BIOS and its Cirrus VGA BIOS (Debian's bochsbios and vgabios).\n\
         romimage: file={bios}\n\
         vgaromimage: file={vga_bios}\n\
         # The i440FX PCI chipset with Bochs's Cirrus GD5446 in slot 1.\n\
         pci: enabled=1, chipset=i440fx, slot1=cirrus\n\
         vga: extension=cirrus\n\
         # A 64-bit CPU (the kernel runs in long mode).\n\
         cpu: model=corei7_sandy_bridge_2600k\n\
         # The image as the first hard disk; Bochs writes to it, so it is a copy.\n\
         ata0-master: type=disk, path={image}, mode=flat\n\
         boot: disk\n\
         # COM1 connects to the harness, which listens on this port.\n\
         com1: enabled=1, mode=socket-client, dev=127.0.0.1:{port}\n\
         # No window and no network: the text display, drawn on a pseudo-terminal\n\
         # of Bochs's own that nothing reads.\n\
         display_library: term\n\
         # Bochs's own messages go to the run's log; a panic ends the run.\n\
         log: bochs.log\n\
         panic: action=fatal\n\
         error: action=report\n\
         info: action=ignore\n\
         debug: action=ignore\n"
    )
}

/// A running Bochs. Dropping it kills the process and removes its run
/// folder (its watchdog does both if the harness dies first).
pub struct Bochs {
    process: Supervised,
    /// Kept open: Bochs's debugger reads it, and ends the run at its end.
    _stdin: ChildStdin,
    /// The protocol session on COM1.
    pub console: Console,
    /// What the kernel's READY frame said.
    pub ready: Ready,
}

impl Bochs {
    /// Builds (or reuses) the image, starts Bochs on a copy of it and waits
    /// for the kernel's READY frame. On any failure the run's Bochs is
    /// killed and reaped and its folder removed.
    pub fn boot() -> Result<Self> {
        ensure_bochs()?;
        let image = build_image()?;
        let mut process = Supervised::with_folder("bochs")?;
        let run_dir = process.folder().to_path_buf();
        let disk = run_dir.join("polylab.img");
        std::fs::copy(&image, &disk)
            .with_context(|| format!("failed to copy {} to {}", image.display(), disk.display()))?;
        let listener = TcpListener::bind("127.0.0.1:0").context("failed to listen for Bochs's COM1")?;
        let port = listener.local_addr()?.port();
        let config = run_dir.join("bochsrc");
        std::fs::write(&config, bochsrc(&disk, port))
            .with_context(|| format!("failed to write {}", config.display()))?;
        let output = File::create(run_dir.join("bochs.out"))?;
        let mut command = Command::new(BOCHS);
        command.arg("-q").arg("-f").arg(&config).current_dir(&run_dir);
        command.stdin(Stdio::piped()).stdout(output.try_clone()?).stderr(output);
        eprintln!("harness: running {}", command_line(&command));
        let mut stdin = process.spawn(&mut command)?.stdin.take().expect("stdin is piped");
        std::io::Write::write_all(&mut stdin, b"c\n").context("failed to start Bochs's CPU (its debugger's `c`)")?;
        let com1 = accept_within(&listener, CONNECT_TIMEOUT).map_err(|error| error.context(last_words(&run_dir)))?;
        let console = Console::new(com1.try_clone()?, FrameReader::new(forward_bytes(com1)));
        let mut bochs = Self { process, _stdin: stdin, console, ready: Ready::default() };
        bochs.ready = bochs.console.wait_ready().map_err(|error| error.context(last_words(&run_dir)))?;
        Ok(bochs)
    }

    /// Bochs's process id (its process group's too).
    pub fn pid(&self) -> u32 {
        self.process.pid()
    }
}

/// The connection Bochs makes to `listener`, within `timeout`.
fn accept_within(listener: &TcpListener, timeout: Duration) -> Result<TcpStream> {
    listener.set_nonblocking(true)?;
    let deadline = Instant::now() + timeout;
    loop {
        match listener.accept() {
            Ok((stream, _)) => {
                stream.set_nonblocking(false)?;
                return Ok(stream);
            }
            Err(error) if error.kind() == std::io::ErrorKind::WouldBlock => {
                if Instant::now() >= deadline {
                    bail!("Bochs did not connect COM1 within {} s", timeout.as_secs());
                }
                std::thread::sleep(Duration::from_millis(20));
            }
            Err(error) => return Err(error).context("failed to accept Bochs's COM1 connection"),
        }
    }
}

/// The end of what Bochs printed, for an error.
fn last_words(run_dir: &Path) -> String {
    let text = std::fs::read_to_string(run_dir.join("bochs.out")).unwrap_or_default();
    let lines: Vec<&str> = text.lines().filter(|line| !line.starts_with("ALSA lib")).collect();
    format!("Bochs's last words:\n{}", lines[lines.len().saturating_sub(12)..].join("\n"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_configuration_boots_the_copy_with_bochs_own_firmware_and_cirrus_card_and_com1_on_the_port() {
        let config = bochsrc(Path::new("/run/polylab.img"), 4321);
        for line in [
            "romimage: file=/usr/share/bochs/BIOS-bochs-latest",
            "vgaromimage: file=/usr/share/vgabios/vgabios-cirrus.bin",
            "pci: enabled=1, chipset=i440fx, slot1=cirrus",
            "vga: extension=cirrus",
            "ata0-master: type=disk, path=/run/polylab.img, mode=flat",
            "com1: enabled=1, mode=socket-client, dev=127.0.0.1:4321",
            "display_library: term",
        ] {
            assert!(config.lines().any(|l| l == line), "`{line}` missing from:\n{config}");
        }
        assert!(!config.contains("rfb"), "a network display in:\n{config}");
    }
}
