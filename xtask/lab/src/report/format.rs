//! Figures as the report writes them: counts with thousands separators,
//! durations in their unit, ratios with their interval.

use crate::stats::Ratio;

/// A ratio with its interval: `1.55× (1.49–1.61)`, or alone where it has
/// none.
pub(super) fn ratio(r: &Ratio) -> String {
    match (r.low, r.high) {
        (Some(low), Some(high)) => format!("{:.2}× ({low:.2}–{high:.2})", r.ratio),
        _ => format!("{:.2}×", r.ratio),
    }
}

/// Nanoseconds, readably.
pub(super) fn duration(ns: f64) -> String {
    if ns >= 1e6 {
        format!("{:.2} ms", ns / 1e6)
    } else if ns >= 1e3 {
        format!("{:.2} µs", ns / 1e3)
    } else {
        format!("{ns:.0} ns")
    }
}

/// An integer with thin thousands separators.
pub(super) fn count(n: u64) -> String {
    let digits = n.to_string();
    let mut grouped = String::new();
    for (i, d) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i).is_multiple_of(3) {
            grouped.push(',');
        }
        grouped.push(d);
    }
    grouped
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_group_thousands() {
        assert_eq!(count(0), "0");
        assert_eq!(count(999), "999");
        assert_eq!(count(1_234_567), "1,234,567");
    }

    #[test]
    fn ratios_carry_their_interval() {
        let r = Ratio { ratio: 1.554, low: Some(1.49), high: Some(1.612), count: 7 };
        assert_eq!(ratio(&r), "1.55× (1.49–1.61)");
        assert_eq!(ratio(&Ratio { low: None, high: None, count: 1, ..r }), "1.55×");
    }

    #[test]
    fn durations_pick_their_unit() {
        assert_eq!(duration(820.4), "820 ns");
        assert_eq!(duration(1_500.0), "1.50 µs");
        assert_eq!(duration(2_500_000.0), "2.50 ms");
    }
}
