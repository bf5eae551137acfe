//! The `OK` text of `FAULT strayinterrupt`: the one fault the kernel
//! survives, and how it was raised.

use core::fmt;

use super::fields::{Expected, Malformed};
use super::prose::Prose;

/// How the kernel raised the interrupt.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Raised {
    /// A self-IPI through the local APIC, as a device's interrupt arrives.
    LocalApic,
    /// By `INT`, where there is no enabled local APIC.
    Int,
}

impl Raised {
    const ALL: [Raised; 2] = [Raised::LocalApic, Raised::Int];

    fn words(self) -> &'static str {
        match self {
            Raised::LocalApic => "sent through the local APIC",
            Raised::Int => "raised by INT (no enabled local APIC)",
        }
    }
}

/// The `OK` text of `FAULT strayinterrupt`: `strayinterrupt: vector 0xV
/// HOW; N taken on it so far`, the count read once the interrupt was taken
/// (or a bounded wait for it ended).
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
        write!(f, "strayinterrupt: vector {vector:#04x} {}; {taken} taken on it so far", raised.words())
    }
}

impl StrayRaised {
    /// Parses the text written by `Display`.
    pub fn parse(text: &str) -> Result<Self, Malformed> {
        let mut prose = Prose::new("FAULT", text);
        prose.expect("strayinterrupt: vector ", "`strayinterrupt: vector`")?;
        let vector = prose.hex_of("vector")?;
        prose.expect(" ", "a space")?;
        let raised = Raised::ALL
            .into_iter()
            .find(|raised| prose.next_is(raised.words()))
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
        let by_int = StrayRaised { vector: 0xff, raised: Raised::Int, taken: 0 };
        assert_eq!(StrayRaised::parse(&by_int.to_string()), Ok(by_int));
        for garbage in [
            "strayinterrupt: vector 0x99 sent; 2 taken on it so far",
            "strayinterrupt: vector 0x99 sent through the local APIC; 2 taken",
            "strayinterrupt: vector 0x099 sent through the local APIC; 2 taken on it so far",
        ] {
            assert!(StrayRaised::parse(garbage).is_err(), "{garbage}");
        }
    }
}
