//! The `OK` text of `CLOCK`: the time-stamp counter's rate, how the
//! kernel knows it, and what every source gave.

use core::fmt;

use super::fields::{Fields, Malformed};

/// How the kernel knows its time-stamp counter's rate (`kernel/src/time/clock.rs`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ClockSource {
    /// Counted against the PIT at boot.
    Pit,
    /// Counted against the ACPI power management timer (3.579545 MHz),
    /// found through the ACPI tables.
    PmTimer,
    /// Counted against the HPET's main counter, found through the ACPI
    /// tables.
    Hpet,
    /// Stated by the CPU (CPUID leaf 0x15 or 0x16), where nothing could
    /// measure it.
    Cpuid,
    /// Nothing measured or stated it: a rate taken on trust, so times in
    /// seconds are not to be believed.
    Assumed,
}

impl ClockSource {
    pub const ALL: [ClockSource; 5] =
        [ClockSource::Pit, ClockSource::PmTimer, ClockSource::Hpet, ClockSource::Cpuid, ClockSource::Assumed];

    pub fn name(self) -> &'static str {
        match self {
            ClockSource::Pit => "pit",
            ClockSource::PmTimer => "pmtimer",
            ClockSource::Hpet => "hpet",
            ClockSource::Cpuid => "cpuid",
            ClockSource::Assumed => "assumed",
        }
    }

    pub(crate) fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|source| source.name() == name)
    }
}

/// The rate each source gave, where the machine has it: the kernel
/// measures against every timer it finds and reads what the CPU states,
/// so that each can be checked against the others. Text: `pit_hz=A
/// pmtimer_hz=B hpet_hz=C cpuid_hz=D`, each only where that source is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct ClockReadings {
    pub pit: Option<u64>,
    pub pm_timer: Option<u64>,
    pub hpet: Option<u64>,
    pub cpuid: Option<u64>,
}

impl ClockReadings {
    /// Each reading with its field name, in the order of the text.
    fn named(&self) -> [(&'static str, Option<u64>); 4] {
        [("pit_hz", self.pit), ("pmtimer_hz", self.pm_timer), ("hpet_hz", self.hpet), ("cpuid_hz", self.cpuid)]
    }
}

/// The `OK` text of `CLOCK`: `tsc_hz=N source=S` and the [`ClockReadings`],
/// the time-stamp counter's ticks per second, how the kernel knows it,
/// and what every source gave. rdtsc ticks over `hz` are seconds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TscRate {
    pub hz: u64,
    pub source: ClockSource,
    pub readings: ClockReadings,
}

impl fmt::Display for TscRate {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "tsc_hz={} source={}", self.hz, self.source.name())?;
        for (name, reading) in self.readings.named() {
            if let Some(hz) = reading {
                write!(f, " {name}={hz}")?;
            }
        }
        Ok(())
    }
}

impl TscRate {
    /// Parses the text written by `Display` (an older kernel's has no
    /// readings).
    pub fn parse(text: &str) -> Result<Self, Malformed> {
        let mut fields = Fields::new("CLOCK", text);
        let hz = fields.parsed("tsc_hz")?;
        let source = fields.read("source", ClockSource::from_name)?;
        let readings = ClockReadings {
            pit: fields.optional("pit_hz")?,
            pm_timer: fields.optional("pmtimer_hz")?,
            hpet: fields.optional("hpet_hz")?,
            cpuid: fields.optional("cpuid_hz")?,
        };
        fields.end()?;
        Ok(Self { hz, source, readings })
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use crate::replies::fields::Expected;
    use std::string::ToString;

    #[test]
    fn tsc_rates_round_trip_and_reject_garbage() {
        let readings =
            ClockReadings { pit: Some(2_893_000_000), pm_timer: None, hpet: Some(2_894_000_000), cpuid: None };
        for source in ClockSource::ALL {
            for readings in [readings, ClockReadings::default()] {
                let rate = TscRate { hz: 2_893_421_000, source, readings };
                assert_eq!(TscRate::parse(&rate.to_string()), Ok(rate));
            }
        }
        let rate = TscRate { hz: 7, source: ClockSource::Pit, readings: ClockReadings::default() };
        assert_eq!(rate.to_string(), "tsc_hz=7 source=pit");
        let rate = TscRate { hz: 7, source: ClockSource::PmTimer, readings };
        assert_eq!(rate.to_string(), "tsc_hz=7 source=pmtimer pit_hz=2893000000 hpet_hz=2894000000");
        let malformed = |expected| Err(Malformed { reply: "CLOCK", expected });
        for (garbage, expected) in [
            ("tsc_hz=7", Expected::Field("source")),
            ("tsc_hz=x source=pit", Expected::Value("tsc_hz")),
            ("tsc_hz=7 source=rtc", Expected::Value("source")),
            ("source=pit tsc_hz=7", Expected::Field("tsc_hz")),
            ("tsc_hz=7 source=pit x=1", Expected::End),
            ("tsc_hz=7 source=pit hpet_hz=1 pit_hz=2", Expected::End),
            ("tsc_hz=7 source=pit pit_hz=x", Expected::Value("pit_hz")),
            ("tsc_hz=7 source=pit pit_hz=1 pit_hz=1", Expected::End),
        ] {
            assert_eq!(TscRate::parse(garbage), malformed(expected), "{garbage}");
        }
    }

    #[test]
    fn an_older_kernels_clock_still_parses_without_the_readings() {
        let rate = TscRate::parse("tsc_hz=2596138016 source=pit").unwrap();
        assert_eq!(rate.readings, ClockReadings::default());
    }
}
