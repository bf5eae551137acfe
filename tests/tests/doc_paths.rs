//! Every repository path the docs and the code's comments name exists, and
//! every link between the Markdown pages leads to a file and a heading that
//! are there: a file or section that moved or went away leaves no citation
//! behind. And the names the docs use are the code's: every `cargo xtask`
//! command is one of xtask's, every `--method`, `--vga` and `--test` names
//! a method, a card and a test suite, every `POLYLAB_` variable is one the
//! code reads, and every variable the code reads is in the docs.
//!
//! A path is a token that starts with one of the repository's top-level
//! folders (`kernel/`, `boot/`, `xtask/`, `tests/`, `docs/`, `.ci/`,
//! `.cargo/`). It resolves against the repository's root, or, in a crate's
//! own files, against that crate's folder (`tests/hostile.rs` in `raster`
//! means `kernel/raster/tests/hostile.rs`). A token with a `*` names the
//! files it matches within one folder, and must match at least one of
//! them, unless it is an argument of `rm` (the README's regeneration
//! commands remove what they just made). Tokens built from shell variables
//! (`$s`) or brace lists are the commands' own, not citations.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use harness::workspace;
use regex::Regex;
use walkdir::WalkDir;

/// The top-level folders a cited path starts with.
const TOP: &str = r"(?:\.ci|\.cargo|kernel|boot|xtask|tests|docs)";

/// The files read for citations: text the project wrote.
fn cited_in(path: &Path) -> bool {
    matches!(path.extension().and_then(|e| e.to_str()), Some("md" | "rs" | "toml" | "js" | "html" | "css"))
        || path.ends_with(".ci/run")
}

fn sources(root: &Path) -> Vec<PathBuf> {
    WalkDir::new(root)
        .into_iter()
        .filter_entry(|entry| !matches!(entry.file_name().to_str(), Some("target" | ".git" | "node_modules")))
        .filter_map(|entry| entry.ok())
        .filter(|entry| entry.file_type().is_file() && cited_in(entry.path()))
        .map(|entry| entry.into_path())
        .collect()
}

/// The folder of the crate a file belongs to (the nearest `Cargo.toml`
/// above it), if it is inside one below the root.
fn crate_dir(root: &Path, file: &Path) -> Option<PathBuf> {
    file.ancestors()
        .skip(1)
        .take_while(|dir| *dir != root)
        .find(|dir| dir.join("Cargo.toml").is_file())
        .map(Path::to_path_buf)
}

/// Whether `cited` names something under `base`: a file or folder, or for a
/// `*` pattern in its last component at least one entry of that folder.
fn exists_under(base: &Path, cited: &str) -> bool {
    let Some(star) = cited.rfind('/').map(|slash| &cited[slash + 1..]).filter(|name| name.contains('*')) else {
        return base.join(cited).exists();
    };
    let folder = base.join(&cited[..cited.len() - star.len()]);
    let (head, tail) = star.split_once('*').expect("the last component has a star");
    std::fs::read_dir(folder).into_iter().flatten().filter_map(|entry| entry.ok()).any(|entry| {
        let name = entry.file_name();
        let name = name.to_string_lossy();
        name.len() >= head.len() + tail.len() && name.starts_with(head) && name.ends_with(tail)
    })
}

/// The repository paths `text` cites that exist neither under the root nor
/// under `own_crate`, with their line numbers.
fn missing_citations(root: &Path, own_crate: Option<&Path>, text: &str) -> Vec<(usize, String)> {
    let token = Regex::new(&format!(r"(?:^|[^A-Za-z0-9_./-])({TOP}/[A-Za-z0-9_.*/$\{{\}},-]*[A-Za-z0-9_*/])"))
        .expect("a valid pattern");
    let mut missing = Vec::new();
    for (number, line) in text.lines().enumerate() {
        let removes = line.trim_start().starts_with("rm ");
        for found in token.captures_iter(line) {
            let cited = &found[1];
            if cited.contains(['$', '{', '}']) || (removes && cited.contains('*')) {
                continue;
            }
            let cited = cited.trim_end_matches('/');
            if !exists_under(root, cited) && !own_crate.is_some_and(|dir| exists_under(dir, cited)) {
                missing.push((number + 1, cited.to_string()));
            }
        }
    }
    missing
}

#[test]
fn every_path_the_docs_and_comments_name_exists() -> Result<()> {
    let root = workspace::root();
    let mut missing = Vec::new();
    // This file's own examples of missing paths are its test data.
    let files: Vec<PathBuf> = sources(root).into_iter().filter(|file| !file.ends_with(file!())).collect();
    assert!(files.iter().any(|file| file.ends_with("README.md")), "the README was not read");
    for file in &files {
        let text = std::fs::read_to_string(file).with_context(|| format!("failed to read {}", file.display()))?;
        let shown = file.strip_prefix(root).unwrap_or(file).display().to_string();
        for (line, cited) in missing_citations(root, crate_dir(root, file).as_deref(), &text) {
            missing.push(format!("{shown}:{line} names {cited}, which does not exist"));
        }
    }
    assert!(missing.is_empty(), "{} citations of missing paths:\n{}", missing.len(), missing.join("\n"));
    Ok(())
}

#[test]
fn a_gone_file_is_caught_and_a_present_one_is_not() {
    let root = workspace::root();
    let raster = root.join("kernel/raster");
    let text = "see `kernel/raster/tests/gone.rs` and (docs/methods.md),\n\
                tests/hostile.rs and kernel/raster/tests/exact_*.rs, docs/$s.gif\n\
                rm docs/*.screen.png\nxtask/nothing_*.rs";
    assert_eq!(
        missing_citations(root, Some(&raster), text),
        [(1, "kernel/raster/tests/gone.rs".to_string()), (4, "xtask/nothing_*.rs".to_string())]
    );
    // Outside raster, its crate-relative citation is not found.
    assert_eq!(missing_citations(root, None, "tests/hostile.rs"), [(1, "tests/hostile.rs".to_string())]);
}

/// A heading's anchor as GitHub makes it: lower case, punctuation dropped
/// (but `-` and `_`), spaces turned into `-`.
fn anchor(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter(|c| c.is_alphanumeric() || matches!(c, '-' | '_' | ' '))
        .map(|c| if c == ' ' { '-' } else { c })
        .collect()
}

fn anchors(markdown: &str) -> Vec<String> {
    markdown
        .lines()
        .filter_map(|line| line.trim_start_matches('#').strip_prefix(' ').filter(|_| line.starts_with('#')))
        .map(anchor)
        .collect()
}

/// The links of the Markdown page `page` that lead nowhere: to a file that
/// is not there, or to a heading its page does not have. Web addresses are
/// not followed.
fn broken_links(page: &Path, text: &str) -> Vec<String> {
    let link = Regex::new(r"\]\(([^)\s]+)\)").expect("a valid pattern");
    let folder = page.parent().expect("a page is in a folder");
    let mut broken = Vec::new();
    for found in link.captures_iter(text) {
        let target = &found[1];
        if target.contains("://") || target.starts_with("mailto:") {
            continue;
        }
        let (file, heading) = target.split_once('#').unwrap_or((target, ""));
        let file = if file.is_empty() { page.to_path_buf() } else { folder.join(file) };
        if !file.exists() {
            broken.push(format!("{target}: no such file"));
        } else if !heading.is_empty() && file.extension().is_some_and(|e| e == "md") {
            let linked = std::fs::read_to_string(&file).unwrap_or_default();
            if !anchors(&linked).iter().any(|a| a == heading) {
                broken.push(format!("{target}: no such heading"));
            }
        }
    }
    broken
}

#[test]
fn every_markdown_link_leads_somewhere() -> Result<()> {
    let root = workspace::root();
    let pages: Vec<PathBuf> =
        sources(root).into_iter().filter(|file| file.extension().is_some_and(|e| e == "md")).collect();
    assert!(pages.iter().any(|page| page.ends_with("docs/methods.md")), "the docs were not read");
    let mut broken = Vec::new();
    for page in &pages {
        let text = std::fs::read_to_string(page).with_context(|| format!("failed to read {}", page.display()))?;
        let shown = page.strip_prefix(root).unwrap_or(page).display().to_string();
        broken.extend(broken_links(page, &text).into_iter().map(|problem| format!("{shown}: {problem}")));
    }
    assert!(broken.is_empty(), "{} broken links:\n{}", broken.len(), broken.join("\n"));
    Ok(())
}

#[test]
fn a_link_to_a_missing_file_or_heading_is_caught() {
    let readme = workspace::root().join("README.md");
    let text = "[ok](docs/methods.md#measured-deviations) [here](#the-methods) [web](https://example.org/x#y)\n\
                [gone](docs/gone.md) [no heading](docs/methods.md#no-such-section) [self](#nowhere)";
    assert_eq!(
        broken_links(&readme, text),
        ["docs/gone.md: no such file", "docs/methods.md#no-such-section: no such heading", "#nowhere: no such heading"]
    );
    assert_eq!(anchor("What the tests prove, adapter by adapter"), "what-the-tests-prove-adapter-by-adapter");
    assert_eq!(anchor("`exact`: the `i32` limits"), "exact-the-i32-limits");
}

/// The section a plain-text citation names (`docs/PAGE.md#anchor`, as the
/// code's comments write them) that its page does not have.
fn missing_sections(root: &Path, text: &str) -> Vec<String> {
    let cited = Regex::new(r"docs/([a-z0-9-]+\.md)#([A-Za-z0-9_-]+)").expect("a valid pattern");
    cited
        .captures_iter(text)
        .filter(|found| {
            let page = std::fs::read_to_string(root.join("docs").join(&found[1])).unwrap_or_default();
            !anchors(&page).iter().any(|a| a == &found[2])
        })
        .map(|found| found[0].to_string())
        .collect()
}

#[test]
fn every_section_the_code_cites_exists() -> Result<()> {
    let root = workspace::root();
    let mut missing = Vec::new();
    // The pages' own links are `every_markdown_link_leads_somewhere`'s.
    let code = sources(root).into_iter().filter(|f| !f.ends_with(file!()) && f.extension().is_none_or(|e| e != "md"));
    for file in code {
        let text = std::fs::read_to_string(&file).with_context(|| format!("failed to read {}", file.display()))?;
        let shown = file.strip_prefix(root).unwrap_or(&file).display().to_string();
        missing.extend(missing_sections(root, &text).into_iter().map(|cited| format!("{shown} cites {cited}")));
    }
    assert!(missing.is_empty(), "{} citations of missing sections:\n{}", missing.len(), missing.join("\n"));
    Ok(())
}

#[test]
fn a_cited_section_that_is_not_there_is_caught() {
    let text = "see docs/lab.md#goals and docs/lab.md#what-holds-exact-back, docs/gone.md#x";
    assert_eq!(missing_sections(workspace::root(), text), ["docs/lab.md#what-holds-exact-back", "docs/gone.md#x"]);
}

/// xtask's commands, as clap names them: the variants of `Action` in
/// `xtask/src/opt.rs`, in kebab case.
fn xtask_commands(root: &Path) -> Result<Vec<String>> {
    let opt = std::fs::read_to_string(root.join("xtask/src/opt.rs")).context("failed to read xtask/src/opt.rs")?;
    let start = opt.find("pub enum Action {").context("xtask/src/opt.rs has no `enum Action`")?;
    let body = &opt[start..start + opt[start..].find("\n}").context("`enum Action` does not end")?];
    let variant = Regex::new(r"(?m)^    ([A-Z][A-Za-z0-9]*)\s*[(,]").expect("a valid pattern");
    let kebab = |name: &str| {
        name.chars().enumerate().fold(String::new(), |mut out, (i, c)| {
            if c.is_uppercase() && i > 0 {
                out.push('-');
            }
            out.push(c.to_ascii_lowercase());
            out
        })
    };
    Ok(variant.captures_iter(body).map(|found| kebab(&found[1])).collect())
}

/// The test suites of every crate: the files of a `tests/` folder beside a
/// `Cargo.toml`, by name, as `--test NAME` runs them.
fn test_suites(root: &Path) -> Vec<String> {
    sources(root)
        .into_iter()
        .filter(|file| file.extension().is_some_and(|e| e == "rs"))
        .filter(|file| {
            let folder = file.parent().expect("a file is in a folder");
            folder.ends_with("tests") && folder.parent().is_some_and(|krate| krate.join("Cargo.toml").is_file())
        })
        .filter_map(|file| Some(file.file_stem()?.to_str()?.to_string()))
        .collect()
}

/// The `POLYLAB_` variables the code reads: the names its `.rs` files spell
/// as string literals, outside comments.
fn variables_read(root: &Path) -> Result<Vec<String>> {
    let literal = Regex::new(r#""(POLYLAB_[A-Z0-9_]+)""#).expect("a valid pattern");
    let mut names = Vec::new();
    for file in sources(root).into_iter().filter(|f| f.extension().is_some_and(|e| e == "rs") && !f.ends_with(file!()))
    {
        let text = std::fs::read_to_string(&file).with_context(|| format!("failed to read {}", file.display()))?;
        for line in text.lines().filter(|line| !line.trim_start().starts_with("//")) {
            names.extend(literal.captures_iter(line).map(|found| found[1].to_string()));
        }
    }
    names.sort();
    names.dedup();
    Ok(names)
}

/// What the docs may name, kind by kind: the pattern a name is found by (its
/// first group the name) and the names there are.
struct Names {
    kinds: Vec<(&'static str, Regex, Vec<String>)>,
}

impl Names {
    fn of(root: &Path) -> Result<Self> {
        let pattern = |p: &str| Regex::new(p).expect("a valid pattern");
        let methods = raster::MethodId::ALL.iter().map(|m| m.name().to_string()).collect();
        let cards = harness::Adapter::ALL.iter().map(|a| a.name().to_string()).collect();
        Ok(Self {
            kinds: vec![
                ("command", pattern(r"cargo xtask ([a-z][a-z-]*)"), xtask_commands(root)?),
                ("method", pattern(r"--method[ =]([a-z][a-z0-9_]*)"), methods),
                ("card", pattern(r"--vga[ =]([a-z][a-z0-9-]*)"), cards),
                ("test suite", pattern(r"--test[ =]([a-z][a-z0-9_]*)"), test_suites(root)),
                ("variable", pattern(r"(POLYLAB_[A-Z0-9_]*[A-Z0-9])"), variables_read(root)?),
            ],
        })
    }

    /// The names `text` uses that are not there: kind, line and name.
    fn unknown(&self, text: &str) -> Vec<(&'static str, usize, String)> {
        let mut unknown = Vec::new();
        for (number, line) in text.lines().enumerate() {
            for (kind, pattern, known) in &self.kinds {
                for found in pattern.captures_iter(line) {
                    if !known.iter().any(|name| name == &found[1]) {
                        unknown.push((*kind, number + 1, found[1].to_string()));
                    }
                }
            }
        }
        unknown
    }
}

#[test]
fn every_command_method_card_suite_and_variable_named_is_real() -> Result<()> {
    let root = workspace::root();
    let names = Names::of(root)?;
    for (kind, _, known) in &names.kinds {
        assert!(!known.is_empty(), "no {kind} found to hold the docs to");
    }
    let mut unknown = Vec::new();
    for file in sources(root).into_iter().filter(|file| !file.ends_with(file!())) {
        let text = std::fs::read_to_string(&file).with_context(|| format!("failed to read {}", file.display()))?;
        let shown = file.strip_prefix(root).unwrap_or(&file).display().to_string();
        for (kind, line, name) in names.unknown(&text) {
            unknown.push(format!("{shown}:{line} names the {kind} {name}, which there is not"));
        }
    }
    assert!(unknown.is_empty(), "{} unknown names:\n{}", unknown.len(), unknown.join("\n"));
    Ok(())
}

#[test]
fn a_wrong_command_method_card_suite_or_variable_is_caught() -> Result<()> {
    let names = Names::of(workspace::root())?;
    let right = "cargo xtask run --method exact --vga cirrus; cargo xtask test -- --test pages; POLYLAB_OVMF_CODE\n\
                 cargo xtask kbench --serial X; cargo test -p raster --test exact_golden; --method M --vga CARD";
    assert_eq!(names.unknown(right), []);
    let wrong = "cargo xtask runn --method exakt --vga cga\ncargo xtask test -- --test pagez; POLYLAB_OVMF_CODES";
    assert_eq!(
        names.unknown(wrong),
        [
            ("command", 1, "runn".to_string()),
            ("method", 1, "exakt".to_string()),
            ("card", 1, "cga".to_string()),
            ("test suite", 2, "pagez".to_string()),
            ("variable", 2, "POLYLAB_OVMF_CODES".to_string()),
        ]
    );
    Ok(())
}

#[test]
fn every_variable_the_code_reads_is_in_the_docs() -> Result<()> {
    let root = workspace::root();
    let docs: String = sources(root)
        .into_iter()
        .filter(|file| file.extension().is_some_and(|e| e == "md"))
        .filter_map(|page| std::fs::read_to_string(page).ok())
        .collect();
    let read = variables_read(root)?;
    assert!(read.iter().any(|name| name == "POLYLAB_IMAGE"), "the variables were not found: {read:?}");
    // Whole names, as the docs spell them: `POLYLAB_OVMF_CODE` documents
    // that variable, not a `POLYLAB_OVMF` the code might read.
    let name = Regex::new(r"POLYLAB_[A-Z0-9_]*[A-Z0-9]").expect("a valid pattern");
    let documented: BTreeSet<&str> = name.find_iter(&docs).map(|found| found.as_str()).collect();
    let undocumented: Vec<&String> = read.iter().filter(|name| !documented.contains(name.as_str())).collect();
    assert!(undocumented.is_empty(), "variables the code reads and no page names: {undocumented:?}");
    Ok(())
}

/// The backticked words of the text from the start of the line where
/// `start` first stands to the end of the first `end` after it, or `None`
/// where either is not there.
fn quoted_between(text: &str, start: &str, end: &str) -> Option<Vec<String>> {
    let from = text[..text.find(start)?].rfind('\n').map_or(0, |newline| newline + 1);
    let to = from + text[from..].find(end)? + end.len();
    let quoted = Regex::new(r"`([^`]+)`").expect("a valid pattern");
    Some(quoted.captures_iter(&text[from..to]).map(|found| found[1].to_string()).collect())
}

/// The kernel's modules that have `unsafe` code (a block, a function, an
/// impl or a trait), by their paths from the crate's root (`video::screen`
/// for `video/screen.rs`, `video` for `video/mod.rs`).
fn modules_with_unsafe(kernel_src: &Path) -> Result<Vec<String>> {
    let unsafe_code = Regex::new(r"\bunsafe\s*(\{|fn\b|impl\b|trait\b|extern\b)").expect("a valid pattern");
    let mut modules = Vec::new();
    for file in sources(kernel_src).into_iter().filter(|file| file.extension().is_some_and(|e| e == "rs")) {
        let text = std::fs::read_to_string(&file).with_context(|| format!("failed to read {}", file.display()))?;
        let code = text.lines().map(|line| line.split("//").next().unwrap_or("")).collect::<Vec<_>>().join("\n");
        let relative = file.strip_prefix(kernel_src).expect("under kernel/src").with_extension("");
        let mut names: Vec<String> =
            relative.components().map(|part| part.as_os_str().to_string_lossy().into_owned()).collect();
        if names.last().is_some_and(|name| name == "mod") {
            names.pop();
        }
        let module = names.join("::");
        if unsafe_code.is_match(&code) && module != "main" && !modules.contains(&module) {
            modules.push(module);
        }
    }
    modules.sort();
    Ok(modules)
}

/// The modules `main.rs`'s paragraph on `unsafe` names: its backticked
/// words that are paths of modules of `kernel_src` (`time::clock`).
fn modules_listed(kernel_src: &Path, main_rs: &str) -> Option<Vec<String>> {
    let quoted =
        quoted_between(main_rs, "`unsafe` code lives in these modules alone", "Everything above them is safe")?;
    let mut modules: Vec<String> = quoted
        .into_iter()
        .filter(|word| {
            let file = kernel_src.join(word.replace("::", "/"));
            file.with_extension("rs").is_file() || file.join("mod.rs").is_file()
        })
        .collect();
    modules.sort();
    modules.dedup();
    Some(modules)
}

#[test]
fn the_kernel_lists_every_module_with_unsafe_code_and_no_other() -> Result<()> {
    let kernel_src = workspace::root().join("kernel/src");
    let main_rs = std::fs::read_to_string(kernel_src.join("main.rs")).context("failed to read kernel/src/main.rs")?;
    let listed = modules_listed(&kernel_src, &main_rs).context("kernel/src/main.rs has no paragraph on `unsafe`")?;
    let found = modules_with_unsafe(&kernel_src)?;
    assert!(found.iter().any(|module| module == "platform::port"), "no unsafe code found: {found:?}");
    assert_eq!(listed, found, "kernel/src/main.rs lists these modules as having `unsafe` code; the code has");
    Ok(())
}

#[test]
fn a_module_with_unsafe_code_left_off_the_list_is_caught() {
    let kernel_src = workspace::root().join("kernel/src");
    let text = "//! `unsafe` code lives in these modules alone, each block with a\n\
                //! `// SAFETY:` note: `platform::port`, `video` and `nowhere`;\n\
                //! `time::clock`'s one RDTSC. Everything above them is safe\n//! code.\n//! `platform::heap`";
    assert_eq!(
        modules_listed(&kernel_src, text),
        Some(vec!["platform::port".to_string(), "time::clock".to_string(), "video".to_string()])
    );
    assert_eq!(modules_listed(&kernel_src, "//! no such paragraph"), None);
}

/// The files of `folder` (recursively) that the words `quoted` do not
/// name, and the `.rs` words that name no file there: a word is a path
/// from the root, or a file's name, which names every file of that name
/// in the folder.
fn reading_order_gaps(root: &Path, folder: &Path, quoted: &[String]) -> (Vec<String>, Vec<String>) {
    let files: Vec<PathBuf> =
        sources(folder).into_iter().filter(|f| f.extension().is_some_and(|e| e == "rs")).collect();
    let names = |file: &Path, word: &str| {
        root.join(word) == file || file.file_name().is_some_and(|name| name.to_string_lossy() == word)
    };
    let rust: Vec<&String> = quoted.iter().filter(|word| word.ends_with(".rs")).collect();
    let unnamed = files
        .iter()
        .filter(|file| !rust.iter().any(|word| names(file, word)))
        .map(|file| file.strip_prefix(root).unwrap_or(file).display().to_string())
        .collect();
    let strays = rust
        .iter()
        .filter(|word| !files.iter().any(|file| names(file, word)) && !root.join(word).is_file())
        .map(|word| word.to_string())
        .collect();
    (unnamed, strays)
}

#[test]
fn the_reading_order_of_exact_names_every_file_of_its_folder() -> Result<()> {
    let root = workspace::root();
    let page = std::fs::read_to_string(root.join("docs/development.md")).context("failed to read development.md")?;
    let quoted = quoted_between(&page, "**`exact`, one polygon at a time.**", "holds this list to the folder")
        .context("docs/development.md has no reading order for `exact`")?;
    let (unnamed, strays) = reading_order_gaps(root, &root.join("kernel/raster/src/methods/exact"), &quoted);
    assert!(unnamed.is_empty(), "exact's reading order in docs/development.md leaves out {unnamed:?}");
    assert!(strays.is_empty(), "exact's reading order in docs/development.md names {strays:?}, not files of exact");
    assert!(quoted.iter().any(|word| word == "kernel/raster/src/classify.rs"), "the reading order skips classify.rs");
    Ok(())
}

#[test]
fn a_file_of_exact_left_out_of_the_reading_order_is_caught() {
    let root = workspace::root();
    let folder = root.join("kernel/raster/src/methods/exact");
    let mut quoted: Vec<String> = [
        "kernel/raster/src/methods/exact/mod.rs",
        "bounds.rs",
        "clip.rs",
        "edge.rs",
        "monotone.rs",
        "spans.rs",
        "gone.rs",
    ]
    .map(String::from)
    .to_vec();
    quoted.extend(
        ["mod.rs", "lent.rs", "scratch.rs", "fixed.rs", "build.rs", "walk.rs", "order.rs", "runs.rs", "columns.rs"]
            .map(String::from),
    );
    quoted.extend(["grid.rs", "scatter.rs", "scan.rs"].map(String::from));
    let (unnamed, strays) = reading_order_gaps(root, &folder, &quoted);
    assert_eq!(unnamed, ["kernel/raster/src/methods/exact/active_edges/tables.rs"]);
    assert_eq!(strays, ["gone.rs"]);
}

/// The members of `[workspace]` in the root `Cargo.toml` under `key`.
fn workspace_list(manifest: &str, key: &str) -> Option<Vec<String>> {
    let list = Regex::new(&format!(r"(?m)^{key}\s*=\s*\[([^\]]*)\]")).expect("a valid pattern");
    let entry = Regex::new(r#""([^"]+)""#).expect("a valid pattern");
    let found = list.captures(manifest)?;
    let mut members: Vec<String> = entry.captures_iter(&found[1]).map(|e| e[1].to_string()).collect();
    members.sort();
    Some(members)
}

#[test]
fn the_host_crates_development_md_names_are_the_default_members() -> Result<()> {
    let root = workspace::root();
    let manifest = std::fs::read_to_string(root.join("Cargo.toml")).context("failed to read Cargo.toml")?;
    let default_members = workspace_list(&manifest, "default-members").context("Cargo.toml has no default-members")?;
    let page = std::fs::read_to_string(root.join("docs/development.md")).context("failed to read development.md")?;
    let mut named = quoted_between(&page, "**Two toolchains.** The host crates", "build on stable Rust")
        .context("docs/development.md does not list the host crates")?;
    named.sort();
    assert_eq!(named, default_members, "docs/development.md's host crates against Cargo.toml's default-members");
    Ok(())
}

#[test]
fn a_host_crate_left_out_of_the_list_is_caught() {
    let manifest = "[workspace]\nmembers = [\"kernel\", \"a\", \"b\"]\ndefault-members = [\"b\", \"a\"]\n";
    assert_eq!(workspace_list(manifest, "default-members"), Some(vec!["a".to_string(), "b".to_string()]));
    let page = "- **Two toolchains.** The host crates, the workspace's default members\n  (`a`), build on stable Rust.";
    assert_eq!(
        quoted_between(page, "**Two toolchains.** The host crates", "build on stable Rust"),
        Some(vec!["a".into()])
    );
}
