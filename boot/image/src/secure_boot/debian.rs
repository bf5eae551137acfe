//! Debian's signed shim and MokManager, and its `sbsign`, taken from
//! Debian's packages without installing them: `apt-get download` (which
//! checks each package against the archive's signed index, and needs no
//! root) and `dpkg-deb -x` into a folder under `target/`, once; later
//! builds use the unpacked files, offline.
//!
//! Never built by us: shim is what Microsoft signed, and taking Debian's
//! current package (not a pinned one) is what keeps it up to date with
//! the SBAT revocations that retire old shims.

use std::path::{Path, PathBuf};
use std::process::Command;

use anyhow::{bail, ensure, Context, Result};

use crate::process::run_streaming;

/// One Debian package and the file the build takes from it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DebianFile {
    pub package: &'static str,
    /// The file's path inside the package.
    pub path: &'static str,
}

/// shim, signed by Microsoft's UEFI CA (package `shim-signed`).
pub const SHIM: DebianFile = DebianFile { package: "shim-signed", path: "usr/lib/shim/shimx64.efi.signed" };
/// MokManager, signed by Debian's key that shim carries.
pub const MOK_MANAGER: DebianFile =
    DebianFile { package: "shim-helpers-amd64-signed", path: "usr/lib/shim/mmx64.efi.signed" };
/// The signing tool, and the tool that strips a signature (the tests use it).
pub const SBSIGN: DebianFile = DebianFile { package: "sbsigntool", path: "usr/bin/sbsign" };
pub const SBATTACH: DebianFile = DebianFile { package: "sbsigntool", path: "usr/bin/sbattach" };

/// The unpacked packages.
pub struct Unpacked {
    dir: PathBuf,
}

impl Unpacked {
    /// Where the packages are (or will be) unpacked.
    pub fn in_dir(dir: PathBuf) -> Self {
        Self { dir }
    }

    /// The path of `file`, downloading and unpacking its package first if
    /// it is not there yet.
    pub fn get(&self, file: DebianFile) -> Result<PathBuf> {
        let root = self.dir.join(file.package);
        if !root.is_dir() {
            self.unpack(file.package)?;
        }
        let path = root.join(file.path);
        ensure!(path.is_file(), "Debian's {} has no /{} (unpacked in {})", file.package, file.path, root.display());
        Ok(path)
    }

    /// The package's version, as `apt-get download` named its file.
    pub fn version(&self, package: &str) -> Result<String> {
        let name = self.dir.join(format!("{package}.deb-name"));
        let deb = std::fs::read_to_string(&name).with_context(|| format!("failed to read {}", name.display()))?;
        deb_version(package, &deb).with_context(|| format!("{} names no version of {package}", name.display()))
    }

    fn unpack(&self, package: &str) -> Result<()> {
        let downloads = self.dir.join("downloads");
        std::fs::create_dir_all(&downloads).with_context(|| format!("failed to create {}", downloads.display()))?;
        eprintln!("image: fetching Debian's {package} (apt-get download, no root needed)");
        let mut download = Command::new("apt-get");
        download.args(["download", package]).current_dir(&downloads);
        run_streaming(&mut download).map_err(|error| {
            error.context(format!(
                "the image takes shim, MokManager and sbsign from Debian's packages; apt-get could not download \
                 {package} (on Debian or Ubuntu, `sudo apt-get update` refreshes the package lists)"
            ))
        })?;
        self.unpack_deb(package, &newest_deb(&downloads, package)?)
    }

    /// Unpacks `deb`, a `.deb` of `package` named as `apt-get download`
    /// names it, where [`Self::get`] finds it (a test builds an image from
    /// given packages this way).
    pub fn unpack_deb(&self, package: &str, deb: &Path) -> Result<()> {
        let root = self.dir.join(package);
        let scratch = root.with_extension("partial");
        std::fs::create_dir_all(&self.dir).with_context(|| format!("failed to create {}", self.dir.display()))?;
        if scratch.exists() {
            std::fs::remove_dir_all(&scratch).with_context(|| format!("failed to remove {}", scratch.display()))?;
        }
        run_streaming(Command::new("dpkg-deb").arg("-x").arg(deb).arg(&scratch))?;
        let deb_name = deb.file_name().and_then(|name| name.to_str()).context("a .deb name that is not UTF-8")?;
        let name_file = self.dir.join(format!("{package}.deb-name"));
        std::fs::write(&name_file, deb_name).with_context(|| format!("failed to write {}", name_file.display()))?;
        std::fs::rename(&scratch, &root)
            .with_context(|| format!("failed to move {} to {}", scratch.display(), root.display()))
    }
}

/// The `PACKAGE_VERSION_ARCH.deb` of `package` in `dir` (apt-get download's
/// naming); the last by name if there are several.
fn newest_deb(dir: &Path, package: &str) -> Result<PathBuf> {
    let mut debs: Vec<PathBuf> = std::fs::read_dir(dir)
        .with_context(|| format!("failed to list {}", dir.display()))?
        .filter_map(|entry| entry.ok().map(|entry| entry.path()))
        .filter(|path| {
            path.file_name().and_then(|name| name.to_str()).is_some_and(|name| deb_version(package, name).is_some())
        })
        .collect();
    debs.sort();
    match debs.pop() {
        Some(deb) => Ok(deb),
        None => bail!("apt-get download left no {package}_*.deb in {}", dir.display()),
    }
}

/// The version in `PACKAGE_VERSION_ARCH.deb` (apt-get writes a version's
/// `:` as `%3a`).
fn deb_version(package: &str, file_name: &str) -> Option<String> {
    let rest = file_name.strip_prefix(package)?.strip_prefix('_')?.strip_suffix(".deb")?;
    let (version, _arch) = rest.rsplit_once('_')?;
    Some(version.replace("%3a", ":"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn versions_are_read_from_apt_get_downloads_file_names() {
        assert_eq!(
            deb_version("shim-signed", "shim-signed_1.51~1+deb12u1+16.1-2~deb12u1_amd64.deb").unwrap(),
            "1.51~1+deb12u1+16.1-2~deb12u1"
        );
        assert_eq!(deb_version("sbsigntool", "sbsigntool_0.9.4-3.1_amd64.deb").unwrap(), "0.9.4-3.1");
        assert_eq!(deb_version("qemu", "qemu_1%3a7.2_amd64.deb").unwrap(), "1:7.2");
        assert_eq!(deb_version("shim", "shim-signed_1_amd64.deb"), None, "another package");
        assert_eq!(deb_version("shim-signed", "shim-signed_1_amd64.deb.partial"), None);
    }

    #[test]
    fn the_package_folder_is_used_as_unpacked_without_downloading() {
        let dir = tempfile::tempdir().unwrap();
        let shim = dir.path().join("shim-signed/usr/lib/shim/shimx64.efi.signed");
        std::fs::create_dir_all(shim.parent().unwrap()).unwrap();
        std::fs::write(&shim, b"MZ").unwrap();
        std::fs::write(dir.path().join("shim-signed.deb-name"), "shim-signed_16.1_amd64.deb").unwrap();
        let unpacked = Unpacked::in_dir(dir.path().to_path_buf());
        assert_eq!(unpacked.get(SHIM).unwrap(), shim);
        assert_eq!(unpacked.version("shim-signed").unwrap(), "16.1");
    }
}
