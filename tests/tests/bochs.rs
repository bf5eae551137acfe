//! The image under a second, independent emulator: Bochs 2.7 with its own
//! BIOS, its own VGA BIOS and its own Cirrus card. The kernel must answer
//! READY (COM1 found and set up although Bochs's port reads cost a few
//! nanoseconds of its virtual time), put the card in mode 13h with every
//! register and DAC entry reading back as written, and draw what the host
//! asks exactly as the host renders it. Bochs does not say what it is (no
//! hypervisor bit, no subsystem IDs on its host bridge), so the kernel
//! takes it for an unknown machine and refuses `EXIT` and `FAULT`, as on
//! a PC, with nothing touched; and Bochs must listen on no TCP port while
//! it does (its VNC display, which took 5900-5949 on every interface with
//! no password, is not used).
//!
//! What the pictures prove here, and no more: the harness reads no
//! screendump from Bochs, so every picture and palette is what the kernel
//! reads back from Bochs's video memory and DAC (a `DUMP`), judged against
//! the host render and the palette the kernel loaded. That the card puts
//! them on its screen is not seen; QEMU's screendump shows that for
//! QEMU's cards (`adapters.rs`).

use anyhow::{bail, ensure, Context, Result};
use harness::bochs::Bochs;
use harness::checks::{dump_matches_host_render, show_matches_host_render};
use harness::Reply;
use protocol::{Command, ErrorReply, FaultKind, Firmware, Machine, PciId, Video, EXIT_SUCCESS};
use scenes::builtin;

#[test]
fn bochs_boots_the_image_and_reads_back_from_its_card_what_the_host_renders() -> Result<()> {
    let mut bochs = Bochs::boot()?;
    let ready = bochs.ready;
    eprintln!("harness: bochs: {ready}");
    ensure!(ready.firmware == Firmware::Bios, "Bochs: READY names the firmware {:?}", ready.firmware);
    let cirrus = Some(PciId { vendor: 0x1013, device: 0x00b8 });
    ensure!(ready.display == cirrus, "Bochs: READY names the display {:?}, not Bochs's Cirrus", ready.display);
    ensure!(ready.video == (Video::Vga13h { mismatches: 0 }), "Bochs: READY names the video path {:?}", ready.video);
    ensure!(ready.losses.none(), "Bochs: READY says the serial line lost bytes: {}", ready.losses);
    for log in bochs.console.logs() {
        eprintln!("harness: bochs: LOG {log}");
    }
    ensure!(ready.machine == Some(Machine::Unknown), "Bochs: READY names the machine {:?}", ready.machine);
    for command in [Command::Exit(EXIT_SUCCESS), Command::Fault(FaultKind::DivideError)] {
        match bochs.console.request(&command)? {
            Reply::Err(text) if ErrorReply::parse(&text)? == ErrorReply::NotQemu(command.name()) => {}
            other => bail!("Bochs: `{command}` answered {other:?}, expected ERR"),
        }
    }
    bochs.console.ok(&Command::VgaCheck)?;
    for page in [builtin::ABRASH38_1, builtin::ABRASH40_2] {
        dump_matches_host_render(&mut bochs.console, page.name, page.method)?;
    }
    show_matches_host_render(&mut bochs.console, "lamothe-rotate", 0, None)?;
    let losses = bochs.console.ping()?;
    ensure!(losses.none(), "Bochs: PING says the serial line lost bytes: {losses}");
    let pid = bochs.pid();
    let ports = listening_tcp_ports(pid)?;
    ensure!(ports.is_empty(), "Bochs (process {pid}) listens on TCP ports {ports:?}");
    Ok(())
}

/// The TCP ports process `pid` listens on (IPv4 and IPv6): its sockets
/// (`/proc/PID/fd` links `socket:[INODE]`) that `/proc/net/tcp` and
/// `tcp6` list in state LISTEN (0A).
fn listening_tcp_ports(pid: u32) -> Result<Vec<u16>> {
    let mut sockets = Vec::new();
    for entry in std::fs::read_dir(format!("/proc/{pid}/fd")).with_context(|| format!("process {pid}'s files"))? {
        let target = std::fs::read_link(entry?.path()).unwrap_or_default();
        let inode = target.to_str().and_then(|t| t.strip_prefix("socket:[")?.strip_suffix(']').map(str::to_string));
        sockets.extend(inode);
    }
    ensure!(!sockets.is_empty(), "process {pid} has no socket at all, not even COM1's connection");
    let mut ports = Vec::new();
    for table in ["/proc/net/tcp", "/proc/net/tcp6"] {
        for line in std::fs::read_to_string(table).with_context(|| format!("reading {table}"))?.lines().skip(1) {
            // `sl local_address rem_address st ... uid timeout inode ...`
            let fields: Vec<&str> = line.split_whitespace().collect();
            if fields.len() > 9 && fields[3] == "0A" && sockets.iter().any(|inode| inode == fields[9]) {
                let port = fields[1].rsplit(':').next().unwrap_or_default();
                ports.push(u16::from_str_radix(port, 16).with_context(|| format!("{table}: `{line}`"))?);
            }
        }
    }
    Ok(ports)
}
