//! What `cargo xtask test ARGS` asks of `cargo test`, in the terms the
//! runner understands: which packages and targets, whether doc tests run,
//! and what every test binary is given. Anything else in ARGS leaves the
//! run to `cargo test` itself.

/// The arguments for cargo itself: those before a `--` (after it they
/// are the test binaries').
pub fn cargo_part(args: &[String]) -> &[String] {
    &args[..args.iter().position(|arg| arg == "--").unwrap_or(args.len())]
}

/// The arguments before a `--` are cargo's; after it, the test binaries'.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Selection {
    /// Package and target flags for `cargo test`, as given (`-p NAME`,
    /// `--test NAME`, `--lib`, ...).
    pub cargo: Vec<String>,
    pub doc_tests: DocTests,
    /// For every test binary (and the doc tests): what followed `--`.
    pub test_args: Vec<String>,
}

/// Whether the doc tests run, as `cargo test` decides it: with no target
/// flag they run beside the test binaries, with `--doc` alone.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DocTests {
    No,
    Also,
    Only,
}

/// Flags that take a value (`--test NAME` or `--test=NAME`): the target
/// flag first.
const VALUE_FLAGS: [&str; 3] = ["--test", "-p", "--package"];
/// Flags that choose targets other than the doc tests.
const TARGET_FLAGS: [&str; 4] = ["--lib", "--bins", "--tests", "--test"];

impl Selection {
    /// The selection `args` make, or `None` if they hold anything but
    /// package and target flags before a `--` (a test name, `--release`,
    /// `--features`...): such a run is left to `cargo test`.
    pub fn parse(args: &[String]) -> Option<Self> {
        let cargo = cargo_part(args);
        let test_args = args.get(cargo.len() + 1..).unwrap_or_default();
        let (mut targets, mut doc) = (false, false);
        let mut words = cargo.iter();
        while let Some(word) = words.next() {
            let flag = word.split_once('=').map_or(word.as_str(), |(flag, _)| flag);
            match flag {
                "--doc" => doc = true,
                "--no-fail-fast" => {}
                "--lib" | "--bins" | "--tests" => targets = true,
                _ if VALUE_FLAGS.contains(&flag) => {
                    targets |= TARGET_FLAGS.contains(&flag);
                    if flag == word.as_str() {
                        words.next().filter(|value| !value.starts_with('-'))?;
                    }
                }
                _ => return None,
            }
        }
        let doc_tests = match (doc, targets) {
            (true, true) => return None,
            (true, false) => DocTests::Only,
            (false, true) => DocTests::No,
            (false, false) => DocTests::Also,
        };
        let cargo = cargo.iter().filter(|word| *word != "--doc" && *word != "--no-fail-fast").cloned().collect();
        Some(Self { cargo, doc_tests, test_args: test_args.to_vec() })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(line: &str) -> Vec<String> {
        line.split_whitespace().map(String::from).collect()
    }

    fn parse(line: &str) -> Option<Selection> {
        Selection::parse(&args(line))
    }

    #[test]
    fn a_whole_run_is_every_binary_and_the_doc_tests() {
        let whole = parse("").unwrap();
        assert_eq!((whole.cargo.len(), whole.doc_tests, whole.test_args.len()), (0, DocTests::Also, 0));
        let captured = parse("-- --nocapture").unwrap();
        assert_eq!((captured.doc_tests, captured.test_args), (DocTests::Also, args("--nocapture")));
    }

    #[test]
    fn named_suites_run_without_the_doc_tests() {
        for line in ["--test pages", "--test=pages --test bochs", "-p harness --lib", "--tests"] {
            let selection = parse(line).unwrap();
            assert_eq!((selection.cargo, selection.doc_tests), (args(line), DocTests::No), "{line}");
        }
        let one = parse("--test pages -- --nocapture every_page").unwrap();
        assert_eq!((one.cargo, one.test_args), (args("--test pages"), args("--nocapture every_page")));
    }

    #[test]
    fn packages_alone_keep_their_doc_tests_and_doc_alone_is_only_them() {
        assert_eq!(parse("-p harness").unwrap().doc_tests, DocTests::Also);
        assert_eq!(parse("--package=raster --no-fail-fast").unwrap(), {
            Selection { cargo: args("--package=raster"), doc_tests: DocTests::Also, test_args: vec![] }
        });
        let doc = parse("-p raster --doc").unwrap();
        assert_eq!((doc.cargo, doc.doc_tests), (args("-p raster"), DocTests::Only));
    }

    #[test]
    fn anything_else_is_left_to_cargo_test() {
        for line in ["every_page", "--release", "--test", "--test --lib", "--doc --lib", "-j 2", "--features x"] {
            assert_eq!(parse(line), None, "{line}");
        }
    }
}
