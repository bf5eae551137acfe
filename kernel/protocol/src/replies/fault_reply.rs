//! The `OK` text of `FAULT strayinterrupt`, `strayirq` and
//! `interruptstorm`: the faults the kernel survives, and how each was
//! raised.

use core::fmt;

use super::fields::{Expected, Malformed};
use super::prose::Prose;

/// How the kernel raised the interrupt.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Raised {
    /// `strayinterrupt`: a self-IPI through the local APIC, as a device's
    /// interrupt arrives.
    LocalApic,
    /// `strayinterrupt`: by `INT`, where there is no enabled local APIC.
    Int,
    /// Not at all: `strayinterrupt` with no enabled local APIC and a
    /// vector `INT` is not given for (only the default one is), or
    /// `interruptstorm` with no I/O APIC taking the RTC's IRQ.
    NotRaised,
    /// `strayirq`: the RTC's periodic interrupt, IRQ 8, let through the two
    /// 8259s.
    Pic,
    /// `interruptstorm`: the RTC's IRQ 8 routed level-triggered through
    /// the I/O APIC, its line left high.
    IoApicLevel,
}

impl Raised {
    const ALL: [Raised; 5] = [Raised::LocalApic, Raised::Int, Raised::NotRaised, Raised::Pic, Raised::IoApicLevel];

    /// The `FAULT` kind that raises it this way, as the text starts.
    fn kind(self) -> &'static str {
        match self {
            Raised::LocalApic | Raised::Int | Raised::NotRaised => "strayinterrupt",
            Raised::Pic => "strayirq",
            Raised::IoApicLevel => "interruptstorm",
        }
    }

    fn words(self) -> &'static str {
        match self {
            Raised::LocalApic => "sent through the local APIC",
            Raised::Int => "raised by INT (no enabled local APIC)",
            Raised::NotRaised => "not raised (nothing here can raise it)",
            Raised::Pic => "raised by the RTC's IRQ 8 through the two 8259s",
            Raised::IoApicLevel => {
                "raised by the RTC's IRQ 8, level-triggered through the I/O APIC, its line left high"
            }
        }
    }
}

/// The `OK` text of the stray `FAULT`s: `KIND: vector 0xV HOW; N taken on
/// it so far`, the count of stray interrupts on the vector read once the
/// interrupt was taken (or a bounded wait for it ended).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct StrayRaised {
    pub vector: u8,
    pub raised: Raised,
    /// Interrupts taken on the vector since boot.
    pub taken: u32,
}

impl fmt::Display for StrayRaised {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let Self { vector, raised, taken } = *self;
        write!(f, "{}: vector {vector:#04x} {}; {taken} taken on it so far", raised.kind(), raised.words())
    }
}

impl StrayRaised {
    /// Parses the text written by `Display`.
    pub fn parse(text: &str) -> Result<Self, Malformed> {
        let mut prose = Prose::new("FAULT", text);
        let kind = prose.until(": vector ", "`KIND: vector`")?;
        let vector = prose.hex_of("vector")?;
        prose.expect(" ", "a space")?;
        let raised = Raised::ALL
            .into_iter()
            .find(|raised| raised.kind() == kind && prose.next_is(raised.words()))
            .ok_or(prose.malformed(Expected::Value("how it was raised")))?;
        prose.expect("; ", "`; `")?;
        let taken = prose.number("taken")?;
        prose.expect(" taken on it so far", "`taken on it so far`")?;
        prose.written_by(Self { vector, raised, taken })
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use std::string::ToString;

    #[test]
    fn stray_interrupts_round_trip_and_garbage_is_refused() {
        let raised = StrayRaised { vector: 0x99, raised: Raised::LocalApic, taken: 2 };
        let text = raised.to_string();
        assert_eq!(text, "strayinterrupt: vector 0x99 sent through the local APIC; 2 taken on it so far");
        assert_eq!(StrayRaised::parse(&text), Ok(raised));
        for raised in Raised::ALL {
            let stray = StrayRaised { vector: 0xff, raised, taken: 0 };
            assert_eq!(StrayRaised::parse(&stray.to_string()), Ok(stray));
        }
        let irq = StrayRaised { vector: 0x28, raised: Raised::Pic, taken: 1 };
        assert_eq!(
            irq.to_string(),
            "strayirq: vector 0x28 raised by the RTC's IRQ 8 through the two 8259s; 1 taken on it so far"
        );
        for garbage in [
            "strayinterrupt: vector 0x99 sent; 2 taken on it so far",
            "strayinterrupt: vector 0x99 sent through the local APIC; 2 taken",
            "strayinterrupt: vector 0x099 sent through the local APIC; 2 taken on it so far",
            "strayirq: vector 0x99 sent through the local APIC; 2 taken on it so far",
        ] {
            assert!(StrayRaised::parse(garbage).is_err(), "{garbage}");
        }
    }
}
