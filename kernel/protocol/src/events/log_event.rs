//! The `LOG` frames: what the kernel tells unasked, at boot (the machine
//! and the signs it knew it by, an interrupt that did not arrive, what the
//! screen found on its way) and later (a line dropped, an NMI, a stray
//! interrupt, a storm stopped).

use core::fmt;

use firmware_tables::Misplaced;

use crate::replies::{Expected, Machine, Malformed, Mismatch, PciAddress, PciId, Prose};

/// One `LOG` frame's text.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LogEvent {
    /// At boot, the machine and the signs it was identified by:
    /// `machine: qemu (CPUID hypervisor "TCGTCGTCGTCG", host bridge
    /// subsystem 1af4:1100)`.
    Machine(MachineEvidence),
    /// At boot, COM1's IRQ 4 did not arrive: the kernel receives by
    /// polling alone.
    Com1Polling,
    /// At boot, the PIT's IRQ 0 did not arrive: the server never halts.
    NoTimerTick,
    /// Under UEFI, the firmware's framebuffer is not in the memory of the
    /// VGA at `vga_at`: the frame goes to the framebuffer.
    FramebufferBesideTheVga { vga_at: PciAddress },
    /// Under UEFI, the loader handed over no framebuffer.
    NoFramebuffer,
    /// At boot, a VGA register or DAC entry that did not read back as
    /// written.
    VgaMismatch(Mismatch),
    /// A command line left unfinished (or, `overlong`, thrown away up to
    /// its end) for `idle_seconds` with no byte arriving, dropped with the
    /// `kept` bytes received of it.
    LineDropped { overlong: bool, kept: usize, idle_seconds: u64 },
    /// The `count`th NMI since boot, and port 0x61 as its handler read it
    /// (`reason`), with what the kernel made of its bits 7 and 6.
    Nmi { count: u32, reason: u8, serr: bool, iochk: bool },
    /// Interrupts on `vector`, which the kernel does not use: `count`
    /// since boot, and where the last one was ended.
    StrayInterrupt { vector: u8, count: u32, ended: EndedAt },
    /// Interrupts on `vector` came `count` times within `window_ms`: a
    /// source that fires again after every end of interrupt (a
    /// level-triggered line left high), stopped where `masked` says.
    InterruptStorm { vector: u8, count: u32, window_ms: u32, masked: MaskedAt },
    /// At boot, the HPET the ACPI tables place at `address` was not used,
    /// for `why`: nothing of it was mapped or written where the address
    /// itself was wrong.
    HpetRefused { address: u64, why: HpetRefusal },
    /// At boot, an I/O APIC an ACPI MADT places at `address` was not used,
    /// for `why`: nothing of it was mapped or written where the address
    /// itself was wrong, nothing written where nothing answered.
    IoApicRefused { address: u64, why: IoApicRefusal },
    /// At boot, the PM timer the FADT places at `port` was not used: the
    /// port is one of a PC's fixed devices' (a serial port's, the VGA's,
    /// ...), which the clock's reads would disturb; nothing was read there.
    PmTimerRefused { port: u16 },
}

/// Why the kernel did not use an I/O APIC a MADT names.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum IoApicRefusal {
    /// The address is not on a 16-byte boundary, as the I/O APIC's
    /// registers (IOREGSEL at 0x00, IOWIN at 0x10) are.
    Misaligned,
    /// The registers would lie in RAM of any kind the memory map names
    /// (usable, the loader's, ACPI tables, runtime services', ...).
    InRam,
    /// IOREGSEL, read before anything is written, read all ones: nothing
    /// answers there.
    NothingThere,
    /// The version register (index 1) read `version`, whose version (bits
    /// 0-7) is 0 or 0xFF: no I/O APIC answers there (QEMU reads 0 where
    /// nothing is; a PC's bus all ones).
    NotAnIoApic { version: u32 },
}

/// Why the kernel did not use the HPET its ACPI table names.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum HpetRefusal {
    /// The address is not on a 1 KiB boundary, as an HPET's register
    /// block is.
    Misaligned,
    /// The registers would lie in RAM the memory map gives the kernel or
    /// its loader.
    InRam,
    /// The capabilities register read `capabilities`: no revision (bits
    /// 0-7 zero), or all ones (nothing answers there).
    NotAnHpet { capabilities: u32 },
    /// The counter's period, in femtoseconds, is outside 100 ps to 100 ns
    /// (the specification's longest; Linux refuses shorter than 100 ps).
    Period { femtoseconds: u32 },
}

/// Where the kernel masked a storming vector's source.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MaskedAt {
    /// The redirection entry of an I/O APIC that takes that global system
    /// interrupt.
    IoApic { interrupt: u32 },
    /// A local vector table entry of the local APIC (timer, thermal,
    /// performance counter, LINT0, LINT1, error, CMCI).
    LocalApic,
    /// Nowhere: no entry the kernel knows of sends that vector; it may
    /// come again.
    Nowhere,
}

/// Where an interrupt was in service, and got its end of interrupt.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EndedAt {
    /// In service nowhere (raised by `INT`, or an 8259's spurious IRQ).
    Nowhere,
    LocalApic,
    /// One of the 8259s (the master, or the slave and the master).
    Pic,
    LocalApicAndPic,
}

impl EndedAt {
    /// The longer words first: one is the start of another.
    const ALL: [EndedAt; 4] = [EndedAt::LocalApicAndPic, EndedAt::LocalApic, EndedAt::Pic, EndedAt::Nowhere];

    fn words(self) -> &'static str {
        match self {
            EndedAt::Nowhere => "in service nowhere, so no end of interrupt",
            EndedAt::LocalApic => "ended at the local APIC",
            EndedAt::Pic => "ended at the 8259",
            EndedAt::LocalApicAndPic => "ended at the local APIC and the 8259",
        }
    }

    /// Where it was ended, from whether the local APIC and a PIC had it.
    pub fn of(local_apic: bool, pic: bool) -> Self {
        match (local_apic, pic) {
            (false, false) => EndedAt::Nowhere,
            (true, false) => EndedAt::LocalApic,
            (false, true) => EndedAt::Pic,
            (true, true) => EndedAt::LocalApicAndPic,
        }
    }
}

/// The machine the kernel found, and by what signs (`kernel/src/platform/machine.rs`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MachineEvidence {
    pub machine: Machine,
    /// CPUID's hypervisor vendor signature, where CPUID says there is a
    /// hypervisor.
    pub hypervisor: Option<[u8; 12]>,
    /// The host bridge's PCI subsystem IDs, where it has any.
    pub board: Option<PciId>,
}

const COM1_POLLING: &str = "COM1: its interrupt (IRQ 4) did not arrive; receiving by polling alone";
const NO_TIMER_TICK: &str = "PIT: its interrupt (IRQ 0) did not arrive; the server waits without halting";
const NO_FRAMEBUFFER: &str = "video: the loader handed over no framebuffer (the firmware's graphics mode has none it \
                              can draw in: a PixelBitmask or BltOnly mode, or no graphics output at all)";
const BESIDE_THE_VGA: [&str; 2] = [
    "video: the firmware's framebuffer is not in the memory of the VGA at ",
    ": the frame goes to the framebuffer, where the firmware showed its screen",
];
// The firmware's address checks (`firmware_tables::MemoryMap::
// device_registers`) say what is wrong with an address; each device's
// refusal says it in its own words.
impl From<Misplaced> for HpetRefusal {
    fn from(misplaced: Misplaced) -> Self {
        match misplaced {
            Misplaced::Misaligned => HpetRefusal::Misaligned,
            Misplaced::InRam => HpetRefusal::InRam,
        }
    }
}

impl From<Misplaced> for IoApicRefusal {
    fn from(misplaced: Misplaced) -> Self {
        match misplaced {
            Misplaced::Misaligned => IoApicRefusal::Misaligned,
            Misplaced::InRam => IoApicRefusal::InRam,
        }
    }
}

const HPET_AT: &str = "HPET: its ACPI table places it at ";
const MISALIGNED: &str = ", not on a 1 KiB boundary; not used";
const IN_RAM: &str = ", in RAM the memory map names; not used";
const NOT_AN_HPET: &str = ": no HPET there; not used";
const BAD_PERIOD: &str = ", outside 100000 fs to 100000000 fs; not used";
const PM_TIMER_AT: &str = "PM timer: the FADT places it at port ";
const ON_A_DEVICE: &str = ", a fixed device's; not used";
const IO_APIC_AT: &str = "I/O APIC: its ACPI table places it at ";
const MISALIGNED_16: &str = ", not on a 16-byte boundary; not used";
const NOTHING_THERE: &str = ", where its index register reads 0xffffffff: no I/O APIC there; not used";
const NOT_AN_IO_APIC: &str = ": no I/O APIC there; not used";
const NOWHERE: &str = "no entry sends it, so nothing was masked";
const SERR: [&str; 2] = ["no SERR#", "SERR# (a PCI system error)"];
const IOCHK: [&str; 2] = ["no IOCHK#", "IOCHK# (an I/O channel check)"];

impl fmt::Display for LogEvent {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            LogEvent::Machine(MachineEvidence { machine, hypervisor, board }) => {
                write!(f, "machine: {} (CPUID ", machine.name())?;
                match hypervisor {
                    Some(name) => write!(f, "hypervisor \"{}\"", name.escape_ascii())?,
                    None => write!(f, "no hypervisor")?,
                }
                match board {
                    Some(id) => write!(f, ", host bridge subsystem {id})"),
                    None => write!(f, ", no host bridge subsystem)"),
                }
            }
            LogEvent::Com1Polling => write!(f, "{COM1_POLLING}"),
            LogEvent::NoTimerTick => write!(f, "{NO_TIMER_TICK}"),
            LogEvent::FramebufferBesideTheVga { vga_at } => {
                write!(f, "{}{vga_at}{}", BESIDE_THE_VGA[0], BESIDE_THE_VGA[1])
            }
            LogEvent::NoFramebuffer => write!(f, "{NO_FRAMEBUFFER}"),
            LogEvent::VgaMismatch(mismatch) => write!(f, "{mismatch}"),
            LogEvent::LineDropped { overlong, kept, idle_seconds } => {
                let what = if overlong { "an overlong line" } else { "an unfinished line" };
                write!(f, "dropped {what} ({kept} bytes kept) idle for {idle_seconds} s")
            }
            LogEvent::Nmi { count, reason, serr, iochk } => write!(
                f,
                "NMI {count} (port 0x61 = {reason:#04x}: {}, {}); the kernel carries on",
                SERR[usize::from(serr)],
                IOCHK[usize::from(iochk)]
            ),
            LogEvent::StrayInterrupt { vector, count, ended } => {
                write!(f, "stray interrupt: vector {vector:#04x}, {count} so far, {}; returned", ended.words())
            }
            LogEvent::InterruptStorm { vector, count, window_ms, masked } => {
                write!(f, "interrupt storm: vector {vector:#04x} came {count} times within {window_ms} ms; ")?;
                match masked {
                    MaskedAt::IoApic { interrupt } => write!(f, "masked at the I/O APIC, interrupt {interrupt}"),
                    MaskedAt::LocalApic => write!(f, "masked in the local APIC's vector table"),
                    MaskedAt::Nowhere => write!(f, "{NOWHERE}"),
                }
            }
            LogEvent::HpetRefused { address, why } => {
                write!(f, "{HPET_AT}{address:#x}")?;
                match why {
                    HpetRefusal::Misaligned => write!(f, "{MISALIGNED}"),
                    HpetRefusal::InRam => write!(f, "{IN_RAM}"),
                    HpetRefusal::NotAnHpet { capabilities } => {
                        write!(f, ", where its capabilities read {capabilities:#010x}{NOT_AN_HPET}")
                    }
                    HpetRefusal::Period { femtoseconds } => {
                        write!(f, ", where its period reads {femtoseconds} fs{BAD_PERIOD}")
                    }
                }
            }
            LogEvent::IoApicRefused { address, why } => {
                write!(f, "{IO_APIC_AT}{address:#x}")?;
                match why {
                    IoApicRefusal::Misaligned => write!(f, "{MISALIGNED_16}"),
                    IoApicRefusal::InRam => write!(f, "{IN_RAM}"),
                    IoApicRefusal::NothingThere => write!(f, "{NOTHING_THERE}"),
                    IoApicRefusal::NotAnIoApic { version } => {
                        write!(f, ", where its version register reads {version:#010x}{NOT_AN_IO_APIC}")
                    }
                }
            }
            LogEvent::PmTimerRefused { port } => write!(f, "{PM_TIMER_AT}{port:#x}{ON_A_DEVICE}"),
        }
    }
}

impl LogEvent {
    /// Parses the text written by `Display`.
    pub fn parse(text: &str) -> Result<Self, Malformed> {
        let mut prose = Prose::new("LOG", text);
        let sentences = [
            (COM1_POLLING, LogEvent::Com1Polling),
            (NO_TIMER_TICK, LogEvent::NoTimerTick),
            (NO_FRAMEBUFFER, LogEvent::NoFramebuffer),
        ];
        let event = if let Some((_, event)) = sentences.into_iter().find(|(words, _)| prose.next_is(words)) {
            event
        } else if prose.next_is("machine: ") {
            LogEvent::Machine(read_machine(&mut prose)?)
        } else if prose.next_is(BESIDE_THE_VGA[0]) {
            let address = prose.until(BESIDE_THE_VGA[1], "where the VGA is")?;
            let vga_at = PciAddress::parse(address).ok_or(prose.malformed(Expected::Value("VGA address")))?;
            LogEvent::FramebufferBesideTheVga { vga_at }
        } else if prose.next_is("dropped ") {
            let overlong = prose.next_is("an overlong line (");
            if !overlong {
                prose.expect("an unfinished line (", "`an unfinished line`")?;
            }
            let kept = prose.number("bytes kept")?;
            prose.expect(" bytes kept) idle for ", "`bytes kept`")?;
            let idle_seconds = prose.number("idle seconds")?;
            prose.expect(" s", "`s`")?;
            LogEvent::LineDropped { overlong, kept, idle_seconds }
        } else if prose.next_is("NMI ") {
            let count = prose.number("NMI count")?;
            prose.expect(" (port 0x61 = ", "`port 0x61`")?;
            let reason = prose.hex_of("port 0x61")?;
            prose.expect(": ", "`: `")?;
            let serr = read_either(&mut prose, SERR, "SERR#")?;
            prose.expect(", ", "`, `")?;
            let iochk = read_either(&mut prose, IOCHK, "IOCHK#")?;
            prose.expect("); the kernel carries on", "`the kernel carries on`")?;
            LogEvent::Nmi { count, reason, serr, iochk }
        } else if prose.next_is("stray interrupt: vector ") {
            let vector = prose.hex_of("vector")?;
            prose.expect(", ", "`, `")?;
            let count = prose.number("count")?;
            prose.expect(" so far, ", "`so far`")?;
            let ended = EndedAt::ALL
                .into_iter()
                .find(|ended| prose.next_is(ended.words()))
                .ok_or(prose.malformed(Expected::Value("where it was ended")))?;
            prose.expect("; returned", "`returned`")?;
            LogEvent::StrayInterrupt { vector, count, ended }
        } else if prose.next_is("interrupt storm: vector ") {
            let vector = prose.hex_of("vector")?;
            prose.expect(" came ", "`came`")?;
            let count = prose.number("count")?;
            prose.expect(" times within ", "`times within`")?;
            let window_ms = prose.number("window")?;
            prose.expect(" ms; ", "`ms`")?;
            let masked = if prose.next_is("masked at the I/O APIC, interrupt ") {
                MaskedAt::IoApic { interrupt: prose.number("interrupt")? }
            } else if prose.next_is("masked in the local APIC's vector table") {
                MaskedAt::LocalApic
            } else {
                prose.expect(NOWHERE, "where it was masked")?;
                MaskedAt::Nowhere
            };
            LogEvent::InterruptStorm { vector, count, window_ms, masked }
        } else if prose.next_is(HPET_AT) {
            let address = prose.hex("HPET address")?;
            let why = if prose.next_is(MISALIGNED) {
                HpetRefusal::Misaligned
            } else if prose.next_is(IN_RAM) {
                HpetRefusal::InRam
            } else if prose.next_is(", where its capabilities read ") {
                let capabilities = prose.hex_of("capabilities")?;
                prose.expect(NOT_AN_HPET, "`no HPET there`")?;
                HpetRefusal::NotAnHpet { capabilities }
            } else {
                prose.expect(", where its period reads ", "why the HPET was not used")?;
                let femtoseconds = prose.number("period")?;
                prose.expect(" fs", "`fs`")?;
                prose.expect(BAD_PERIOD, "`outside`")?;
                HpetRefusal::Period { femtoseconds }
            };
            LogEvent::HpetRefused { address, why }
        } else if prose.next_is(IO_APIC_AT) {
            let address = prose.hex("I/O APIC address")?;
            let why = if prose.next_is(MISALIGNED_16) {
                IoApicRefusal::Misaligned
            } else if prose.next_is(IN_RAM) {
                IoApicRefusal::InRam
            } else if prose.next_is(NOTHING_THERE) {
                IoApicRefusal::NothingThere
            } else {
                prose.expect(", where its version register reads ", "why the I/O APIC was not used")?;
                let version = prose.hex_of("version")?;
                prose.expect(NOT_AN_IO_APIC, "`no I/O APIC there`")?;
                IoApicRefusal::NotAnIoApic { version }
            };
            LogEvent::IoApicRefused { address, why }
        } else if prose.next_is(PM_TIMER_AT) {
            let port = prose.hex_of("port")?;
            prose.expect(ON_A_DEVICE, "`a fixed device's`")?;
            LogEvent::PmTimerRefused { port }
        } else {
            LogEvent::VgaMismatch(Mismatch::parse(text).map_err(|_| prose.malformed(Expected::Shape("a LOG text")))?)
        };
        if let LogEvent::VgaMismatch(_) = event {
            return Ok(event);
        }
        prose.written_by(event)
    }
}

/// Which of `words` comes next: `false` for the first, `true` for the
/// second.
fn read_either(prose: &mut Prose<'_>, words: [&str; 2], what: &'static str) -> Result<bool, Malformed> {
    // The second ones are longer and start like no first one.
    match (prose.next_is(words[1]), prose.next_is(words[0])) {
        (true, _) => Ok(true),
        (false, true) => Ok(false),
        (false, false) => Err(prose.malformed(Expected::Value(what))),
    }
}

fn read_machine(prose: &mut Prose<'_>) -> Result<MachineEvidence, Malformed> {
    let name = prose.until(" (CPUID ", "the machine's name")?;
    let machine = Machine::from_name(name).ok_or(prose.malformed(Expected::Value("machine")))?;
    let hypervisor = match prose.next_is("no hypervisor") {
        true => None,
        false => {
            prose.expect("hypervisor \"", "`hypervisor`")?;
            let name = prose.escaped("hypervisor")?;
            Some(name.try_into().map_err(|_| prose.malformed(Expected::Value("hypervisor")))?)
        }
    };
    let board = match prose.next_is(", no host bridge subsystem)") {
        true => None,
        false => {
            prose.expect(", host bridge subsystem ", "`host bridge subsystem`")?;
            let id = prose.until(")", "the host bridge's subsystem")?;
            Some(PciId::parse(id).ok_or(prose.malformed(Expected::Value("host bridge subsystem")))?)
        }
    };
    Ok(MachineEvidence { machine, hypervisor, board })
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use crate::replies::RegisterGroup;
    use std::string::ToString;

    fn events() -> [LogEvent; 26] {
        let qemu = MachineEvidence {
            machine: Machine::Qemu,
            hypervisor: Some(*b"TCGTCGTCGTCG"),
            board: Some(PciId { vendor: 0x1af4, device: 0x1100 }),
        };
        let odd =
            MachineEvidence { machine: Machine::Unknown, hypervisor: Some(*b"a\"\\\x00b\n, )x\xffy"), board: None };
        let bare = MachineEvidence { machine: Machine::Unknown, hypervisor: None, board: None };
        [
            LogEvent::Machine(qemu),
            LogEvent::Machine(odd),
            LogEvent::Machine(bare),
            LogEvent::Com1Polling,
            LogEvent::NoTimerTick,
            LogEvent::FramebufferBesideTheVga { vga_at: PciAddress { bus: 0, device: 5, function: 0 } },
            LogEvent::NoFramebuffer,
            LogEvent::VgaMismatch(Mismatch { group: RegisterGroup::Crtc, index: 0x11, expected: 0x8e, actual: 0x0e }),
            LogEvent::LineDropped { overlong: false, kept: 6, idle_seconds: 10 },
            LogEvent::LineDropped { overlong: true, kept: 0, idle_seconds: 10 },
            LogEvent::Nmi { count: 1, reason: 0x20, serr: false, iochk: false },
            LogEvent::Nmi { count: 7, reason: 0xc0, serr: true, iochk: true },
            LogEvent::StrayInterrupt { vector: 0x99, count: 2, ended: EndedAt::LocalApic },
            LogEvent::StrayInterrupt { vector: 0xff, count: 1, ended: EndedAt::Nowhere },
            LogEvent::InterruptStorm {
                vector: 0x9a,
                count: 1001,
                window_ms: 10,
                masked: MaskedAt::IoApic { interrupt: 8 },
            },
            LogEvent::InterruptStorm { vector: 0xfe, count: 5000, window_ms: 10, masked: MaskedAt::LocalApic },
            LogEvent::InterruptStorm { vector: 0x30, count: 1001, window_ms: 1, masked: MaskedAt::Nowhere },
            LogEvent::HpetRefused { address: 0x100_0000, why: HpetRefusal::InRam },
            LogEvent::HpetRefused { address: 0xfed0_0004, why: HpetRefusal::Misaligned },
            LogEvent::HpetRefused { address: 0xfed0_0000, why: HpetRefusal::NotAnHpet { capabilities: u32::MAX } },
            LogEvent::HpetRefused { address: 0xfed0_0000, why: HpetRefusal::Period { femtoseconds: 99_999 } },
            LogEvent::IoApicRefused { address: 0x100_0000, why: IoApicRefusal::InRam },
            LogEvent::IoApicRefused { address: 0xfec0_0004, why: IoApicRefusal::Misaligned },
            LogEvent::IoApicRefused { address: 0xfeb0_0000, why: IoApicRefusal::NothingThere },
            LogEvent::IoApicRefused { address: 0xfeb0_0000, why: IoApicRefusal::NotAnIoApic { version: 0 } },
            LogEvent::PmTimerRefused { port: 0x3f8 },
        ]
    }

    #[test]
    fn every_log_event_round_trips_through_its_text() {
        for event in events() {
            let text = event.to_string();
            assert_eq!(LogEvent::parse(&text), Ok(event), "{text}");
        }
        for ended in EndedAt::ALL {
            let event = LogEvent::StrayInterrupt { vector: 0x28, count: 3, ended };
            assert_eq!(LogEvent::parse(&event.to_string()), Ok(event));
        }
    }

    #[test]
    fn the_texts_are_the_ones_the_protocol_page_shows() {
        let [qemu, _, _, com1, pit, ..] = events();
        assert_eq!(
            qemu.to_string(),
            "machine: qemu (CPUID hypervisor \"TCGTCGTCGTCG\", host bridge subsystem 1af4:1100)"
        );
        assert_eq!(com1.to_string(), "COM1: its interrupt (IRQ 4) did not arrive; receiving by polling alone");
        assert_eq!(pit.to_string(), "PIT: its interrupt (IRQ 0) did not arrive; the server waits without halting");
        let nmi = LogEvent::Nmi { count: 1, reason: 0x20, serr: false, iochk: false };
        assert_eq!(nmi.to_string(), "NMI 1 (port 0x61 = 0x20: no SERR#, no IOCHK#); the kernel carries on");
        let stray = LogEvent::StrayInterrupt { vector: 0x99, count: 2, ended: EndedAt::LocalApic };
        assert_eq!(stray.to_string(), "stray interrupt: vector 0x99, 2 so far, ended at the local APIC; returned");
        let dropped = LogEvent::LineDropped { overlong: false, kept: 6, idle_seconds: 10 };
        assert_eq!(dropped.to_string(), "dropped an unfinished line (6 bytes kept) idle for 10 s");
    }

    #[test]
    fn texts_the_kernel_would_not_write_are_refused() {
        for garbage in [
            "",
            "NMI 1 (port 0x61 = 0x20: no SERR#, no IOCHK#)",
            "NMI 1 (port 0x61 = 0x20: no SERR#, no IOCHK#); the kernel carries on; and more",
            "NMI 1 (port 0x61 = 0x2: no SERR#, no IOCHK#); the kernel carries on",
            "NMI 1 (port 0x61 = 0x20: SERR#, no IOCHK#); the kernel carries on",
            "stray interrupt: vector 0x99, 2 so far, ended somewhere; returned",
            "stray interrupt: vector 0x199, 2 so far, ended at the 8259; returned",
            "machine: qemu (CPUID hypervisor \"TCG\", host bridge subsystem 1af4:1100)",
            "machine: bochs (CPUID no hypervisor, no host bridge subsystem)",
            "dropped a line (6 bytes kept) idle for 10 s",
            "COM1: its interrupt (IRQ 4) did not arrive",
            "COM1: its interrupt (IRQ 4) did not arrive; receiving by polling alone.",
        ] {
            assert!(LogEvent::parse(garbage).is_err(), "{garbage:?}");
        }
    }
}
