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
//! unpacked in its place; offline, the kept one is used, with a warning.
//! The downloaded `.deb` is kept, and on every use checked against the
//! SHA-256 apt's lists give for it, and the file taken is compared with
//! the `.deb`'s own: an unpacked folder is never trusted as found.

use std::path::{Path, PathBuf};
use std::process::Command;

use anyhow::{bail, ensure, Context, Result};

use install::apt::PrivateApt;
use install::process::{command_line, find_in_path, output_of, run_streaming};

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

/// A `.deb` given by its path and the SHA-256 it must have.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PinnedDeb {
    pub package: &'static str,
    pub deb: PathBuf,
    pub sha256: &'static str,
}

/// Where the `.deb`s come from and what they are checked against.
enum Source {
    /// Debian's archive, through apt (downloaded, and replaced when it
    /// has another version), each `.deb` kept and checked against the
    /// SHA-256 apt's lists give for its version.
    Archive,
    /// Given files, checked against the digests given with them (a test
    /// builds an image around an older shim this way).
    Pinned(Vec<PinnedDeb>),
}

/// The unpacked packages.
pub struct Unpacked {
    dir: PathBuf,
    source: Source,
}

impl Unpacked {
    /// The packages of Debian's archive, unpacked in `dir`.
    pub fn in_dir(dir: PathBuf) -> Self {
        Self { dir, source: Source::Archive }
    }

    /// The packages `debs` give, unpacked in `dir`, never replaced by the
    /// archive's.
    pub fn pinned(dir: PathBuf, debs: Vec<PinnedDeb>) -> Self {
        Self { dir, source: Source::Pinned(debs) }
    }

    /// The path of `file`, its package downloaded and unpacked first if
    /// it is not there yet or the archive has another version now. The
    /// unpacked folder is never trusted as found (anything that runs as
    /// the user could have changed it since, and `sbsign` is handed the
    /// decrypted key): the file must equal the one in the package's
    /// `.deb`, whose SHA-256 is checked first; if it does not, the
    /// package is unpacked again.
    pub fn get(&self, file: DebianFile) -> Result<PathBuf> {
        // Tests ask for files side by side (sbsign and sbattach share a
        // package): one asks apt, checks and unpacks at a time, and the
        // others find its work done.
        let _one_at_a_time = FETCHING.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        let deb = self.checked_deb(file.package)?;
        let expected = file_in_deb(&deb, file.path)?;
        let path = self.dir.join(file.package).join(file.path);
        if std::fs::read(&path).ok().as_ref() != Some(&expected) {
            if path.exists() {
                eprintln!(
                    "image: {} is not the file of Debian's {} it was unpacked from; unpacking the checked \
                     package again",
                    path.display(),
                    file.package
                );
            }
            self.unpack_deb(file.package, &deb)?;
            ensure!(
                std::fs::read(&path).ok().as_ref() == Some(&expected),
                "Debian's {} has no /{} as its package lists it (unpacked in {})",
                file.package,
                file.path,
                self.dir.join(file.package).display()
            );
        }
        Ok(path)
    }

    /// Whether shim and MokManager can be had: they were given, apt-get is
    /// there to download them, or they were fetched before.
    pub fn obtainable(&self) -> bool {
        matches!(self.source, Source::Pinned(_))
            || find_in_path("apt-get").is_some()
            || [SHIM, MOK_MANAGER].iter().all(|file| self.kept_deb(file.package).is_ok_and(|deb| deb.is_file()))
    }

    /// The package's version, as `apt-get download` named its file.
    pub fn version(&self, package: &str) -> Result<String> {
        let name = self.dir.join(format!("{package}.deb-name"));
        let deb = std::fs::read_to_string(&name).with_context(|| format!("failed to read {}", name.display()))?;
        deb_version(package, &deb).with_context(|| format!("{} names no version of {package}", name.display()))
    }

    /// The `.deb` of `package`, its SHA-256 checked: the given one's
    /// against its pin; the archive's, fetched if missing or outdated,
    /// against the SHA-256 apt's lists give for its version.
    fn checked_deb(&self, package: &str) -> Result<PathBuf> {
        let (deb, sha256) = match &self.source {
            Source::Pinned(debs) => {
                let pinned = debs
                    .iter()
                    .find(|pinned| pinned.package == package)
                    .with_context(|| format!("no .deb of {package} was given"))?;
                (pinned.deb.clone(), vec![pinned.sha256.to_string()])
            }
            Source::Archive => {
                let kept = self.kept_deb(package).ok().filter(|deb| deb.is_file());
                let unpacked = kept.as_ref().and_then(|_| self.version(package).ok());
                let deb = match refresh_for(package, unpacked.as_deref(), self.archive_version(package))? {
                    Refresh::Keep => kept.context("a kept package")?,
                    Refresh::Fetch => self.download(package)?,
                    Refresh::KeepWarning(warning) => {
                        eprintln!("image: warning: {warning}");
                        kept.context("a kept package")?
                    }
                };
                let version = self.version(package)?;
                (deb, self.listed_sha256(package, &version)?)
            }
        };
        let bytes = std::fs::read(&deb).with_context(|| format!("failed to read {}", deb.display()))?;
        let found = crate::sources::sha256_hex(&bytes);
        ensure!(
            sha256.contains(&found),
            "{} has SHA-256 {found}, not {} as {}: not the package it claims to be; remove it to have it fetched \
             again",
            deb.display(),
            sha256.join(" or "),
            match self.source {
                Source::Pinned(_) => "pinned",
                Source::Archive => "apt's package lists say",
            }
        );
        Ok(deb)
    }

    /// Where the `.deb` of `package` the last download left is kept.
    fn kept_deb(&self, package: &str) -> Result<PathBuf> {
        let name = std::fs::read_to_string(self.dir.join(format!("{package}.deb-name")))?;
        Ok(self.dir.join("debs").join(package).join(name.trim()))
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

    /// The SHA-256 apt's lists (checked against the archive's signed
    /// index when fetched) give for `package` at `version`.
    fn listed_sha256(&self, package: &str, version: &str) -> Result<Vec<String>> {
        let mut show = self.apt().command("apt-cache");
        show.args(["show", &format!("{package}={version}")]);
        let listed = sha256_in_apt_cache_show(&output_of(&mut show)?);
        ensure!(!listed.is_empty(), "apt's lists give no SHA-256 for {package} {version}");
        Ok(listed)
    }

    /// Downloads `package` into a folder of its own under `debs/`, where
    /// it is kept, and unpacks it; returns the `.deb`.
    fn download(&self, package: &str) -> Result<PathBuf> {
        let downloads = self.dir.join("debs").join(package);
        if downloads.exists() {
            std::fs::remove_dir_all(&downloads).with_context(|| format!("failed to remove {}", downloads.display()))?;
        }
        std::fs::create_dir_all(&downloads).with_context(|| format!("failed to create {}", downloads.display()))?;
        eprintln!("image: fetching Debian's {package} (apt-get download, no root needed)");
        let mut download = self.apt().command("apt-get");
        download.args(["download", package]).current_dir(&downloads);
        run_streaming(&mut download).context(format!("apt-get could not download {package}"))?;
        let deb = newest_deb(&downloads, package)?;
        self.unpack_deb(package, &deb)?;
        Ok(deb)
    }

    /// Unpacks `deb`, a `.deb` of `package` named as `apt-get download`
    /// names it, where [`Self::get`] finds it, in place of any unpacked
    /// before.
    fn unpack_deb(&self, package: &str, deb: &Path) -> Result<()> {
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

/// The bytes of the file at `path` (relative, `usr/bin/sbsign`) in `deb`,
/// read from the package's own data (`dpkg-deb --fsys-tarfile`).
fn file_in_deb(deb: &Path, path: &str) -> Result<Vec<u8>> {
    let tar = output_bytes(Command::new("dpkg-deb").arg("--fsys-tarfile").arg(deb))?;
    let mut archive = tar::Archive::new(tar.as_slice());
    for entry in archive.entries().with_context(|| format!("failed to read {}", deb.display()))? {
        let mut entry = entry.with_context(|| format!("failed to read {}", deb.display()))?;
        let name = entry.path()?.to_string_lossy().trim_start_matches("./").to_string();
        if name == path {
            let mut bytes = Vec::new();
            std::io::Read::read_to_end(&mut entry, &mut bytes)?;
            return Ok(bytes);
        }
    }
    bail!("{} has no /{path}", deb.display())
}

/// The standard output of `command`, bytes, failing unless it succeeds.
fn output_bytes(command: &mut Command) -> Result<Vec<u8>> {
    let line = command_line(command);
    let output = command.output().with_context(|| format!("failed to start `{line}`"))?;
    ensure!(
        output.status.success(),
        "`{line}` failed with {}: {}",
        output.status,
        String::from_utf8_lossy(&output.stderr).trim()
    );
    Ok(output.stdout)
}

/// The `SHA256:` fields of `apt-cache show` output, one a stanza.
fn sha256_in_apt_cache_show(show: &str) -> Vec<String> {
    show.lines().filter_map(|line| line.strip_prefix("SHA256:")).map(|hash| hash.trim().to_string()).collect()
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

    /// A `.deb` of package `polylab-test-tool` holding `usr/bin/tool`,
    /// built with dpkg-deb in `dir`, and its pin.
    fn test_deb(dir: &Path) -> PinnedDeb {
        let root = dir.join("package");
        std::fs::create_dir_all(root.join("DEBIAN")).unwrap();
        std::fs::create_dir_all(root.join("usr/bin")).unwrap();
        std::fs::write(
            root.join("DEBIAN/control"),
            "Package: polylab-test-tool\nVersion: 1.0\nArchitecture: all\nMaintainer: polylab\nDescription: a test\n",
        )
        .unwrap();
        std::fs::write(root.join("usr/bin/tool"), "the packaged tool\n").unwrap();
        let deb = dir.join("polylab-test-tool_1.0_all.deb");
        let built = Command::new("dpkg-deb").args(["--build", "--root-owner-group"]).arg(&root).arg(&deb).output();
        assert!(built.unwrap().status.success(), "dpkg-deb --build");
        let sha256 = crate::sources::sha256_hex(&std::fs::read(&deb).unwrap());
        PinnedDeb { package: "polylab-test-tool", deb, sha256: Box::leak(sha256.into_boxed_str()) }
    }

    const TOOL: DebianFile = DebianFile { package: "polylab-test-tool", path: "usr/bin/tool" };

    #[test]
    fn an_unpacked_file_changed_since_is_unpacked_again_from_the_checked_package() {
        let dir = tempfile::tempdir().unwrap();
        let pinned = test_deb(dir.path());
        let unpacked = || Unpacked::pinned(dir.path().join("unpacked"), vec![pinned.clone()]);
        let tool = unpacked().get(TOOL).unwrap();
        assert_eq!(std::fs::read_to_string(&tool).unwrap(), "the packaged tool\n");
        std::fs::write(&tool, "#!/bin/sh\n# a tool put in its place\n").unwrap();
        assert_eq!(unpacked().get(TOOL).unwrap(), tool);
        assert_eq!(std::fs::read_to_string(&tool).unwrap(), "the packaged tool\n", "a later build trusted it");
    }

    #[test]
    fn a_package_that_is_not_its_pin_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        let pinned = test_deb(dir.path());
        let mut bytes = std::fs::read(&pinned.deb).unwrap();
        bytes.push(0);
        std::fs::write(&pinned.deb, bytes).unwrap();
        let error = Unpacked::pinned(dir.path().join("unpacked"), vec![pinned]).get(TOOL).unwrap_err().to_string();
        assert!(error.contains("has SHA-256") && error.contains("not the package it claims to be"), "{error}");
    }

    #[test]
    fn the_sha256_is_read_from_apt_cache_show() {
        let show =
            "Package: sbsigntool\nVersion: 0.9.4-3.1\nSHA256: 0a1b\nSize: 1\n\nPackage: sbsigntool\nSHA256: ff\n";
        assert_eq!(sha256_in_apt_cache_show(show), ["0a1b", "ff"]);
    }
}
