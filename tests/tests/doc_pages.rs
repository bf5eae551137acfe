//! No docs page is over 600 lines (docs/development.md's rule): the
//! README and every page of `docs/`, their lines counted as `wc -l` counts
//! them. A page that grows past it is split by concern, its history left
//! to the commit messages or a dated page of its own.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use harness::workspace;

/// The most lines a page may have.
const MOST: usize = 600;

/// The README and the Markdown pages of `docs/`.
fn pages(root: &Path) -> Result<Vec<PathBuf>> {
    let docs = std::fs::read_dir(root.join("docs")).context("failed to list docs/")?;
    let mut pages = vec![root.join("README.md")];
    for entry in docs {
        let path = entry.context("failed to list docs/")?.path();
        if path.extension().is_some_and(|e| e == "md") {
            pages.push(path);
        }
    }
    pages.sort();
    Ok(pages)
}

/// The pages of `texts` (name and text) over [`MOST`] lines, with their
/// lines.
fn too_long(texts: &[(String, String)]) -> Vec<String> {
    texts
        .iter()
        .map(|(name, text)| (name, text.lines().count()))
        .filter(|&(_, lines)| lines > MOST)
        .map(|(name, lines)| format!("{name}: {lines} lines"))
        .collect()
}

#[test]
fn no_docs_page_is_over_600_lines() -> Result<()> {
    let root = workspace::root();
    let pages = pages(root)?;
    assert!(pages.iter().any(|page| page.ends_with("docs/lab.md")), "the docs were not read: {pages:?}");
    let mut texts = Vec::new();
    for page in pages {
        let text = std::fs::read_to_string(&page).with_context(|| format!("failed to read {}", page.display()))?;
        texts.push((page.strip_prefix(root).unwrap_or(&page).display().to_string(), text));
    }
    let long = too_long(&texts);
    assert!(long.is_empty(), "docs pages over {MOST} lines:\n{}", long.join("\n"));
    Ok(())
}

#[test]
fn a_page_of_601_lines_is_caught_and_one_of_600_is_not() {
    let texts = [("full.md".to_string(), "line\n".repeat(600)), ("over.md".to_string(), "line\n".repeat(601))];
    assert_eq!(too_long(&texts), ["over.md: 601 lines"]);
}
