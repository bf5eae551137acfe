//! The `FATAL` frame: a CPU exception or a panic, named, after which the
//! kernel stops (`kernel/src/interrupts/fatal.rs`).

use core::fmt;

use crate::commands::FaultKind;
use crate::replies::{Expected, Malformed, Prose};

/// The CPU's exceptions, by vector, as the manuals name them; the reserved
/// vectors by their number.
pub const EXCEPTION_NAMES: [&str; 32] = [
    "divide error",
    "debug exception",
    "non-maskable interrupt",
    "breakpoint",
    "overflow",
    "bound range exceeded",
    "invalid opcode",
    "device not available",
    "double fault",
    "coprocessor segment overrun",
    "invalid TSS",
    "segment not present",
    "stack-segment fault",
    "general protection fault",
    "page fault",
    "reserved exception 15",
    "x87 floating-point error",
    "alignment check",
    "machine check",
    "SIMD floating-point exception",
    "virtualization exception",
    "control protection exception",
    "reserved exception 22",
    "reserved exception 23",
    "reserved exception 24",
    "reserved exception 25",
    "reserved exception 26",
    "reserved exception 27",
    "hypervisor injection exception",
    "VMM communication exception",
    "security exception",
    "reserved exception 31",
];

/// The vectors with a report of their own.
pub const PAGE_FAULT_VECTOR: u8 = 14;
pub const DOUBLE_FAULT_VECTOR: u8 = 8;

/// A page fault's error code, written by the names of its bits as the
/// kernel wrote it before this type (the `x86_64` crate's
/// `PageFaultErrorCode` debug format): `PageFaultErrorCode(CAUSED_BY_WRITE
/// | USER_MODE)`, `PageFaultErrorCode(0x0)` with none set. Bits without a
/// name are not kept.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PageFaultCode(u64);

/// The error code's bits with a name (Intel's manual, volume 3, "Page-Fault
/// Error Code"; the names the `x86_64` crate gives them).
const PAGE_FAULT_BITS: [(u64, &str); 10] = [
    (1, "PROTECTION_VIOLATION"),
    (1 << 1, "CAUSED_BY_WRITE"),
    (1 << 2, "USER_MODE"),
    (1 << 3, "MALFORMED_TABLE"),
    (1 << 4, "INSTRUCTION_FETCH"),
    (1 << 5, "PROTECTION_KEY"),
    (1 << 6, "SHADOW_STACK"),
    (1 << 7, "HLAT"),
    (1 << 15, "SGX"),
    (1 << 31, "RMP"),
];

impl PageFaultCode {
    /// The code's bits that have a name.
    pub fn new(code: u64) -> Self {
        Self(code & PAGE_FAULT_BITS.iter().fold(0, |all, (bit, _)| all | bit))
    }

    pub fn bits(self) -> u64 {
        self.0
    }
}

impl fmt::Display for PageFaultCode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "PageFaultErrorCode(")?;
        if self.0 == 0 {
            write!(f, "0x0")?;
        }
        let set = PAGE_FAULT_BITS.iter().filter(|(bit, _)| self.0 & bit != 0);
        for (i, (_, name)) in set.enumerate() {
            write!(f, "{}{name}", if i == 0 { "" } else { " | " })?;
        }
        write!(f, ")")
    }
}

/// A `FATAL` frame's text.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FatalReport<'a> {
    /// A CPU exception but a page fault or a double fault, by vector (0
    /// to 31): `NAME at 0xIP`, or `NAME (error code 0xE) at 0xIP`.
    Exception { vector: u8, error: Option<u64>, at: u64 },
    /// `page fault at 0xADDRESS (CODE), instruction at 0xIP`.
    PageFault { address: u64, code: PageFaultCode, at: u64 },
    /// `double fault (error code 0xE) at 0xIP, stack pointer 0xSP`.
    DoubleFault { error: u64, at: u64, stack: u64 },
    /// `panic: MESSAGE`, the message as the panic handler wrote it (cut
    /// where the kernel's buffer ends).
    Panic(&'a str),
    /// `FAULT KIND: the fault handler returned`: a fault provoked on
    /// request that no handler stopped.
    HandlerReturned(FaultKind),
}

impl fmt::Display for FatalReport<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            FatalReport::Exception { vector, error, at } => {
                write!(f, "{}", EXCEPTION_NAMES[usize::from(vector % 32)])?;
                if let Some(code) = error {
                    write!(f, " (error code {code:#x})")?;
                }
                write!(f, " at {at:#x}")
            }
            FatalReport::PageFault { address, code, at } => {
                write!(f, "page fault at {address:#x} ({code}), instruction at {at:#x}")
            }
            FatalReport::DoubleFault { error, at, stack } => {
                write!(f, "double fault (error code {error:#x}) at {at:#x}, stack pointer {stack:#x}")
            }
            FatalReport::Panic(message) => write!(f, "panic: {message}"),
            FatalReport::HandlerReturned(kind) => write!(f, "FAULT {}: the fault handler returned", kind.name()),
        }
    }
}

impl<'a> FatalReport<'a> {
    /// Parses the text written by `Display`.
    pub fn parse(text: &'a str) -> Result<Self, Malformed> {
        let mut prose = Prose::new("FATAL", text);
        let report = if prose.next_is("panic: ") {
            FatalReport::Panic(prose.rest())
        } else if prose.next_is("FAULT ") {
            let name = prose.until(": the fault handler returned", "`the fault handler returned`")?;
            let kind = FaultKind::ALL.into_iter().find(|kind| kind.name() == name);
            FatalReport::HandlerReturned(kind.ok_or(prose.malformed(Expected::Value("fault kind")))?)
        } else if prose.next_is("page fault at ") {
            let address = prose.hex("address")?;
            prose.expect(" (PageFaultErrorCode(", "the error code")?;
            let flags = prose.until(")), instruction at ", "`instruction at`")?;
            let mut code = 0;
            if flags != "0x0" {
                for name in flags.split(" | ") {
                    let bit = PAGE_FAULT_BITS.iter().find(|(_, known)| *known == name);
                    code |= bit.ok_or(prose.malformed(Expected::Value("error code")))?.0;
                }
            }
            FatalReport::PageFault { address, code: PageFaultCode(code), at: prose.hex("instruction")? }
        } else if prose.next_is("double fault (error code ") {
            let error = prose.hex("error code")?;
            prose.expect(") at ", "`at`")?;
            let at = prose.hex("instruction")?;
            prose.expect(", stack pointer ", "`stack pointer`")?;
            FatalReport::DoubleFault { error, at, stack: prose.hex("stack pointer")? }
        } else {
            let vector = (0..32u8)
                .filter(|&vector| vector != PAGE_FAULT_VECTOR && vector != DOUBLE_FAULT_VECTOR)
                .find(|&vector| prose.next_is(EXCEPTION_NAMES[usize::from(vector)]))
                .ok_or(prose.malformed(Expected::Shape("an exception's name, `panic:` or `FAULT`")))?;
            let error = match prose.next_is(" (error code ") {
                true => {
                    let code = prose.hex("error code")?;
                    prose.expect(")", "`)`")?;
                    Some(code)
                }
                false => None,
            };
            prose.expect(" at ", "`at`")?;
            FatalReport::Exception { vector, error, at: prose.hex("instruction")? }
        };
        prose.written_by(report)
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use std::string::ToString;

    #[test]
    fn every_fatal_report_round_trips_through_its_text() {
        let reports = [
            FatalReport::Exception { vector: 0, error: None, at: 0x8000_1234 },
            FatalReport::Exception { vector: 13, error: Some(0x10), at: 0xffff_8000_0000_0000 },
            FatalReport::Exception { vector: 18, error: None, at: 1 },
            FatalReport::Exception { vector: 31, error: None, at: 1 },
            FatalReport::PageFault { address: 0xdeadbeef000, code: PageFaultCode::new(0), at: 0x20_1234 },
            FatalReport::PageFault { address: 0, code: PageFaultCode::new(0b11 | 1 << 31 | 1 << 40), at: 2 },
            FatalReport::DoubleFault { error: 0, at: 0x20_1000, stack: 0x10_0000 },
            FatalReport::Panic("panicked at kernel/src/interrupts/fault.rs:60:30:\nFAULT panic: the host asked for it"),
            FatalReport::Panic(""),
            FatalReport::HandlerReturned(FaultKind::PageFault),
        ];
        for report in reports {
            let text = report.to_string();
            assert_eq!(FatalReport::parse(&text), Ok(report), "{text}");
        }
        for vector in (0..32).filter(|&v| v != PAGE_FAULT_VECTOR && v != DOUBLE_FAULT_VECTOR) {
            let report = FatalReport::Exception { vector, error: Some(u64::from(vector)), at: 0x1000 };
            assert_eq!(FatalReport::parse(&report.to_string()), Ok(report));
        }
    }

    #[test]
    fn the_texts_are_the_ones_the_kernel_wrote_before() {
        let fault = FatalReport::PageFault { address: 0xdeadbeef000, code: PageFaultCode::new(0), at: 0x20_1234 };
        assert_eq!(fault.to_string(), "page fault at 0xdeadbeef000 (PageFaultErrorCode(0x0)), instruction at 0x201234");
        let fault = FatalReport::PageFault { address: 8, code: PageFaultCode::new(0b110), at: 1 };
        assert_eq!(
            fault.to_string(),
            "page fault at 0x8 (PageFaultErrorCode(CAUSED_BY_WRITE | USER_MODE)), instruction at 0x1"
        );
        let protection = FatalReport::Exception { vector: 13, error: Some(0x10), at: 0x20_0000 };
        assert_eq!(protection.to_string(), "general protection fault (error code 0x10) at 0x200000");
        assert_eq!(FatalReport::Exception { vector: 3, error: None, at: 0x20 }.to_string(), "breakpoint at 0x20");
    }

    #[test]
    fn texts_the_kernel_would_not_write_are_refused() {
        for garbage in [
            "",
            "breakpoint",
            "breakpoint at 20",
            "breakpoint at 0x20 again",
            "page fault at 0x20",
            "page fault at 0x8 (PageFaultErrorCode(WRITE)), instruction at 0x1",
            "page fault at 0x8 (PageFaultErrorCode(USER_MODE | CAUSED_BY_WRITE)), instruction at 0x1",
            "double fault at 0x20",
            "FAULT nap: the fault handler returned",
            "general protection fault (error code 0x010) at 0x20",
        ] {
            assert!(FatalReport::parse(garbage).is_err(), "{garbage:?}");
        }
    }
}
