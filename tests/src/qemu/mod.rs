//! Running the image in QEMU: the command line (every flag says why), the
//! firmware (SeaBIOS or OVMF) and the display card, the child process
//! (killed on drop, every wait bounded) and its channels: COM1 on the
//! child's stdin/stdout, QMP on a unix socket.

mod board;
pub mod console;
pub mod qmp;
pub mod serial;

use std::ffi::OsString;
use std::net::{TcpListener, TcpStream};
use std::path::{Path, PathBuf};
use std::process::{Command, ExitStatus, Stdio};
use std::sync::mpsc::Receiver;
use std::time::{Duration, Instant};

use anyhow::{anyhow, bail, Context, Result};
use protocol::{Firmware, PciId, Ready};

use crate::picture::Image;
use crate::prerequisites::{
    ensure_ovmf, ensure_qemu, ensure_qemu_qxl, ensure_secure_boot_ovmf, ovmf_code, ovmf_microsoft_vars,
    ovmf_secure_boot_code, ovmf_vars, QEMU,
};
use crate::process::command_line;
use crate::supervisor::Supervised;
use board::AHEAD_ID;
pub use board::{Board, DisplayAhead};
use boot_image::build_image;
use console::Console;
use qmp::{Qmp, QMP_TIMEOUT};
use serial::{forward_bytes, FrameReader};

/// Longest wait for QEMU to exit after QMP `quit`.
pub const QUIT_TIMEOUT: Duration = Duration::from_secs(30);

/// How the image is attached.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Medium {
    /// The first IDE disk, as a PC's hard disk.
    #[default]
    Disk,
    /// A USB stick (usb-storage on an xHCI controller): the rehearsal for
    /// `dd`-ing the image onto a real stick.
    UsbStick,
}

/// Whether a person watches.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Display {
    #[default]
    Headless,
    /// A window on the user's desktop (QEMU's default display backend).
    Window,
}

/// The display card QEMU emulates.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Adapter {
    /// QEMU's standard VGA, with the Bochs "dispi" VBE extension.
    #[default]
    Std,
    /// A Cirrus Logic GD5446: a real card's design, whose extended
    /// registers keep a VBE mode the standard ones cannot undo.
    Cirrus,
    /// The VMware SVGA II adapter.
    Vmware,
    /// QXL (SPICE's card) with its VGA core and the Bochs VBE interface.
    QxlVga,
    /// virtio-gpu with a VGA core and the Bochs VBE interface.
    VirtioVga,
    /// An ATI Rage 128 Pro, a real card's VGA core (no UEFI driver in OVMF).
    AtiVga,
    /// The Bochs display interface without a VGA core (PCI class 03/80,
    /// the std VGA's PCI IDs): only a framebuffer.
    BochsDisplay,
    /// A framebuffer in guest RAM the firmware sets up: no PCI device, no
    /// VGA.
    Ramfb,
    /// virtio-gpu without a VGA core (class 03/80): OVMF's driver for it
    /// offers only a BltOnly mode, no framebuffer the kernel can draw in.
    VirtioGpu,
    /// No display card at all.
    None,
}

impl Adapter {
    /// Every card, in the order `--vga` lists them.
    pub const ALL: [Adapter; 10] = [
        Adapter::Std,
        Adapter::Cirrus,
        Adapter::Vmware,
        Adapter::QxlVga,
        Adapter::VirtioVga,
        Adapter::AtiVga,
        Adapter::BochsDisplay,
        Adapter::Ramfb,
        Adapter::VirtioGpu,
        Adapter::None,
    ];

    /// Whether the adapter matrix proves the picture (or, with `None` and
    /// `VirtioGpu`, the boot) on this card under `firmware`: SeaBIOS's VGA
    /// BIOSes put the VGA-compatible cards in text mode; OVMF has a
    /// graphics driver for the first five and for bochs-display and ramfb
    /// (none for ati-vga), a BltOnly one for virtio-gpu, and with no card
    /// it shows nothing.
    pub fn proven_under(self, firmware: Firmware) -> bool {
        match self {
            Adapter::Std | Adapter::Cirrus | Adapter::Vmware | Adapter::QxlVga | Adapter::VirtioVga => true,
            Adapter::AtiVga | Adapter::None => firmware == Firmware::Bios,
            // virtio-gpu: the boot with no framebuffer (a BltOnly mode).
            Adapter::BochsDisplay | Adapter::Ramfb | Adapter::VirtioGpu => firmware == Firmware::Uefi,
        }
    }

    /// The card's name for `--vga` (QEMU's device name where it has one).
    pub fn name(self) -> &'static str {
        match self {
            Adapter::Std => "std",
            Adapter::Cirrus => "cirrus",
            Adapter::Vmware => "vmware",
            Adapter::QxlVga => "qxl-vga",
            Adapter::VirtioVga => "virtio-vga",
            Adapter::AtiVga => "ati-vga",
            Adapter::BochsDisplay => "bochs-display",
            Adapter::Ramfb => "ramfb",
            Adapter::VirtioGpu => "virtio-gpu",
            Adapter::None => "none",
        }
    }

    /// The card called `name`; otherwise an error listing them.
    pub fn named(name: &str) -> Result<Adapter> {
        Adapter::ALL.into_iter().find(|adapter| adapter.name() == name).with_context(|| {
            let valid: Vec<&str> = Adapter::ALL.iter().map(|adapter| adapter.name()).collect();
            format!("unknown display adapter `{name}`; the adapters are {}", valid.join(", "))
        })
    }

    /// QEMU's flags for the card: `-vga` for the cards it knows by that
    /// flag; otherwise no built-in card and the card as a `-device`.
    fn qemu_flags(self) -> [&'static str; 2] {
        match self {
            Adapter::Std => ["-vga", "std"],
            Adapter::Cirrus => ["-vga", "cirrus"],
            Adapter::Vmware => ["-vga", "vmware"],
            Adapter::QxlVga => ["-vga", "qxl"],
            Adapter::VirtioVga => ["-vga", "virtio"],
            Adapter::AtiVga => ["-device", "ati-vga"],
            Adapter::BochsDisplay => ["-device", "bochs-display"],
            Adapter::Ramfb => ["-device", "ramfb"],
            Adapter::VirtioGpu => ["-device", "virtio-gpu-pci"],
            Adapter::None => ["-vga", "none"],
        }
    }

    /// QEMU's device for the card on the PCI bus, which `-device` can put
    /// at a slot of one's choosing; `None` for ramfb and no card.
    fn pci_device(self) -> Option<&'static str> {
        match self {
            Adapter::Std => Some("VGA"),
            Adapter::Cirrus => Some("cirrus-vga"),
            Adapter::Vmware => Some("vmware-svga"),
            Adapter::QxlVga => Some("qxl-vga"),
            Adapter::VirtioVga => Some("virtio-vga"),
            Adapter::AtiVga => Some("ati-vga"),
            Adapter::BochsDisplay => Some("bochs-display"),
            Adapter::VirtioGpu => Some("virtio-gpu-pci"),
            Adapter::Ramfb | Adapter::None => None,
        }
    }

    /// The PCI IDs QEMU gives the card (as `lspci -n` shows them in a
    /// guest), which the kernel reports in READY; `None` for no card and
    /// for ramfb, which is not on the PCI bus.
    pub fn pci_id(self) -> Option<PciId> {
        let (vendor, device) = match self {
            Adapter::Std | Adapter::BochsDisplay => (0x1234, 0x1111),
            Adapter::Cirrus => (0x1013, 0x00b8),
            Adapter::Vmware => (0x15ad, 0x0405),
            Adapter::QxlVga => (0x1b36, 0x0100),
            Adapter::VirtioVga | Adapter::VirtioGpu => (0x1af4, 0x1050),
            Adapter::AtiVga => (0x1002, 0x5046),
            Adapter::Ramfb | Adapter::None => return None,
        };
        Some(PciId { vendor, device })
    }
}

/// What the guest's clocks (the PIT, rdtsc) follow.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Clock {
    /// The host's time: the demo plays at its real pace, and rdtsc counts
    /// host time spent emulating, which moves with the host's load.
    #[default]
    RealTime,
    /// Executed instructions: the virtual clock, and with it rdtsc, steps
    /// one nanosecond (one tick) per emulated instruction, whatever the
    /// host does, so the kernel's figures repeat exactly from run to run.
    /// For measuring; the demo's pacing then follows instructions too.
    InstructionCount,
}

/// Where COM1, the protocol line, reaches the harness.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum SerialLine {
    /// QEMU's standard input and output, pipes to the harness: [`Qemu::console`].
    #[default]
    Stdio,
    /// A pseudo-terminal QEMU makes ([`Qemu::pty`]): a tty device that a
    /// program opens as it would a real serial port. [`Qemu::console`]
    /// then hears nothing.
    Pty,
    /// A telnet server on TCP port `port` of 127.0.0.1 (0: [`Qemu::spawn`]
    /// picks a free one): the one QEMU backend that carries a break (IAC
    /// BRK, bytes 255 243, which QEMU turns into a break on the UART's
    /// receiving end). A data byte 255 must be sent twice.
    Telnet { port: u16 },
}

/// What QEMU's CPU tells the guest about itself.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Cpu {
    /// QEMU's default CPU, which says a hypervisor runs it (CPUID leaf 1,
    /// ECX bit 31) and names it (`TCGTCGTCGTCG`).
    #[default]
    Default,
    /// The same CPU with CPUID's hypervisor bit clear: from the CPU, a
    /// guest cannot tell it runs under QEMU.
    WithoutHypervisorBit,
}

/// Whether QEMU has its exit device (`isa-debug-exit`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum ExitDevice {
    #[default]
    Present,
    /// None: a kernel's write to its port goes nowhere, as on a PC.
    Absent,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct QemuOptions {
    pub firmware: Firmware,
    pub medium: Medium,
    pub display: Display,
    pub adapter: Adapter,
    pub clock: Clock,
    pub serial: SerialLine,
    /// With `Firmware::Uefi`: OVMF's Secure Boot build on the q35 machine
    /// (it needs SMM), its variable store Microsoft's keys with Secure Boot
    /// on unless the run is given another ([`Qemu::spawn_with_variables`]).
    pub secure_boot: bool,
    /// A guest reboot restarts the machine (MokManager reboots after
    /// enrolling a key) instead of ending QEMU.
    pub allow_reboot: bool,
    /// COM1's IRQ line if not its standard 4: the UART then interrupts on
    /// a line the kernel does not listen to.
    pub com1_irq: Option<u8>,
    pub cpu: Cpu,
    pub exit_device: ExitDevice,
    /// A display controller with no legacy VGA ranges ahead of the card
    /// in bus order, and the card (a PCI one) in slot 5, where
    /// screendumps are taken of it ([`Qemu::screendump_ahead`] takes the
    /// one ahead).
    pub display_ahead: Option<DisplayAhead>,
    pub board: Board,
}

/// The slot `QemuOptions::display_ahead` puts the card in, and the QEMU
/// id screendumps name it by.
const CARD_BEHIND_SLOT: &str = "05.0";
const CARD_BEHIND_ID: &str = "card";

/// Where a run keeps its QMP socket and, under UEFI, its copy of the
/// firmware's variable store.
fn qmp_socket(run_dir: &Path) -> PathBuf {
    run_dir.join("qmp.sock")
}

fn uefi_variables(run_dir: &Path) -> PathBuf {
    run_dir.join("OVMF_VARS_4M.fd")
}

/// QEMU's arguments for booting `image` with `options`, its QMP socket
/// (and the UEFI variable store) in `run_dir`.
pub fn qemu_arguments(image: &Path, run_dir: &Path, options: QemuOptions) -> Vec<OsString> {
    let mut args: Vec<OsString> = Vec::new();
    if options.firmware == Firmware::Uefi && options.secure_boot {
        // Q35 with SMM: OVMF's Secure Boot build keeps its variables
        // behind SMM, where the guest's OS cannot write them directly...
        flag(&mut args, "-machine", "q35,smm=on");
        // ...its flash writable only from SMM...
        flag(&mut args, "-global", "driver=cfi.pflash01,property=secure,value=on");
        // ...and no S3 resume, which that build does not support.
        flag(&mut args, "-global", "ICH9-LPC.disable_s3=1");
        flag(
            &mut args,
            "-drive",
            with_path("if=pflash,format=raw,unit=0,readonly=on,file=", &ovmf_secure_boot_code(), ""),
        );
        flag(&mut args, "-drive", with_path("if=pflash,format=raw,unit=1,file=", &uefi_variables(run_dir), ""));
    } else {
        // The i440FX PC (or Q35). Its own firmware is SeaBIOS: a BIOS that
        // boots the image's BIOS side, like a PC's BIOS or CSM. `pit=off`
        // leaves the 8254 out, as on a legacy-free PC.
        flag(&mut args, "-machine", options.board.machine());
    }
    if options.firmware == Firmware::Uefi && !options.secure_boot {
        // OVMF instead, as a UEFI PC's flash: its code read-only, and its
        // variable store (boot entries it writes as it boots) a copy of
        // the package's empty one, private to this run.
        flag(&mut args, "-drive", with_path("if=pflash,format=raw,unit=0,readonly=on,file=", &ovmf_code(), ""));
        flag(&mut args, "-drive", with_path("if=pflash,format=raw,unit=1,file=", &uefi_variables(run_dir), ""));
    }
    // Always emulate: KVM here is nested and pathologically slow, and TCG
    // exists everywhere QEMU does.
    flag(&mut args, "-accel", "tcg");
    // Plenty for the bootloader and the kernel's heap; small enough to start fast.
    flag(&mut args, "-m", "128M");
    if options.clock == Clock::InstructionCount {
        // `shift=0`: each instruction advances the virtual clock by 2^0 ns,
        // which rdtsc then reads; `sleep=off`: when the guest halts, the
        // clock jumps to the next timer instead of waiting for the host.
        flag(&mut args, "-icount", "shift=0,sleep=off");
    }
    // The display card (`Adapter`). Under SeaBIOS the VGA-compatible ones'
    // VGA BIOS puts them in text mode; under OVMF its graphics driver sets
    // their native mode, which the kernel undoes on the cards it knows.
    let [card_flag, card] = options.adapter.qemu_flags();
    match options.adapter.pci_device().zip(options.display_ahead) {
        Some((device, ahead)) => {
            // A display controller without VGA first in bus order, the
            // card behind it: the kernel must find the VGA by the legacy
            // VGA decoding, not by bus order, and under UEFI the head the
            // firmware used.
            flag(&mut args, "-vga", "none");
            flag(&mut args, "-device", ahead.device());
            flag(&mut args, "-device", format!("{device},addr={CARD_BEHIND_SLOT},id={CARD_BEHIND_ID}"));
        }
        None => {
            flag(&mut args, card_flag, card);
            if card_flag == "-device" {
                // No built-in VGA beside the card given as a device.
                flag(&mut args, "-vga", "none");
            }
        }
    }
    if options.cpu == Cpu::WithoutHypervisorBit {
        // QEMU's default CPU model, its hypervisor bit cleared.
        flag(&mut args, "-cpu", "qemu64,-hypervisor");
    }
    // No network card: nothing boots from the network, and no option ROM
    // of one slows the firmware down.
    flag(&mut args, "-nic", "none");
    match options.display {
        // No window; QMP screendumps still render the card's output.
        Display::Headless => flag(&mut args, "-display", "none"),
        // No `-display`: QEMU picks its best backend for a window (GTK, SDL).
        Display::Window => {}
    }
    // No human monitor: QMP is the control channel and stdio is COM1.
    flag(&mut args, "-monitor", "none");
    match options.serial {
        // COM1 on QEMU's stdin and stdout, both pipes to us: the protocol line.
        SerialLine::Stdio => flag(&mut args, "-serial", "stdio"),
        // COM1 on a pseudo-terminal, found through QMP (`Qemu::pty`).
        SerialLine::Pty => flag(&mut args, "-serial", "pty"),
        SerialLine::Telnet { port } => {
            // COM1 on a telnet server; `wait=on`: the guest starts once
            // the harness has connected, so no frame is lost.
            let server = format!("socket,id=com1,host=127.0.0.1,port={port},server=on,wait=on,telnet=on");
            flag(&mut args, "-chardev", server);
            flag(&mut args, "-serial", "chardev:com1");
        }
    }
    if let Some(irq) = options.com1_irq {
        flag(&mut args, "-global", format!("isa-serial.irq={irq}"));
    }
    // Screendump and quit; `wait=off` lets the guest run with no client yet.
    flag(&mut args, "-qmp", with_path("unix:", &qmp_socket(run_dir), ",server=on,wait=off"));
    if options.exit_device == ExitDevice::Present {
        // `EXIT n` and fault reports leave QEMU with exit status (n << 1) | 1.
        flag(&mut args, "-device", "isa-debug-exit,iobase=0xf4,iosize=0x04");
    }
    if !options.allow_reboot {
        // A triple fault exits QEMU instead of rebooting the guest forever.
        args.push("-no-reboot".into());
    }
    // `snapshot=on` sends writes to a temporary overlay: the image file stays
    // untouched and parallel runs can share it without QEMU's write lock.
    match options.medium {
        Medium::Disk => {
            flag(&mut args, "-drive", with_path("if=ide,index=0,format=raw,snapshot=on,file=", image, ""));
        }
        Medium::UsbStick => {
            // The stick's drive has no bus of its own; usb-storage carries it.
            flag(&mut args, "-drive", with_path("if=none,id=stick,format=raw,snapshot=on,file=", image, ""));
            // A USB 3 controller, as on the PCs the stick is meant for.
            flag(&mut args, "-device", "qemu-xhci,id=xhci");
            // The stick itself; SeaBIOS and OVMF boot from it as from a disk.
            flag(&mut args, "-device", "usb-storage,bus=xhci.0,drive=stick");
        }
    }
    args
}

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

fn flag(args: &mut Vec<OsString>, flag: &str, value: impl Into<OsString>) {
    args.push(flag.into());
    args.push(value.into());
}

/// `prefix`, `path` and `suffix` as one argument (paths need not be UTF-8).
fn with_path(prefix: &str, path: &Path, suffix: &str) -> OsString {
    let mut arg = OsString::from(prefix);
    arg.push(path);
    arg.push(suffix);
    arg
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
        let variables = if options.secure_boot {
            ensure_secure_boot_ovmf()?;
            ovmf_microsoft_vars()
        } else {
            ovmf_vars()
        };
        Self::spawn_with_variables(image, options, &variables)
    }

    /// [`Qemu::spawn`] under UEFI with a copy of `variables` as the
    /// firmware's variable store (the Secure Boot tests' MOK lists).
    pub fn spawn_with_variables(image: &Path, options: QemuOptions, variables: &Path) -> Result<Self> {
        ensure_qemu()?;
        if options.adapter == Adapter::QxlVga {
            ensure_qemu_qxl()?;
        }
        let options = match options.serial {
            SerialLine::Telnet { port: 0 } => {
                QemuOptions { serial: SerialLine::Telnet { port: free_port()? }, ..options }
            }
            _ => options,
        };
        if options.firmware == Firmware::Uefi {
            ensure_ovmf()?;
            if options.secure_boot {
                ensure_secure_boot_ovmf()?;
            }
        }
        let mut process = Supervised::with_folder("qemu")?;
        let run_dir = process.folder().to_path_buf();
        if options.firmware == Firmware::Uefi {
            std::fs::copy(variables, uefi_variables(&run_dir))
                .with_context(|| format!("failed to copy {} into {}", variables.display(), run_dir.display()))?;
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
        quit.map_err(|error| self.explain(error))?;
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

#[cfg(test)]
mod tests {
    use super::*;

    fn arguments(options: QemuOptions) -> Vec<String> {
        qemu_arguments(Path::new("/img/polylab.img"), Path::new("/run"), options)
            .into_iter()
            .map(|a| a.into_string().unwrap())
            .collect()
    }

    fn has_pair(args: &[String], flag: &str, value: &str) -> bool {
        args.windows(2).any(|w| w[0] == flag && w[1] == value)
    }

    #[test]
    fn headless_disk_boot_has_every_required_flag() {
        let args = arguments(QemuOptions::default());
        for (flag, value) in [
            ("-accel", "tcg"),
            ("-display", "none"),
            ("-serial", "stdio"),
            ("-qmp", "unix:/run/qmp.sock,server=on,wait=off"),
            ("-device", "isa-debug-exit,iobase=0xf4,iosize=0x04"),
            ("-m", "128M"),
            ("-nic", "none"),
            ("-drive", "if=ide,index=0,format=raw,snapshot=on,file=/img/polylab.img"),
        ] {
            assert!(has_pair(&args, flag, value), "{flag} {value} missing from {args:?}");
        }
        assert!(args.contains(&"-no-reboot".to_string()));
        assert!(!args.iter().any(|a| a.contains("usb")));
        assert!(!args.iter().any(|a| a.contains("pflash")), "SeaBIOS is the default firmware: {args:?}");
    }

    #[test]
    fn uefi_boots_ovmf_from_read_only_code_and_a_private_variable_store() {
        let args = arguments(QemuOptions { firmware: Firmware::Uefi, ..QemuOptions::default() });
        let code = format!("if=pflash,format=raw,unit=0,readonly=on,file={}", ovmf_code().display());
        assert!(has_pair(&args, "-drive", &code), "{args:?}");
        assert!(has_pair(&args, "-drive", "if=pflash,format=raw,unit=1,file=/run/OVMF_VARS_4M.fd"), "{args:?}");
        assert!(has_pair(&args, "-drive", "if=ide,index=0,format=raw,snapshot=on,file=/img/polylab.img"));
    }

    #[test]
    fn secure_boot_is_ovmfs_secure_build_on_q35_with_smm_and_its_flash_secured() {
        let args = arguments(QemuOptions { firmware: Firmware::Uefi, secure_boot: true, ..QemuOptions::default() });
        let code = format!("if=pflash,format=raw,unit=0,readonly=on,file={}", ovmf_secure_boot_code().display());
        assert!(has_pair(&args, "-drive", &code), "{args:?}");
        assert!(has_pair(&args, "-drive", "if=pflash,format=raw,unit=1,file=/run/OVMF_VARS_4M.fd"), "{args:?}");
        assert!(has_pair(&args, "-machine", "q35,smm=on"), "{args:?}");
        assert!(has_pair(&args, "-global", "driver=cfi.pflash01,property=secure,value=on"), "{args:?}");
        assert!(has_pair(&args, "-global", "ICH9-LPC.disable_s3=1"), "{args:?}");
        assert_eq!(args.iter().filter(|a| *a == "-machine").count(), 1, "{args:?}");
        assert_eq!(args.iter().filter(|a| a.starts_with("if=pflash")).count(), 2, "{args:?}");
        assert!(args.contains(&"-no-reboot".to_string()));
    }

    #[test]
    fn a_reboot_restarts_the_machine_only_when_allowed() {
        let args = arguments(QemuOptions { allow_reboot: true, ..QemuOptions::default() });
        assert!(!args.contains(&"-no-reboot".to_string()), "{args:?}");
    }

    #[test]
    fn usb_stick_boot_puts_the_image_on_xhci_usb_storage() {
        let args = arguments(QemuOptions { medium: Medium::UsbStick, ..QemuOptions::default() });
        assert!(has_pair(&args, "-drive", "if=none,id=stick,format=raw,snapshot=on,file=/img/polylab.img"));
        assert!(has_pair(&args, "-device", "qemu-xhci,id=xhci"));
        assert!(has_pair(&args, "-device", "usb-storage,bus=xhci.0,drive=stick"));
        assert!(!args.iter().any(|a| a.starts_with("if=ide")));
    }

    #[test]
    fn each_card_is_one_vga_flag_or_a_device_with_no_built_in_vga() {
        assert!(has_pair(&arguments(QemuOptions::default()), "-vga", "std"));
        for (adapter, flag, value) in [
            (Adapter::Cirrus, "-vga", "cirrus"),
            (Adapter::Vmware, "-vga", "vmware"),
            (Adapter::QxlVga, "-vga", "qxl"),
            (Adapter::VirtioVga, "-vga", "virtio"),
            (Adapter::AtiVga, "-device", "ati-vga"),
            (Adapter::BochsDisplay, "-device", "bochs-display"),
            (Adapter::Ramfb, "-device", "ramfb"),
            (Adapter::VirtioGpu, "-device", "virtio-gpu-pci"),
            (Adapter::None, "-vga", "none"),
        ] {
            let args = arguments(QemuOptions { adapter, ..QemuOptions::default() });
            assert!(has_pair(&args, flag, value), "{adapter:?}: {args:?}");
            assert_eq!(args.iter().filter(|a| *a == "-vga").count(), 1, "{args:?}");
            if flag == "-device" {
                assert!(has_pair(&args, "-vga", "none"), "{args:?}");
            }
        }
    }

    #[test]
    fn cards_are_found_by_name_and_others_refused_with_the_list() {
        for adapter in Adapter::ALL {
            assert_eq!(Adapter::named(adapter.name()).unwrap(), adapter);
        }
        for name in ["qxl", "virtio", ""] {
            let error = Adapter::named(name).unwrap_err().to_string();
            assert_eq!(
                error,
                format!(
                    "unknown display adapter `{name}`; the adapters are std, cirrus, vmware, qxl-vga, virtio-vga, \
                     ati-vga, bochs-display, ramfb, virtio-gpu, none"
                )
            );
        }
    }

    #[test]
    fn the_matrix_covers_every_card_under_one_firmware_or_the_other() {
        for adapter in Adapter::ALL {
            let proven = Firmware::ALL.into_iter().any(|firmware| adapter.proven_under(firmware));
            assert!(proven, "{adapter:?} is proven under no firmware");
        }
    }

    #[test]
    fn com1_goes_to_stdio_or_to_a_pty() {
        assert!(has_pair(&arguments(QemuOptions::default()), "-serial", "stdio"));
        let args = arguments(QemuOptions { serial: SerialLine::Pty, ..QemuOptions::default() });
        assert!(has_pair(&args, "-serial", "pty"), "{args:?}");
        assert_eq!(args.iter().filter(|a| *a == "-serial").count(), 1, "{args:?}");
    }

    #[test]
    fn only_instruction_counting_adds_icount() {
        assert!(!arguments(QemuOptions::default()).iter().any(|a| a == "-icount"));
        let args = arguments(QemuOptions { clock: Clock::InstructionCount, ..QemuOptions::default() });
        assert!(has_pair(&args, "-icount", "shift=0,sleep=off"), "{args:?}");
    }

    #[test]
    fn a_telnet_com1_waits_for_the_harness_and_carries_breaks() {
        let args = arguments(QemuOptions { serial: SerialLine::Telnet { port: 4555 }, ..QemuOptions::default() });
        let server = "socket,id=com1,host=127.0.0.1,port=4555,server=on,wait=on,telnet=on";
        assert!(has_pair(&args, "-chardev", server), "{args:?}");
        assert!(has_pair(&args, "-serial", "chardev:com1"), "{args:?}");
        assert!(!has_pair(&args, "-serial", "stdio"), "{args:?}");
    }

    #[test]
    fn com1_irq_cpu_and_exit_device_options_change_only_their_flags() {
        let default = arguments(QemuOptions::default());
        assert!(!default.iter().any(|a| a == "-cpu" || a == "-global"), "{default:?}");
        let moved = arguments(QemuOptions { com1_irq: Some(3), ..QemuOptions::default() });
        assert!(has_pair(&moved, "-global", "isa-serial.irq=3"), "{moved:?}");
        let disguised = arguments(QemuOptions { cpu: Cpu::WithoutHypervisorBit, ..QemuOptions::default() });
        assert!(has_pair(&disguised, "-cpu", "qemu64,-hypervisor"), "{disguised:?}");
        let bare = arguments(QemuOptions { exit_device: ExitDevice::Absent, ..QemuOptions::default() });
        assert!(!bare.iter().any(|a| a.contains("isa-debug-exit")), "{bare:?}");
        // One flag and its value more, or less; nothing else moves.
        assert_eq!(
            [moved.len(), disguised.len(), bare.len()],
            [default.len() + 2, default.len() + 2, default.len() - 2]
        );
    }

    #[test]
    fn a_display_ahead_puts_bochs_display_in_slot_2_or_secondary_vga_in_slot_4_and_the_card_in_slot_5() {
        for (ahead, expected) in [
            (DisplayAhead::BochsDisplay, "bochs-display,addr=02.0,id=ahead"),
            (DisplayAhead::SecondaryVga, "secondary-vga,addr=04.0,id=ahead"),
        ] {
            let options =
                QemuOptions { adapter: Adapter::Cirrus, display_ahead: Some(ahead), ..QemuOptions::default() };
            let args = arguments(options);
            assert!(has_pair(&args, "-vga", "none"), "{args:?}");
            let devices: Vec<&String> = args.windows(2).filter(|w| w[0] == "-device").map(|w| &w[1]).collect();
            assert_eq!(devices[..2], [expected, "cirrus-vga,addr=05.0,id=card"], "{args:?}");
        }
        let options = QemuOptions {
            adapter: Adapter::Ramfb,
            display_ahead: Some(DisplayAhead::BochsDisplay),
            ..QemuOptions::default()
        };
        let ramfb = arguments(options);
        assert!(has_pair(&ramfb, "-device", "ramfb") && !ramfb.iter().any(|a| a.contains("bochs-display")));
    }

    #[test]
    fn a_board_without_a_pit_is_pc_or_q35_with_pit_off() {
        assert!(has_pair(&arguments(QemuOptions::default()), "-machine", "pc"));
        for (board, machine) in [(Board::PcWithoutPit, "pc,pit=off"), (Board::Q35WithoutPit, "q35,pit=off")] {
            for firmware in Firmware::ALL {
                let args = arguments(QemuOptions { board, firmware, ..QemuOptions::default() });
                assert!(has_pair(&args, "-machine", machine), "{args:?}");
                assert_eq!(args.iter().filter(|a| *a == "-machine").count(), 1, "{args:?}");
            }
        }
    }

    #[test]
    fn a_window_drops_only_the_display_flag() {
        let headless = arguments(QemuOptions::default());
        let window = arguments(QemuOptions { display: Display::Window, ..QemuOptions::default() });
        let mut expected = headless.clone();
        let display = headless.iter().position(|a| a == "-display").unwrap();
        expected.drain(display..display + 2);
        assert_eq!(window, expected);
    }
}
