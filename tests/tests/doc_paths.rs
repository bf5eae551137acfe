//! Every repository path the docs and the code's comments name exists, and
//! every link between the Markdown pages leads to a file and a heading that
//! are there: a file or section that moved or went away leaves no citation
//! behind.
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
