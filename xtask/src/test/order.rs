//! The order the test binaries start in: the longest first, so that the
//! run does not end waiting for one long binary started late. The
//! figures are each binary's time alone, measured; a binary not named
//! here is short and starts after these.

/// Seconds each long binary took alone (see the module's note): its
/// package, its target, the seconds.
const MEASURED: &[(&str, &str, u32)] = &[];

/// The seconds `target` of `package` took alone, or 0 if not measured.
pub fn expected_seconds(package: &str, target: &str) -> u32 {
    MEASURED.iter().find(|&&(p, t, _)| p == package && t == target).map_or(0, |&(_, _, seconds)| seconds)
}
