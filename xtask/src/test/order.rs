//! The order the test binaries start in: the longest first, so that the
//! run does not end waiting for one long binary started late. The
//! figures are each binary's time alone: the shortest of up to three
//! runs of it alone (`target/debug/deps/NAME-*` from its package's
//! folder) on this project's 2-core machine, 2026-11-28, at load averages
//! of 3.4 to 15 (others' builds); a binary not named here took under 15 s
//! and starts after these.

/// Seconds each long binary took alone (see the module's note): its
/// package, its target, the seconds.
const MEASURED: &[(&str, &str, u32)] = &[
    ("suites", "adapters", 133),
    ("suites", "secure_boot_key", 111),
    ("suites", "secure_boot", 108),
    ("suites", "soak", 98),
    ("suites", "serial_check", 96),
    ("suites", "loader_refusals", 70),
    ("suites", "clock", 63),
    ("xtask", "xtask", 34),
    ("suites", "exit", 34),
    ("suites", "demo_keys", 31),
    ("suites", "show", 28),
    ("suites", "vga_path", 25),
    ("suites", "bench", 24),
    ("suites", "explorer", 22),
    ("suites", "line_trouble", 20),
    ("suites", "interrupts", 19),
    ("suites", "pages", 16),
];

/// The seconds `target` of `package` took alone, or 0 if not measured.
pub fn expected_seconds(package: &str, target: &str) -> u32 {
    MEASURED.iter().find(|&&(p, t, _)| p == package && t == target).map_or(0, |&(_, _, seconds)| seconds)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A binary renamed or removed would drop out of the order unseen:
    /// every one named is a test file of its package.
    #[test]
    fn every_binary_named_is_a_test_file() {
        let root = install::workspace::root();
        for &(package, target, _) in MEASURED {
            let file = match (package, target) {
                ("suites", suite) => root.join("tests/tests").join(format!("{suite}.rs")),
                ("xtask", "xtask") => root.join("xtask/src/main.rs"),
                other => panic!("{other:?}: not a binary the test knows how to find"),
            };
            assert!(file.is_file(), "{package}/{target}: no {}", file.display());
        }
    }

    #[test]
    fn the_longest_comes_first_and_the_unmeasured_last() {
        assert!(expected_seconds("suites", "adapters") > expected_seconds("suites", "pages"));
        assert_eq!(expected_seconds("suites", "doc_paths"), 0);
        assert_eq!(expected_seconds("raster", "adapters"), 0);
    }
}
