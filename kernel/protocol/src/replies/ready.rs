//! Kernel to host: the `READY` frame's text, what it names (the firmware,
//! the machine, the display controller, the video path and its memory
//! type) and how each is written, by `Display`, and read back, by
//! `parse`.

use core::fmt;

use super::fields::{Expected, Fields, Malformed};
use super::pong::LineLosses;

/// A PCI function's vendor and device IDs, written `vvvv:dddd` in hex as
/// `lspci -n` does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PciId {
    pub vendor: u16,
    pub device: u16,
}

impl fmt::Display for PciId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:04x}:{:04x}", self.vendor, self.device)
    }
}

impl PciId {
    pub(crate) fn parse(text: &str) -> Option<Self> {
        let (vendor, device) = text.split_once(':')?;
        Some(Self { vendor: hex(vendor, 4)?, device: hex(device, 4)? })
    }
}

/// `text` as a number of exactly `digits` hex digits.
fn hex<T: TryFrom<u32>>(text: &str, digits: usize) -> Option<T> {
    let valid = text.len() == digits && text.bytes().all(|b| b.is_ascii_hexdigit());
    valid.then(|| u32::from_str_radix(text, 16).ok()?.try_into().ok()).flatten()
}

/// Where a PCI function sits: bus, device (0-31), function (0-7), written
/// `bb:dd.f` in hex as `lspci` does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PciAddress {
    pub bus: u8,
    pub device: u8,
    pub function: u8,
}

impl fmt::Display for PciAddress {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:02x}:{:02x}.{:x}", self.bus, self.device, self.function)
    }
}

impl PciAddress {
    pub(crate) fn parse(text: &str) -> Option<Self> {
        let (bus, rest) = text.split_once(':')?;
        let (device, function) = rest.split_once('.')?;
        let address = Self { bus: hex(bus, 2)?, device: hex(device, 2)?, function: hex(function, 1)? };
        (address.device < 32 && address.function < 8).then_some(address)
    }
}

/// The machine the kernel found itself on, as far as it can tell without
/// touching a port it has not identified (`kernel/src/platform/machine.rs`). Only on
/// QEMU does the kernel answer `EXIT` and `FAULT`, and write QEMU's exit
/// port after a fatal error.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Machine {
    /// QEMU: its CPUID hypervisor signature and its PCI subsystem IDs.
    Qemu,
    /// Anything else: a PC, or an emulator that does not say what it is.
    #[default]
    Unknown,
}

impl Machine {
    pub const ALL: [Machine; 2] = [Machine::Qemu, Machine::Unknown];

    /// `qemu` or `unknown`, as `READY` writes it.
    pub fn name(self) -> &'static str {
        match self {
            Machine::Qemu => "qemu",
            Machine::Unknown => "unknown",
        }
    }

    /// The machine [`Machine::name`] calls `name`.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|machine| machine.name() == name)
    }
}

/// The firmware that booted the kernel.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Firmware {
    /// A PC BIOS, or a UEFI firmware's compatibility support module (CSM).
    #[default]
    Bios,
    Uefi,
}

impl Firmware {
    pub const ALL: [Firmware; 2] = [Firmware::Bios, Firmware::Uefi];

    /// `bios` or `uefi`, as `READY` writes it.
    pub fn name(self) -> &'static str {
        match self {
            Firmware::Bios => "bios",
            Firmware::Uefi => "uefi",
        }
    }

    /// The firmware [`Firmware::name`] calls `name`.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|firmware| firmware.name() == name)
    }
}

/// How the 320x200 frame reaches the screen.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Video {
    /// The card in mode 13h by the kernel's own register writes; the frame
    /// is video memory at 0xA0000. `mismatches`: the registers and DAC
    /// entries that did not read back as written (each also went out in a
    /// `LOG` frame before `READY`).
    Vga13h { mismatches: usize },
    /// The frame is memory of the kernel's, presented in the firmware's
    /// framebuffer.
    Framebuffer(Presentation),
    /// Nothing shows the frame (no VGA, no framebuffer): the kernel draws
    /// and answers all the same.
    #[default]
    None,
}

/// Where the framebuffer path puts the frame: a `width` x `height`
/// framebuffer, each frame pixel a `scale` x `scale` block, the frame's
/// top left corner at pixel (`left`, `top`), black around it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Presentation {
    pub width: u32,
    pub height: u32,
    pub scale: u32,
    pub left: u32,
    pub top: u32,
}

/// The payload of the `READY` frame the kernel sends once at boot:
/// `firmware=bios|uefi machine=qemu|unknown display=vvvv:dddd
/// display_at=bb:dd.f VIDEO memory=M LOSSES`, where VIDEO is `video=vga13h
/// vga_mismatches=K`, `video=framebuffer screen=WxH scale=S offset=X,Y` or
/// `video=none` ([`Video`]), M the [`MemoryType`] the output is written
/// with (no `memory=` with `video=none`) and LOSSES the [`LineLosses`].
/// `display` is the display controller the kernel uses: on the
/// framebuffer path the one whose memory holds the framebuffer, where the
/// kernel finds it; else the one that decodes the legacy VGA addresses if
/// any does, else the first in bus order (`display=none`, and no
/// `display_at`, if there is none).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct Ready {
    pub firmware: Firmware,
    /// `None` in what a kernel older than the field says.
    pub machine: Option<Machine>,
    pub display: Option<PciId>,
    /// Where `display` sits; `None` with no display, or from an older
    /// kernel.
    pub display_at: Option<PciAddress>,
    pub video: Video,
    /// The memory type the live output is written with (`memory=`,
    /// after the video path); `None` with no output, or from an older
    /// kernel.
    pub memory: Option<MemoryType>,
    pub losses: LineLosses,
}

impl fmt::Display for Ready {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "firmware={} ", self.firmware.name())?;
        if let Some(machine) = self.machine {
            write!(f, "machine={} ", machine.name())?;
        }
        match self.display {
            Some(id) => write!(f, "display={id}")?,
            None => write!(f, "display=none")?,
        }
        if let Some(address) = self.display_at {
            write!(f, " display_at={address}")?;
        }
        match self.video {
            Video::Vga13h { mismatches } => write!(f, " video=vga13h vga_mismatches={mismatches}")?,
            Video::Framebuffer(Presentation { width, height, scale, left, top }) => {
                write!(f, " video=framebuffer screen={width}x{height} scale={scale} offset={left},{top}")?
            }
            Video::None => write!(f, " video=none")?,
        }
        if let Some(memory) = self.memory {
            write!(f, " memory={}", memory.name())?;
        }
        write!(f, " {}", self.losses)
    }
}

impl Ready {
    /// Parses the text written by `Display` (an older kernel's has no
    /// `machine`, `display_at` or `memory`).
    pub fn parse(text: &str) -> Result<Self, Malformed> {
        let mut fields = Fields::new("READY", text);
        let firmware = fields.read("firmware", Firmware::from_name)?;
        let machine = match fields.next_is("machine") {
            true => Some(fields.read("machine", Machine::from_name)?),
            false => None,
        };
        let display = fields.read("display", |id| match id {
            "none" => Some(None),
            id => PciId::parse(id).map(Some),
        })?;
        let display_at = match fields.next_is("display_at") {
            true => Some(fields.read("display_at", PciAddress::parse)?),
            false => None,
        };
        let video = match fields.text("video")? {
            "vga13h" => Video::Vga13h { mismatches: fields.parsed("vga_mismatches")? },
            "framebuffer" => {
                let number = |text: &str| text.parse().ok();
                let (width, height) = fields.read("screen", |screen| {
                    screen.split_once('x').and_then(|(w, h)| Some((number(w)?, number(h)?)))
                })?;
                let scale = fields.parsed("scale")?;
                let (left, top) = fields.read("offset", |offset| {
                    offset.split_once(',').and_then(|(x, y)| Some((number(x)?, number(y)?)))
                })?;
                Video::Framebuffer(Presentation { width, height, scale, left, top })
            }
            "none" => Video::None,
            _ => return Err(fields.malformed(Expected::Value("video"))),
        };
        let memory = match fields.next_is("memory") {
            true => Some(fields.read("memory", MemoryType::from_name)?),
            false => None,
        };
        let losses = LineLosses::read(&mut fields)?;
        fields.end()?;
        Ok(Self { firmware, machine, display, display_at, video, memory, losses })
    }
}

/// The memory type the CPU writes the live output with, as the kernel's
/// page tables and the PAT give it (`kernel/src/platform/pat.rs`): `memory=uc`,
/// `wc`, `wt`, `wp`, `wb` or `uc-` in `READY`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MemoryType {
    Uncacheable,
    WriteCombining,
    WriteThrough,
    WriteProtected,
    WriteBack,
    /// UC-: uncacheable, unless an MTRR says write-combining.
    UncachedMinus,
}

impl MemoryType {
    pub const ALL: [MemoryType; 6] = [
        MemoryType::Uncacheable,
        MemoryType::WriteCombining,
        MemoryType::WriteThrough,
        MemoryType::WriteProtected,
        MemoryType::WriteBack,
        MemoryType::UncachedMinus,
    ];

    /// The short name `READY` writes.
    pub fn name(self) -> &'static str {
        match self {
            MemoryType::Uncacheable => "uc",
            MemoryType::WriteCombining => "wc",
            MemoryType::WriteThrough => "wt",
            MemoryType::WriteProtected => "wp",
            MemoryType::WriteBack => "wb",
            MemoryType::UncachedMinus => "uc-",
        }
    }

    /// The name for people, as `VGACHECK` writes it: `write-combining (WC)`.
    pub fn description(self) -> &'static str {
        match self {
            MemoryType::Uncacheable => "uncacheable (UC)",
            MemoryType::WriteCombining => "write-combining (WC)",
            MemoryType::WriteThrough => "write-through (WT)",
            MemoryType::WriteProtected => "write-protected (WP)",
            MemoryType::WriteBack => "write-back (WB)",
            MemoryType::UncachedMinus => "uncacheable minus (UC-)",
        }
    }

    fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|memory| memory.name() == name)
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use crate::LineErrors;
    use std::string::ToString;

    #[test]
    fn readies_round_trip_and_reject_garbage() {
        let errors = Some(LineErrors { framing: 4, parity: 0, breaks: 1 });
        let losses = LineLosses { overruns: 2, dropped: 0, errors };
        let display = Some(PciId { vendor: 0x1013, device: 0x00b8 });
        let display_at = Some(PciAddress { bus: 0, device: 0x1f, function: 2 });
        let ready = Ready {
            firmware: Firmware::Bios,
            machine: Some(Machine::Qemu),
            display,
            display_at,
            video: Video::Vga13h { mismatches: 3 },
            memory: Some(MemoryType::Uncacheable),
            losses,
        };
        assert_eq!(
            ready.to_string(),
            "firmware=bios machine=qemu display=1013:00b8 display_at=00:1f.2 video=vga13h vga_mismatches=3 \
             memory=uc overruns=2 dropped=0 framing=4 parity=0 breaks=1"
        );
        let presentation = Presentation { width: 800, height: 600, scale: 2, left: 80, top: 100 };
        let framed = Ready {
            firmware: Firmware::Uefi,
            machine: Some(Machine::Unknown),
            video: Video::Framebuffer(presentation),
            memory: Some(MemoryType::WriteCombining),
            ..ready
        };
        assert_eq!(
            framed.to_string(),
            "firmware=uefi machine=unknown display=1013:00b8 display_at=00:1f.2 video=framebuffer screen=800x600 \
             scale=2 offset=80,100 memory=wc overruns=2 dropped=0 framing=4 parity=0 breaks=1"
        );
        let headless = Ready { display: None, display_at: None, video: Video::None, memory: None, ..ready };
        assert_eq!(
            headless.to_string(),
            "firmware=bios machine=qemu display=none video=none overruns=2 dropped=0 framing=4 parity=0 breaks=1"
        );
        for ready in [ready, framed, headless] {
            assert_eq!(Ready::parse(&ready.to_string()), Ok(ready));
        }
        for garbage in [
            "firmware=bios display=1013:b8 video=vga13h vga_mismatches=3 overruns=2 dropped=0",
            "firmware=bios display=1013:00b8 video=vga13h vga_mismatches=3 overruns=2",
            "firmware=bios display=1013:00b8 video=vga13h vga_mismatches=3 overruns=2 dropped=0 more=1",
            "firmware=coreboot display=1013:00b8 video=none overruns=2 dropped=0",
            "firmware=uefi display=none video=framebuffer screen=800x600 scale=2 overruns=2 dropped=0",
            "firmware=uefi display=none video=framebuffer screen=800 scale=2 offset=80,100 overruns=2 dropped=0",
            "firmware=bios display=none video=vga13h overruns=2 dropped=0",
            "display=1013:00b8 vga_mismatches=3 overruns=2 dropped=0",
            "vga: 0 mismatches",
            "firmware=bios machine=bochs display=none video=none overruns=2 dropped=0",
            "firmware=bios display=1013:00b8 display_at=00:20.0 video=none overruns=2 dropped=0",
            "firmware=bios display=1013:00b8 display_at=0:1.0 video=none overruns=2 dropped=0",
            "firmware=bios display=1013:00b8 display_at=00:01.8 video=none overruns=2 dropped=0",
            "firmware=bios display=none video=none overruns=2 dropped=0 framing=1 parity=0",
            "firmware=bios display=none video=none overruns=2 dropped=0 machine=qemu",
            "firmware=bios display=none video=none memory=ram overruns=2 dropped=0",
            "firmware=bios display=none video=none overruns=2 dropped=0 memory=uc",
        ] {
            assert!(Ready::parse(garbage).is_err(), "{garbage}");
        }
        let malformed = |expected| Err(Malformed { reply: "READY", expected });
        let text = "firmware=coreboot display=none video=none overruns=2 dropped=0";
        assert_eq!(Ready::parse(text), malformed(Expected::Value("firmware")));
        let text = "firmware=bios display=none video=vga13h overruns=2 dropped=0";
        assert_eq!(Ready::parse(text), malformed(Expected::Field("vga_mismatches")));
        let text = "firmware=bios display=none video=none overruns=2 dropped=0 machine=qemu";
        assert_eq!(Ready::parse(text), malformed(Expected::End));
        for memory in MemoryType::ALL {
            assert_eq!(MemoryType::from_name(memory.name()), Some(memory));
        }
    }

    #[test]
    fn an_older_kernels_ready_still_parses_without_the_newer_fields() {
        let ready = Ready::parse("firmware=bios display=1234:1111 video=vga13h vga_mismatches=0 overruns=0 dropped=0");
        let expected = Ready {
            firmware: Firmware::Bios,
            machine: None,
            display: Some(PciId { vendor: 0x1234, device: 0x1111 }),
            display_at: None,
            video: Video::Vga13h { mismatches: 0 },
            memory: None,
            losses: LineLosses { overruns: 0, dropped: 0, errors: None },
        };
        assert_eq!(ready, Ok(expected));
    }
}
