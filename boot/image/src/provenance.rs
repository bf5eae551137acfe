//! Which sources an image was built from: a digest of everything the build
//! reads from the tree, written beside every image the build makes, so that
//! an image named by [`IMAGE_ENV`] is used only if it is
//! this tree's build (`cargo xtask test` builds one and hands it to the
//! tests that way), or if the user says, with [`MEANT_ENV`], that another
//! image is meant. Without that, a variable left exported from an earlier
//! session would have every QEMU test judge an old kernel, saying so only
//! on a standard error the test harness captures.

use std::ffi::OsString;
use std::path::{Path, PathBuf};

use anyhow::{bail, ensure, Context, Result};
use sha2::{Digest, Sha256};

use install::workspace;

/// Names a prebuilt image to use instead of building one (`cargo xtask
/// test` builds once and hands it to every test binary this way). A
/// relative path is taken from the workspace root, since test binaries run
/// in their package's directory.
pub const IMAGE_ENV: &str = "POLYLAB_IMAGE";

/// Set to `1`: the image [`IMAGE_ENV`] names is meant,
/// whatever it was built from (an image of another build, made by hand to
/// test the tests, as docs/boot.md's unpatched stage 2).
pub const MEANT_ENV: &str = "POLYLAB_IMAGE_MEANT";

/// What the image build reads from the tree: the kernel's crates, the image
/// build and writer, and the manifests and lock file that pick the crates.
const INPUTS: [&str; 5] = ["kernel", "boot", "Cargo.toml", "Cargo.lock", ".cargo/config.toml"];

/// The SHA-256 of every file of [`INPUTS`] under `root`, by path and
/// contents, in path order (`target` folders left out), as hex.
pub fn sources_digest(root: &Path) -> Result<String> {
    let mut files = Vec::new();
    for input in INPUTS {
        collect_files(&root.join(input), &mut files)?;
    }
    files.sort();
    let mut digest = Sha256::new();
    for file in files {
        let relative = file.strip_prefix(root).unwrap_or(&file);
        let bytes = std::fs::read(&file).with_context(|| format!("failed to read {}", file.display()))?;
        digest.update(relative.to_string_lossy().as_bytes());
        digest.update([0]);
        digest.update((bytes.len() as u64).to_le_bytes());
        digest.update(&bytes);
    }
    Ok(digest.finalize().iter().map(|byte| format!("{byte:02x}")).collect())
}

fn collect_files(path: &Path, files: &mut Vec<PathBuf>) -> Result<()> {
    if path.is_file() {
        files.push(path.to_path_buf());
    } else if path.is_dir() && path.file_name().is_none_or(|name| name != "target") {
        for entry in std::fs::read_dir(path).with_context(|| format!("failed to list {}", path.display()))? {
            collect_files(&entry?.path(), files)?;
        }
    }
    Ok(())
}

/// Where the digest of `image`'s sources is kept: beside it.
fn record_of(image: &Path) -> PathBuf {
    let mut name = image.as_os_str().to_owned();
    name.push(".sources");
    PathBuf::from(name)
}

/// Writes, beside `image` just built, the digest of the sources it was
/// built from, `digest` (taken before the build, so that an edit during
/// it makes the image count as another tree's).
pub fn record(image: &Path, digest: &str) -> Result<()> {
    let record = record_of(image);
    std::fs::write(&record, digest).with_context(|| format!("failed to write {}", record.display()))
}

/// The image `named` by [`IMAGE_ENV`] (relative to the workspace root,
/// since test binaries run in their package's folder), if one is: it
/// must be a file, and built from the tree as it is now (its record holds
/// this tree's digest) unless `meant` (the value of [`MEANT_ENV`]) is `1`.
pub fn image_given(named: Option<OsString>, meant: Option<OsString>) -> Result<Option<PathBuf>> {
    let Some(named) = named else { return Ok(None) };
    let image = workspace::root().join(named);
    ensure!(image.is_file(), "{IMAGE_ENV} names {}, which is not a file", image.display());
    if meant.is_some_and(|meant| meant == "1") {
        eprintln!("image: using {} as {MEANT_ENV} says, whatever it was built from", image.display());
        return Ok(Some(image));
    }
    let recorded = std::fs::read_to_string(record_of(&image)).ok();
    let digest = sources_digest(workspace::root())?;
    if recorded.as_deref() != Some(digest.as_str()) {
        let why = match recorded {
            None => "has no record of the sources it was built from (it was not made by this build)",
            Some(_) => "was built from other sources than the tree's as they are now",
        };
        bail!(
            "{IMAGE_ENV} names {}, which {why}: the tests would judge another kernel. Unset {IMAGE_ENV} to \
             build this tree's image, or set {MEANT_ENV}=1 if that image is meant",
            image.display(),
        );
    }
    eprintln!("image: using {}, this tree's build, from {IMAGE_ENV}", image.display());
    Ok(Some(image))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A tree of the inputs, with one kernel file of `text`, and a build
    /// folder.
    fn tree(text: &str) -> tempfile::TempDir {
        let root = tempfile::tempdir().unwrap();
        let (sources, built) = (root.path().join("kernel").join("src"), root.path().join("kernel").join("target"));
        std::fs::create_dir_all(&sources).unwrap();
        std::fs::create_dir_all(&built).unwrap();
        std::fs::write(sources.join("main.rs"), text).unwrap();
        std::fs::write(built.join("built"), "anything").unwrap();
        std::fs::write(root.path().join("Cargo.lock"), "lock").unwrap();
        root
    }

    #[test]
    fn the_inputs_hold_every_package_the_image_is_built_from_and_the_image_builds_own_code() {
        let root = workspace::root();
        let mut metadata = std::process::Command::new(std::env::var("CARGO").unwrap_or_else(|_| "cargo".into()));
        metadata.args(["metadata", "--no-deps", "--offline", "--format-version", "1"]).current_dir(root);
        let metadata: serde_json::Value = serde_json::from_str(&install::output_of(&mut metadata).unwrap()).unwrap();
        let packages = metadata["packages"].as_array().unwrap();
        let folder_of =
            |manifest: &serde_json::Value| PathBuf::from(manifest.as_str().unwrap()).parent().unwrap().to_path_buf();
        // The kernel and the image writer, which the image holds; this
        // crate, whose loader edits (`loader/`) and patched copy make the
        // UEFI loader; and every package of the tree they depend on.
        let mut folders: Vec<PathBuf> = Vec::new();
        let mut names: Vec<String> = [crate::cargo::NIGHTLY_ONLY.as_slice(), &["boot-image"]]
            .concat()
            .iter()
            .map(|name| name.to_string())
            .collect();
        while let Some(name) = names.pop() {
            let package = packages.iter().find(|package| package["name"] == name.as_str()).unwrap();
            let folder = folder_of(&package["manifest_path"]);
            if folders.contains(&folder) {
                continue;
            }
            folders.push(folder);
            for dependency in package["dependencies"].as_array().unwrap() {
                if dependency["path"].is_string() {
                    names.push(dependency["name"].as_str().unwrap().to_string());
                }
            }
        }
        assert!(folders.len() >= 4, "{folders:?}");
        for folder in folders {
            let relative = folder.strip_prefix(root).unwrap();
            assert!(
                INPUTS.iter().any(|input| relative.starts_with(input)),
                "{} goes into the image or makes its loader, and no input of the digest holds it: an image built before a change \
                 there would pass as this tree's",
                relative.display()
            );
        }
    }

    #[test]
    fn the_digest_follows_the_sources_and_nothing_else() {
        let (a, b, also_a) = (tree("fn main() {}"), tree("fn main() { }"), tree("fn main() {}"));
        let digest = |root: &tempfile::TempDir| sources_digest(root.path()).unwrap();
        assert_eq!(digest(&a), digest(&also_a));
        assert_ne!(digest(&a), digest(&b));
        let kernel = also_a.path().join("kernel");
        std::fs::write(kernel.join("target").join("built"), "else").unwrap();
        std::fs::write(also_a.path().join("README.md"), "not an input").unwrap();
        assert_eq!(digest(&a), digest(&also_a), "a build folder or a file outside the inputs changed it");
        std::fs::rename(kernel.join("src").join("main.rs"), kernel.join("src").join("other.rs")).unwrap();
        assert_ne!(digest(&a), digest(&also_a), "a file renamed left it as it was");
    }

    #[test]
    fn an_image_without_this_trees_record_is_refused_unless_meant() {
        let dir = tempfile::tempdir().unwrap();
        let image = dir.path().join("old.img");
        std::fs::write(&image, "an image").unwrap();
        let given = |meant: Option<&str>| image_given(Some(image.clone().into()), meant.map(OsString::from));
        let error = format!("{:#}", given(None).unwrap_err());
        assert!(error.contains("has no record of the sources"), "{error}");
        assert!(error.contains("POLYLAB_IMAGE_MEANT=1"), "{error}");
        record(&image, "0123").unwrap();
        let error = format!("{:#}", given(Some("0")).unwrap_err());
        assert!(error.contains("was built from other sources"), "{error}");
        assert_eq!(given(Some("1")).unwrap(), Some(image.clone()));
        record(&image, &sources_digest(workspace::root()).unwrap()).unwrap();
        assert_eq!(given(None).unwrap(), Some(image.clone()));
        assert_eq!(image_given(None, None).unwrap(), None);
        let missing = format!("{:#}", image_given(Some(dir.path().join("none.img").into()), None).unwrap_err());
        assert!(missing.ends_with("which is not a file"), "{missing}");
    }
}
