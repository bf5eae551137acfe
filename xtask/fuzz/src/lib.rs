//! `fuzz`: what the coverage-guided fuzz targets (`cargo xtask fuzz`,
//! libFuzzer through cargo-fuzz; the targets themselves are one line each
//! in `targets/fuzz_targets/`) check, how each decodes the fuzzer's bytes,
//! and the seed corpora and dictionaries the xtask writes for them from
//! the built-in scenes. A check panics when a property fails, which
//! libFuzzer reports as a crash and saves the input of.
//!
//! The checks are plain functions over bytes, so the unit tests here run
//! each one over its seeds on the stable toolchain (`cargo xtask test`),
//! and a crash found by the fuzzer is pinned by a regression test in the
//! crate where the bug was (`docs/testing.md`).

pub mod command;
pub mod exact_reference;
pub mod explore;
pub mod methods;
pub mod polygon;
pub mod scene_file;
pub mod svg;
pub mod upload;

/// A fuzz target: its name (the cargo-fuzz binary's), the property it
/// checks on one input, its seeds (a file name and the bytes) and the
/// words of its dictionary (none for binary inputs).
pub struct Target {
    pub name: &'static str,
    pub check: fn(&[u8]),
    pub seeds: fn() -> Vec<(String, Vec<u8>)>,
    pub dictionary: fn() -> Vec<String>,
}

/// Every target, in the order `cargo xtask fuzz` runs them.
pub static TARGETS: [Target; 7] = [
    Target {
        name: "scene_file",
        check: scene_file::check,
        seeds: scene_file::seeds,
        dictionary: scene_file::dictionary,
    },
    Target { name: "command", check: command::check, seeds: command::seeds, dictionary: command::dictionary },
    Target { name: "upload", check: upload::check, seeds: upload::seeds, dictionary: upload::dictionary },
    Target { name: "methods", check: methods::check, seeds: methods::seeds, dictionary: Vec::new },
    Target {
        name: "exact_reference",
        check: exact_reference::check,
        seeds: exact_reference::seeds,
        dictionary: Vec::new,
    },
    Target { name: "explorer", check: explore::check, seeds: explore::seeds, dictionary: Vec::new },
    Target { name: "svg", check: svg::check, seeds: svg::seeds, dictionary: svg::dictionary },
];

/// The target called `name`.
pub fn target(name: &str) -> Option<&'static Target> {
    TARGETS.iter().find(|target| target.name == name)
}

/// `words` as a libFuzzer dictionary: one quoted word a line, with `\`,
/// `"` and anything outside printable ASCII written as `\xNN`.
pub fn dictionary_file(words: &[String]) -> String {
    let mut text = String::new();
    for word in words {
        text.push('"');
        for byte in word.bytes() {
            match byte {
                b'\\' | b'"' | ..=0x1f | 0x7f.. => text.push_str(&format!("\\x{byte:02X}")),
                _ => text.push(char::from(byte)),
            }
        }
        text.push_str("\"\n");
    }
    text
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_target_holds_on_every_seed() {
        for target in &TARGETS {
            let seeds = (target.seeds)();
            assert!(!seeds.is_empty(), "{} has no seeds", target.name);
            for (name, bytes) in seeds {
                let outcome = std::panic::catch_unwind(|| (target.check)(&bytes));
                assert!(outcome.is_ok(), "{} fails on its seed {name}", target.name);
            }
        }
    }

    #[test]
    fn each_target_is_found_by_name_once() {
        for target in &TARGETS {
            assert!(std::ptr::eq(self::target(target.name).unwrap(), target));
        }
        assert!(self::target("nope").is_none());
    }

    /// The seed counts a page's table gives, target by target: the rows of
    /// the section `heading` whose first cell is a quoted name and whose
    /// second is a number.
    fn seed_counts(page: &str, heading: &str) -> Vec<(String, usize)> {
        let section = page.split_once(heading).map_or("", |(_, after)| after);
        let section = section.split("\n#").next().unwrap_or("");
        section
            .lines()
            .filter_map(|line| {
                let mut cells = line.strip_prefix("| `")?.split('|');
                let name = cells.next()?.trim().strip_suffix('`')?;
                Some((name.to_string(), cells.next()?.trim().parse().ok()?))
            })
            .collect()
    }

    #[test]
    fn testing_md_gives_every_targets_seed_count_as_the_seeds_make_it() {
        let page = concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/testing.md");
        let page = std::fs::read_to_string(page).expect("docs/testing.md is there");
        let documented = seed_counts(&page, "### Inputs, seeds and dictionaries");
        let made: Vec<(String, usize)> =
            TARGETS.iter().map(|target| (target.name.to_string(), (target.seeds)().len())).collect();
        assert_eq!(documented, made, "docs/testing.md's seed counts against the targets' seeds");
    }

    #[test]
    fn a_seed_table_is_read_row_by_row_and_a_count_off_it_is_not() {
        let page = "## Other\n| `methods` | 1 | elsewhere |\n### Seeds\n\n| target | seeds | what |\n|---|---:|---|\n\
                    | `command` | 275 | lines |\n| `svg` | 14 | drawings |\n| `upload` | any bytes | no count |\n### Next\n\
                    | `scene_file` | 10 | after |";
        assert_eq!(seed_counts(page, "### Seeds"), [("command".to_string(), 275), ("svg".to_string(), 14)]);
    }

    #[test]
    fn dictionary_words_are_quoted_and_escaped() {
        let words = ["poly".to_string(), "a\"b\\c\n".to_string()];
        assert_eq!(dictionary_file(&words), "\"poly\"\n\"a\\x22b\\x5Cc\\x0A\"\n");
    }
}
