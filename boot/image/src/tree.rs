//! Two folders compared file by file: what the patched bootloader's copy
//! holds against what its pinned sources and edits make.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result};

/// What a path is, for the comparison: a file's bytes, or a folder.
#[derive(Debug, PartialEq, Eq)]
enum Entry {
    File(Vec<u8>),
    Folder,
    /// A symbolic link (never in a crate archive) or another kind.
    Other,
}

/// Every difference between `expected` and `actual`, as `changed PATH`,
/// `added PATH` (only in `actual`) or `missing PATH`, in path order;
/// `ignored` names top-level entries of `actual` left out.
pub fn differences(expected: &Path, actual: &Path, ignored: &[&str]) -> Result<Vec<String>> {
    let expected = entries(expected, &[])?;
    let actual = entries(actual, ignored)?;
    let mut found = Vec::new();
    for (path, entry) in &expected {
        match actual.get(path) {
            None => found.push(format!("missing {}", path.display())),
            Some(other) if other != entry => found.push(format!("changed {}", path.display())),
            Some(_) => {}
        }
    }
    for path in actual.keys().filter(|path| !expected.contains_key(*path)) {
        found.push(format!("added {}", path.display()));
    }
    found.sort();
    Ok(found)
}

/// Every entry under `root`, by its path relative to `root`, without the
/// top-level entries named in `ignored` and what is under them.
fn entries(root: &Path, ignored: &[&str]) -> Result<BTreeMap<PathBuf, Entry>> {
    let mut found = BTreeMap::new();
    let mut folders = vec![PathBuf::new()];
    while let Some(folder) = folders.pop() {
        let path = root.join(&folder);
        for item in std::fs::read_dir(&path).with_context(|| format!("failed to list {}", path.display()))? {
            let item = item.with_context(|| format!("failed to list {}", path.display()))?;
            let relative = folder.join(item.file_name());
            if folder.as_os_str().is_empty() && ignored.iter().any(|name| item.file_name() == **name) {
                continue;
            }
            let kind = item.file_type().with_context(|| format!("failed to read {}", item.path().display()))?;
            let entry = if kind.is_dir() {
                folders.push(relative.clone());
                Entry::Folder
            } else if kind.is_file() {
                Entry::File(
                    std::fs::read(item.path()).with_context(|| format!("failed to read {}", item.path().display()))?,
                )
            } else {
                Entry::Other
            };
            found.insert(relative, entry);
        }
    }
    Ok(found)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn write(root: &Path, path: &str, contents: &str) {
        let path = root.join(path);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, contents).unwrap();
    }

    #[test]
    fn a_changed_an_added_and_a_missing_file_are_named_and_the_ignored_folder_is_not() {
        let (expected, actual) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
        for root in [expected.path(), actual.path()] {
            write(root, "uefi/src/main.rs", "fn main() {}\n");
            write(root, "uefi/Cargo.toml", "[package]\n");
            std::fs::create_dir_all(root.join("common")).unwrap();
        }
        assert_eq!(differences(expected.path(), actual.path(), &[]).unwrap(), Vec::<String>::new());
        write(actual.path(), "uefi/src/main.rs", "fn main() { boot_anything() }\n");
        write(actual.path(), "uefi/build.rs", "fn main() {}\n");
        write(actual.path(), "target/uefi_target/loader.efi", "MZ");
        std::fs::remove_file(actual.path().join("uefi/Cargo.toml")).unwrap();
        std::fs::remove_dir(actual.path().join("common")).unwrap();
        assert_eq!(
            differences(expected.path(), actual.path(), &["target"]).unwrap(),
            ["added uefi/build.rs", "changed uefi/src/main.rs", "missing common", "missing uefi/Cargo.toml"]
        );
        let with_target = differences(expected.path(), actual.path(), &[]).unwrap();
        assert!(with_target.contains(&"added target/uefi_target/loader.efi".to_string()), "{with_target:?}");
    }
}
