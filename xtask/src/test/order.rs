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
    ("harness", "adapters", 133),
    ("harness", "secure_boot_key", 111),
    ("harness", "secure_boot", 108),
    ("harness", "soak", 98),
    ("harness", "serial_check", 96),
    ("harness", "loader_refusals", 70),
    ("harness", "clock", 63),
    ("xtask", "xtask", 34),
    ("harness", "exit", 34),
    ("harness", "demo_keys", 31),
    ("harness", "show", 28),
    ("harness", "vga_path", 25),
    ("harness", "bench", 24),
    ("harness", "explorer", 22),
    ("harness", "line_trouble", 20),
    ("harness", "interrupts", 19),
    ("harness", "pages", 16),
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
                ("harness", suite) => root.join("tests/tests").join(format!("{suite}.rs")),
                ("xtask", "xtask") => root.join("xtask/src/main.rs"),
                other => panic!("{other:?}: not a binary the test knows how to find"),
            };
            assert!(file.is_file(), "{package}/{target}: no {}", file.display());
        }
    }

    #[test]
    fn the_longest_comes_first_and_the_unmeasured_last() {
        assert!(expected_seconds("harness", "adapters") > expected_seconds("harness", "pages"));
        assert_eq!(expected_seconds("harness", "doc_paths"), 0);
        assert_eq!(expected_seconds("raster", "adapters"), 0);
    }
}
