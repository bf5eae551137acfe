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
//! SHA-256 Debian's archive signed for it ([`Unpacked::signed_sha256`]:
//! gpgv, Debian's keyring, `InRelease`, `Packages`, each read anew), and
//! the file taken is compared with the `.deb`'s own: neither the lists
//! nor an unpacked folder is ever trusted as found.

use std::collections::HashSet;
use std::path::{Path, PathBuf};
use std::process::Command;

use anyhow::{bail, ensure, Context, Result};

use install::ensure_debian_packages;
use install::turn_in;
use install::{command_line, find_in_path, run_streaming};
use install::{PrivateApt, DEBIAN_KEYRING};

/// apt's helper, whose `cat-file` reads a list as apt stored it
/// (compressed or not) and writes it out decompressed.
const APT_HELPER: &str = "/usr/lib/apt/apt-helper";

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

/// Debian's packages cannot be had: apt could not tell their current
/// version (no apt-get, no network, or lists without them), and none was
/// fetched before. Why, in words.
#[derive(Debug)]
pub struct Unobtainable(String);

impl std::fmt::Display for Unobtainable {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for Unobtainable {}

/// The unpacked packages.
pub struct Unpacked {
    dir: PathBuf,
    source: Source,
    /// apt with the build's own lists (over the machine's sources).
    apt: PrivateApt,
    /// The keys the lists' `InRelease` files must be signed by.
    keyring: PathBuf,
}

impl Unpacked {
    /// The packages of Debian's archive, unpacked in `dir`, with apt's
    /// lists in `dir/apt`.
    pub fn in_dir(dir: PathBuf) -> Self {
        let apt = PrivateApt::machines_sources(dir.join("apt"));
        Self::from_archive(dir, apt)
    }

    /// The packages of the archive `apt` reads (its lists signed by
    /// Debian's archive key), unpacked in `dir`.
    pub fn from_archive(dir: PathBuf, apt: PrivateApt) -> Self {
        Self { dir, source: Source::Archive, apt, keyring: PathBuf::from(DEBIAN_KEYRING) }
    }

    /// The packages `debs` give, unpacked in `dir`, never replaced by the
    /// archive's.
    pub fn pinned(dir: PathBuf, debs: Vec<PinnedDeb>) -> Self {
        let apt = PrivateApt::machines_sources(dir.join("apt"));
        Self { dir, source: Source::Pinned(debs), apt, keyring: PathBuf::from(DEBIAN_KEYRING) }
    }

    /// The path of `file`, its package downloaded and unpacked first if
    /// it is not there yet or the archive has another version now. The
    /// unpacked folder is never trusted as found (anything that runs as
    /// the user could have changed it since, and `sbsign` is handed the
    /// decrypted key): the file must equal the one in the package's
    /// `.deb`, whose SHA-256 is checked first; if it does not, the
    /// package is unpacked again.
    pub fn get(&self, file: DebianFile) -> Result<PathBuf> {
        // The image build and the tests ask for files side by side, from
        // threads and processes alike (sbsign and sbattach share a
        // package): one refreshes the lists, checks and unpacks at a time
        // (a file lock in the folder), and the others find its work done.
        let _one_at_a_time = turn_in(&self.dir, "unpack")?;
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

    /// The package's version, as `apt-get download` named its file.
    pub fn version(&self, package: &str) -> Result<String> {
        let name = self.dir.join(format!("{package}.deb-name"));
        let deb = std::fs::read_to_string(&name).with_context(|| format!("failed to read {}", name.display()))?;
        deb_version(package, &deb).with_context(|| format!("{} names no version of {package}", name.display()))
    }

    /// The `.deb` of `package`, its SHA-256 checked: the given one's
    /// against its pin; the archive's, fetched if missing or outdated,
    /// against the SHA-256 Debian's archive signed for its version
    /// ([`Self::signed_sha256`]).
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
                (deb, self.signed_sha256(package, &version)?)
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
                Source::Archive => "Debian's archive signed",
            }
        );
        Ok(deb)
    }

    /// Where the `.deb` of `package` the last download left is kept.
    fn kept_deb(&self, package: &str) -> Result<PathBuf> {
        let name = std::fs::read_to_string(self.dir.join(format!("{package}.deb-name")))?;
        Ok(self.dir.join("debs").join(package).join(name.trim()))
    }

    /// The version of `package` Debian's archive has now, from lists at
    /// most a day old.
    fn archive_version(&self, package: &str) -> Result<String> {
        self.apt.refresh().context("failed to fetch apt's package lists for the image's Secure Boot files")?;
        self.apt.candidate(package)?.with_context(|| {
            format!(
                "the image takes shim, MokManager and sbsign from Debian's packages, and apt's lists (in {}) have \
                 no {package}",
                self.apt.lists_dir().display()
            )
        })
    }

    /// The SHA-256 Debian's archive signed for `package` at `version`,
    /// read through the signature on every use (whoever can write the
    /// lists can change them between two updates): each `InRelease` of
    /// the lists verified by gpgv against the keyring (Debian's archive
    /// keys), and only what gpgv says was signed read from it; a
    /// `Packages` list only if its SHA-256 (decompressed, as apt's
    /// apt-helper reads it) is one a verified `InRelease` gives; and of
    /// that list, the `SHA256:` of the stanzas of `package` at `version`.
    /// Lists of other archives (not signed by these keys) are left out.
    fn signed_sha256(&self, package: &str, version: &str) -> Result<Vec<String>> {
        // Debian 13's apt verifies with sqv and no longer pulls gpgv in.
        ensure_debian_packages("gpgv (to check Debian's signature on the package lists)", &["gpgv"], || {
            find_in_path("gpgv").is_some()
        })?;
        let lists = self.apt.lists_dir();
        let mut files: Vec<PathBuf> = std::fs::read_dir(&lists)
            .with_context(|| format!("failed to list {}", lists.display()))?
            .filter_map(|entry| entry.ok().map(|entry| entry.path()))
            .collect();
        files.sort();
        let name =
            |path: &PathBuf| path.file_name().map(|name| name.to_string_lossy().into_owned()).unwrap_or_default();
        let mut signed = HashSet::new();
        for release in files.iter().filter(|path| name(path).ends_with("_InRelease")) {
            let mut verify = Command::new("gpgv");
            verify.arg("--keyring").arg(&self.keyring).args(["--output", "-"]).arg(release);
            if let Ok(text) = output_bytes(&mut verify) {
                signed.extend(packages_sha256_in_release(&String::from_utf8_lossy(&text)));
            }
        }
        ensure!(
            !signed.is_empty(),
            "no InRelease file in {} is signed by a key of {}: the lists were changed since apt fetched them, or \
             never fetched; remove {} to have them fetched again",
            lists.display(),
            self.keyring.display(),
            lists.display()
        );
        let mut listed = Vec::new();
        for list in files.iter().filter(|path| is_packages_list(&name(path))) {
            let bytes = output_bytes(Command::new(APT_HELPER).arg("cat-file").arg(list))?;
            if signed.contains(&crate::sources::sha256_hex(&bytes)) {
                listed.extend(sha256_of_version(&String::from_utf8_lossy(&bytes), package, version));
            }
        }
        ensure!(
            !listed.is_empty(),
            "no package list that Debian's archive signed (keys {}) gives a SHA-256 for {package} {version}: a list \
             in {} was changed since apt fetched it, or the archive has no such version; remove {} to have them \
             fetched again",
            self.keyring.display(),
            lists.display(),
            lists.display()
        );
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
        self.apt.download(package, &downloads)?;
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

/// The SHA-256 a signed `Release` text gives for each `Packages` list
/// (uncompressed: apt-helper decompresses what apt stored): the lines
/// ` HASH SIZE PATH` of its `SHA256:` field whose path ends `/Packages`.
fn packages_sha256_in_release(release: &str) -> Vec<String> {
    let field = release.lines().skip_while(|line| line.trim_end() != "SHA256:").skip(1);
    let entries = field.take_while(|line| line.starts_with(' '));
    entries
        .filter_map(|entry| match entry.split_whitespace().collect::<Vec<_>>()[..] {
            [hash, _size, path] if path.ends_with("/Packages") => Some(hash.to_string()),
            _ => None,
        })
        .collect()
}

/// Whether the file `name` in apt's lists folder is a `Packages` list,
/// as apt stored it (uncompressed, or with a compressor's suffix).
fn is_packages_list(name: &str) -> bool {
    name.ends_with("_Packages") || name.rsplit_once('.').is_some_and(|(list, _)| list.ends_with("_Packages"))
}

/// The `SHA256:` of the stanzas of `package` at `version` in the
/// `Packages` list `list`.
fn sha256_of_version(list: &str, package: &str, version: &str) -> Vec<String> {
    let field = |stanza: &str, name: &str| {
        stanza.lines().find_map(|line| line.strip_prefix(name)?.strip_prefix(':')).map(str::trim).map(str::to_string)
    };
    list.split("\n\n")
        .filter(|stanza| field(stanza, "Package").as_deref() == Some(package))
        .filter(|stanza| field(stanza, "Version").as_deref() == Some(version))
        .filter_map(|stanza| field(stanza, "SHA256"))
        .collect()
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
        (None, Err(error)) => Err(Unobtainable(format!("{error:#}")).into()),
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
    use install::output_of;

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
        assert!(error.downcast_ref::<Unobtainable>().is_some(), "nothing to keep, and the archive cannot be asked");
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

    /// Set, to the test's folder, in the copy of this test binary the test
    /// below starts.
    const CHILD_DIR: &str = "UNPACK_TEST_CHILD_DIR";

    #[test]
    fn a_process_unpacks_only_when_no_other_holds_the_folders_turn() {
        if let Some(dir) = std::env::var_os(CHILD_DIR) {
            let dir = Path::new(&dir);
            let sha256 = std::fs::read_to_string(dir.join("sha256")).unwrap();
            let deb = dir.join("polylab-test-tool_1.0_all.deb");
            let pinned = PinnedDeb { package: TOOL.package, deb, sha256: Box::leak(sha256.into_boxed_str()) };
            Unpacked::pinned(dir.join("unpacked"), vec![pinned]).get(TOOL).unwrap();
            std::fs::write(dir.join("done"), "").unwrap();
            return;
        }
        let dir = tempfile::tempdir().unwrap();
        let pinned = test_deb(dir.path());
        std::fs::write(dir.path().join("sha256"), pinned.sha256).unwrap();
        let held = turn_in(&dir.path().join("unpacked"), "unpack").unwrap();
        let name = "secure_boot::debian::tests::a_process_unpacks_only_when_no_other_holds_the_folders_turn";
        let mut child = Command::new(std::env::current_exe().unwrap())
            .args(["--exact", name, "--test-threads=1"])
            .env(CHILD_DIR, dir.path())
            .stdout(std::process::Stdio::null())
            .spawn()
            .unwrap();
        std::thread::sleep(std::time::Duration::from_millis(1500));
        let done = dir.path().join("done").exists();
        drop(held);
        let status = child.wait().unwrap();
        assert!(!done, "another process unpacked while this one held the folder's turn");
        assert!(status.success() && dir.path().join("done").exists(), "the other process never unpacked");
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

    /// An archive of the test's own in `dir`: a key made with gpg (its
    /// public half in `dir/keyring.gpg`), and lists as apt leaves them in
    /// `dir/apt/lists`: an `InRelease` signed with the key, giving the
    /// SHA-256 of `packages`, the `Packages` list beside it. Returns the
    /// archive, its keyring and the list.
    fn signed_archive(dir: &Path, packages: &str) -> (Unpacked, PathBuf, PathBuf) {
        ensure_debian_packages("gpg (for a test's signed archive)", &["gpg"], || find_in_path("gpg").is_some())
            .unwrap();
        let home = dir.join("gnupg");
        std::fs::create_dir(&home).unwrap();
        let gpg = || {
            let mut gpg = Command::new("gpg");
            gpg.arg("--homedir").arg(&home).args(["--batch", "--quiet", "--passphrase", "", "--pinentry-mode"]);
            gpg.arg("loopback");
            gpg
        };
        output_of(gpg().args(["--quick-gen-key", "polylab test archive", "ed25519", "sign", "never"])).unwrap();
        let keyring = dir.join("keyring.gpg");
        output_of(gpg().arg("--output").arg(&keyring).arg("--export")).unwrap();
        let lists = dir.join("apt/lists");
        std::fs::create_dir_all(&lists).unwrap();
        let list = lists.join("example.org_debian_dists_test_main_binary-amd64_Packages");
        std::fs::write(&list, packages).unwrap();
        let release = format!(
            "Origin: polylab\nSuite: test\nSHA256:\n {} {} main/binary-amd64/Packages\n",
            crate::sources::sha256_hex(packages.as_bytes()),
            packages.len()
        );
        let unsigned = dir.join("Release");
        std::fs::write(&unsigned, release).unwrap();
        let in_release = lists.join("example.org_debian_dists_test_InRelease");
        output_of(gpg().arg("--output").arg(&in_release).arg("--clearsign").arg(&unsigned)).unwrap();
        let _ = Command::new("gpgconf").arg("--homedir").arg(&home).args(["--kill", "gpg-agent"]).status();
        let apt = PrivateApt::sources_only(dir.join("apt"), &[]);
        let archive = Unpacked { keyring: keyring.clone(), ..Unpacked::from_archive(dir.join("unpacked"), apt) };
        (archive, keyring, list)
    }

    const PACKAGES: &str = "Package: polylab-test-tool\nVersion: 1.0\nArchitecture: all\nSHA256: 1111\n\n\
                            Package: polylab-test-tool\nVersion: 0.9\nSHA256: 0999\n\n\
                            Package: polylab-other\nVersion: 1.0\nSHA256: 2222\n";

    #[test]
    fn the_sha256_is_the_one_debians_signature_covers_for_that_version() {
        let dir = tempfile::tempdir().unwrap();
        let (archive, _, list) = signed_archive(dir.path(), PACKAGES);
        assert_eq!(archive.signed_sha256("polylab-test-tool", "1.0").unwrap(), ["1111"]);
        assert_eq!(archive.signed_sha256("polylab-test-tool", "0.9").unwrap(), ["0999"], "another version's hash");
        let error = archive.signed_sha256("polylab-test-tool", "2.0").unwrap_err().to_string();
        assert!(error.contains("gives a SHA-256 for polylab-test-tool 2.0"), "{error}");
        std::fs::write(&list, PACKAGES.replace("SHA256: 1111", "SHA256: 6666")).unwrap();
        let error = archive.signed_sha256("polylab-test-tool", "1.0").unwrap_err().to_string();
        assert!(error.contains("no package list that Debian's archive signed"), "an edited Packages line: {error}");
    }

    #[test]
    fn an_in_release_changed_after_signing_or_signed_by_another_key_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        let (archive, _, list) = signed_archive(dir.path(), PACKAGES);
        let edited = PACKAGES.replace("SHA256: 1111", "SHA256: 6666");
        std::fs::write(&list, &edited).unwrap();
        let in_release = list.with_file_name("example.org_debian_dists_test_InRelease");
        let signed = std::fs::read_to_string(&in_release).unwrap();
        let hash = crate::sources::sha256_hex(PACKAGES.as_bytes());
        std::fs::write(&in_release, signed.replace(&hash, &crate::sources::sha256_hex(edited.as_bytes()))).unwrap();
        let error = archive.signed_sha256("polylab-test-tool", "1.0").unwrap_err().to_string();
        assert!(error.contains("no InRelease file in"), "an InRelease edited after signing: {error}");
        std::fs::write(&in_release, signed).unwrap();
        std::fs::write(&list, PACKAGES).unwrap();
        let debians = Unpacked { keyring: PathBuf::from(DEBIAN_KEYRING), ..archive };
        let error = debians.signed_sha256("polylab-test-tool", "1.0").unwrap_err().to_string();
        assert!(error.contains("is signed by a key of /usr/share/keyrings/"), "signed by a key not Debian's: {error}");
    }

    #[test]
    fn a_kept_deb_whose_hash_no_signed_list_gives_is_refused_at_its_use() {
        let dir = tempfile::tempdir().unwrap();
        let pinned = test_deb(dir.path());
        let sha256 = pinned.sha256;
        let packages = format!("Package: polylab-test-tool\nVersion: 1.0\nSHA256: {sha256}\n");
        let (archive, _, list) = signed_archive(dir.path(), &packages);
        let debs = dir.path().join("unpacked/debs/polylab-test-tool");
        std::fs::create_dir_all(&debs).unwrap();
        std::fs::copy(&pinned.deb, debs.join("polylab-test-tool_1.0_all.deb")).unwrap();
        std::fs::write(dir.path().join("unpacked/polylab-test-tool.deb-name"), "polylab-test-tool_1.0_all.deb")
            .unwrap();
        // Lists fetched just now, of no source: apt names no version, and
        // the kept package is used (with a warning).
        for folder in ["apt/sources.list.d", "apt/cache"] {
            std::fs::create_dir_all(dir.path().join(folder)).unwrap();
        }
        for file in ["apt/sources.list", "apt/lists-fetched"] {
            std::fs::write(dir.path().join(file), "").unwrap();
        }
        assert!(archive.get(TOOL).is_ok_and(|tool| tool.ends_with("usr/bin/tool")));
        std::fs::write(&list, packages.replace(sha256, &"0".repeat(64))).unwrap();
        let error = format!("{:#}", archive.get(TOOL).unwrap_err());
        assert!(error.contains("no package list that Debian's archive signed"), "{error}");
    }
}
