//! The `BENCH` frame's payload: its unit line, then one line per method.

use alloc::vec::Vec;
use core::fmt;

use raster::{MethodId, Refusal};

use super::fields::{Expected, Malformed};

/// The first line of a `BENCH` payload: the unit of the numbers after it.
pub const BENCH_UNIT_LINE: &str = "# rdtsc ticks per scene draw, median of the repeats; on a PC, cycles; under QEMU, \
     its virtual clock: emulated instructions with -icount shift=0, host time without";

/// One method's line of a `BENCH` payload: `METHOD CYCLES REFUSED
/// [REFUSAL]`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BenchRow {
    pub method: MethodId,
    /// rdtsc ticks of one whole-scene draw, the median of the repeats.
    pub cycles: u64,
    /// Polygons of the scene the method declined.
    pub refused: usize,
    /// Why it declined the first of them ([`Refusal::name`]); there
    /// exactly when `refused` is not 0.
    pub refusal: Option<Refusal>,
}

impl fmt::Display for BenchRow {
    /// The line without its `\n`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} {} {}", self.method, self.cycles, self.refused)?;
        if let Some(refusal) = self.refusal {
            write!(f, " {}", refusal.name())?;
        }
        Ok(())
    }
}

impl BenchRow {
    /// Parses one line written by `Display`.
    pub fn parse(line: &str) -> Result<Self, Malformed> {
        let malformed = |expected| Malformed { reply: "BENCH", expected };
        let mut words = line.split(' ');
        let method = next_value(&mut words, "METHOD")?;
        let cycles = next_value(&mut words, "CYCLES")?;
        let refused = next_value(&mut words, "REFUSED")?;
        let refusal = match words.next() {
            Some(name) => Some(Refusal::from_name(name).ok_or(malformed(Expected::Value("REFUSAL")))?),
            None => None,
        };
        if words.next().is_some() {
            return Err(malformed(Expected::End));
        }
        if (refused > 0) != refusal.is_some() {
            return Err(malformed(Expected::Shape("a refusal count and its reason, both or neither")));
        }
        Ok(Self { method, cycles, refused, refusal })
    }
}

/// The next word of a `BENCH` line, the value called `name`, parsed.
fn next_value<'a, T: core::str::FromStr>(
    words: &mut impl Iterator<Item = &'a str>,
    name: &'static str,
) -> Result<T, Malformed> {
    let word = words.next().ok_or(Malformed { reply: "BENCH", expected: Expected::Shape(LINE) })?;
    word.parse().map_err(|_| Malformed { reply: "BENCH", expected: Expected::Value(name) })
}

/// The shape of a `BENCH` line.
const LINE: &str = "a line `METHOD CYCLES REFUSED [REFUSAL]`";

/// The `BENCH` frame's payload: [`BENCH_UNIT_LINE`], then a [`BenchRow`]
/// per method in [`MethodId::ALL`] order, each line ending in `\n`.
#[derive(Clone, Debug, PartialEq, Eq, Default)]
pub struct BenchReply {
    pub rows: Vec<BenchRow>,
}

impl fmt::Display for BenchReply {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "{BENCH_UNIT_LINE}")?;
        self.rows.iter().try_for_each(|row| writeln!(f, "{row}"))
    }
}

impl BenchReply {
    /// Parses the payload written by `Display`: the unit line first (the
    /// numbers mean nothing without it), then the rows.
    pub fn parse(text: &str) -> Result<Self, Malformed> {
        let mut lines = text.lines();
        if lines.next() != Some(BENCH_UNIT_LINE) {
            return Err(Malformed { reply: "BENCH", expected: Expected::Shape("its unit line first") });
        }
        Ok(Self { rows: lines.map(BenchRow::parse).collect::<Result<_, _>>()? })
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use alloc::vec;
    use std::format;
    use std::string::ToString;

    #[test]
    fn bench_replies_round_trip_and_reject_garbage() {
        let row = |method, cycles, refused, refusal| BenchRow { method, cycles, refused, refusal };
        let reply = BenchReply {
            rows: vec![
                row(MethodId::Pendleton, 1200, 2, Some(Refusal::MultipleContours)),
                row(MethodId::Exact, 900, 0, None),
            ],
        };
        let text = reply.to_string();
        assert_eq!(text, format!("{BENCH_UNIT_LINE}\npendleton 1200 2 multiple-contours\nexact 900 0\n"));
        assert_eq!(BenchReply::parse(&text), Ok(reply));
        assert_eq!(BenchReply::parse(&format!("{BENCH_UNIT_LINE}\n")), Ok(BenchReply::default()));
        let malformed = |expected| Err(Malformed { reply: "BENCH", expected });
        assert_eq!(BenchReply::parse("exact 900 0\n"), malformed(Expected::Shape("its unit line first")));
        let both = Expected::Shape("a refusal count and its reason, both or neither");
        for (garbage, expected) in [
            ("exact many 0", Expected::Value("CYCLES")),
            ("exact 900", Expected::Shape("a line `METHOD CYCLES REFUSED [REFUSAL]`")),
            ("exact 900 x", Expected::Value("REFUSED")),
            ("exakt 900 0", Expected::Value("METHOD")),
            ("exact 900 1", both),
            ("exact 900 0 out-of-range", both),
            ("exact 900 1 bored", Expected::Value("REFUSAL")),
            ("exact 900 1 out-of-range x", Expected::End),
            ("", Expected::Value("METHOD")),
        ] {
            assert_eq!(BenchReply::parse(&format!("{BENCH_UNIT_LINE}\n{garbage}\n")), malformed(expected), "{garbage}");
        }
    }
}
