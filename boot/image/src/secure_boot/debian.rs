//! Debian's signed shim and MokManager, and its `sbsign`, taken from
//! Debian's packages without installing them: `apt-get download` (which
//! checks each package against the archive's signed index, and needs no
//! root) and `dpkg-deb -x` into a folder under `target/`.
//!
//! Never built by us: shim is what Microsoft signed, and taking Debian's
//! current package (not a pinned one) is what keeps it up to date with
//! the SBAT revocations that retire old shims. So the lists apt downloads
//! from are the build's own ([`PrivateApt`], over the machine's sources),
//! fetched before the first download and again once a day: a machine's
//! own lists can be months old (or, in a container image, absent) and
//! name a shim Debian has long replaced. When the archive's version of a
//! package differs from the one unpacked, the new one is downloaded and
//! unpacked in its place; offline, the unpacked one is used, with a
//! warning.

use std::path::{Path, PathBuf};
use std::process::Command;

use anyhow::{bail, ensure, Context, Result};

use install::apt::PrivateApt;
use install::process::{find_in_path, run_streaming};

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

/// Held while the archive is asked for a package and it is unpacked.
static FETCHING: std::sync::Mutex<()> = std::sync::Mutex::new(());

/// The unpacked packages.
pub struct Unpacked {
    dir: PathBuf,
    /// Whether they follow Debian's archive (downloaded, and replaced when
    /// it has another version), or were given ([`Unpacked::given`]).
    from_archive: bool,
}

impl Unpacked {
    /// The packages of Debian's archive, unpacked in `dir`.
    pub fn in_dir(dir: PathBuf) -> Self {
        Self { dir, from_archive: true }
    }

    /// Packages given as `.deb` files ([`Unpacked::unpack_deb`]), unpacked
    /// in `dir`, never replaced by the archive's (a test builds an image
    /// around an older shim this way).
    pub fn given(dir: PathBuf) -> Self {
        Self { dir, from_archive: false }
    }

    /// The path of `file`, downloading and unpacking its package first if
    /// it is not there yet or the archive has another version now.
    pub fn get(&self, file: DebianFile) -> Result<PathBuf> {
        let root = self.dir.join(file.package);
        if self.from_archive {
            // Tests ask for files side by side (sbsign and sbattach share
            // a package): one asks apt and unpacks at a time, and the
            // others find its work done.
            let _one_at_a_time = FETCHING.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
            let unpacked = if root.is_dir() { self.version(file.package).ok() } else { None };
            match refresh_for(file.package, unpacked.as_deref(), self.archive_version(file.package))? {
                Refresh::Keep => {}
                Refresh::Fetch => self.unpack(file.package)?,
                Refresh::KeepWarning(warning) => eprintln!("image: warning: {warning}"),
            }
        }
        let path = root.join(file.path);
        ensure!(path.is_file(), "Debian's {} has no /{} (unpacked in {})", file.package, file.path, root.display());
        Ok(path)
    }

    /// Whether shim and MokManager can be had: they were given, apt-get is
    /// there to download them, or they were unpacked before.
    pub fn obtainable(&self) -> bool {
        !self.from_archive
            || find_in_path("apt-get").is_some()
            || [SHIM, MOK_MANAGER].iter().all(|file| self.dir.join(file.package).is_dir())
    }

    /// The package's version, as `apt-get download` named its file.
    pub fn version(&self, package: &str) -> Result<String> {
        let name = self.dir.join(format!("{package}.deb-name"));
        let deb = std::fs::read_to_string(&name).with_context(|| format!("failed to read {}", name.display()))?;
        deb_version(package, &deb).with_context(|| format!("{} names no version of {package}", name.display()))
    }

    /// apt over the machine's sources with the build's own lists.
    fn apt(&self) -> PrivateApt {
        PrivateApt::machines_sources(self.dir.join("apt"))
    }

    /// The version of `package` Debian's archive has now, from lists at
    /// most a day old.
    fn archive_version(&self, package: &str) -> Result<String> {
        let apt = self.apt();
        apt.refresh().context("failed to fetch apt's package lists for the image's Secure Boot files")?;
        apt.candidate(package)?.with_context(|| {
            format!(
                "the image takes shim, MokManager and sbsign from Debian's packages, and apt's lists (sources: the \
                 machine's, lists in {}) have no {package}",
                self.dir.join("apt").display()
            )
        })
    }

    fn unpack(&self, package: &str) -> Result<()> {
        let downloads = self.dir.join("downloads");
        if downloads.exists() {
            std::fs::remove_dir_all(&downloads).with_context(|| format!("failed to remove {}", downloads.display()))?;
        }
        std::fs::create_dir_all(&downloads).with_context(|| format!("failed to create {}", downloads.display()))?;
        eprintln!("image: fetching Debian's {package} (apt-get download, no root needed)");
        let mut download = self.apt().command("apt-get");
        download.args(["download", package]).current_dir(&downloads);
        run_streaming(&mut download).context(format!("apt-get could not download {package}"))?;
        self.unpack_deb(package, &newest_deb(&downloads, package)?)
    }

    /// Unpacks `deb`, a `.deb` of `package` named as `apt-get download`
    /// names it, where [`Self::get`] finds it, in place of any unpacked
    /// before.
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
        if root.exists() {
            std::fs::remove_dir_all(&root).with_context(|| format!("failed to remove {}", root.display()))?;
        }
        std::fs::rename(&scratch, &root)
            .with_context(|| format!("failed to move {} to {}", scratch.display(), root.display()))
    }
}

/// What to do with an unpacked package.
#[derive(Debug, PartialEq, Eq)]
enum Refresh {
    Keep,
    /// Download and unpack the archive's version.
    Fetch,
    /// Keep it, though the archive could not be asked: why.
    KeepWarning(String),
}

/// What to do with `package`, `unpacked` at that version (or not
/// unpacked), when the archive has `archive` (or could not be asked).
fn refresh_for(package: &str, unpacked: Option<&str>, archive: Result<String>) -> Result<Refresh> {
    match (unpacked, archive) {
        (Some(unpacked), Ok(archive)) if unpacked == archive => Ok(Refresh::Keep),
        (Some(unpacked), Ok(archive)) => {
            eprintln!("image: Debian's archive has {package} {archive} now (unpacked: {unpacked}); fetching it");
            Ok(Refresh::Fetch)
        }
        (None, Ok(_)) => Ok(Refresh::Fetch),
        (Some(unpacked), Err(error)) => Ok(Refresh::KeepWarning(format!(
            "cannot ask Debian's archive for the current {package} ({error:#}); using the unpacked {unpacked}"
        ))),
        (None, Err(error)) => Err(error),
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
    fn a_package_is_fetched_when_missing_or_when_the_archive_has_another_version() {
        let archive = |version: &str| Ok(version.to_string());
        assert_eq!(refresh_for("shim-signed", None, archive("16.1")).unwrap(), Refresh::Fetch);
        assert_eq!(refresh_for("shim-signed", Some("16.1"), archive("16.1")).unwrap(), Refresh::Keep);
        assert_eq!(refresh_for("shim-signed", Some("15.8"), archive("16.1")).unwrap(), Refresh::Fetch);
        let offline = || Err(anyhow::anyhow!("no network"));
        let Refresh::KeepWarning(warning) = refresh_for("shim-signed", Some("16.1"), offline()).unwrap() else {
            panic!("offline, the unpacked package is kept");
        };
        assert!(warning.contains("(no network); using the unpacked 16.1"), "{warning}");
        let error = refresh_for("shim-signed", None, offline()).unwrap_err();
        assert_eq!(error.to_string(), "no network");
    }

    #[test]
    fn the_unpacked_version_is_read_from_the_downloads_name() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("shim-signed.deb-name"), "shim-signed_16.1_amd64.deb").unwrap();
        let unpacked = Unpacked::in_dir(dir.path().to_path_buf());
        assert_eq!(unpacked.version("shim-signed").unwrap(), "16.1");
    }
}
