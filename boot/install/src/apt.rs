//! apt-get and apt-cache with package lists of their own: the machine's
//! sources (plus, where asked, one more suite, such as its backports),
//! fetched into a folder of ours, so that neither the machine's sources
//! nor its lists change, and no root is needed to read them.
//!
//! Two uses: the image build downloads Debian's shim from lists it has
//! just refreshed (a machine's own lists can be months old, and then name
//! an old shim), and `packages` installs QEMU from the backports suite a
//! machine's qemu-utils came from, for that one install, when the
//! machine's sources lack it (with lists in a fresh folder only root can
//! write, which it then installs from).

use std::os::unix::fs::MetadataExt;
use std::path::{Path, PathBuf};
use std::process::Command;

use anyhow::{ensure, Context, Result};

use crate::process::{is_root, output_of, run_streaming};

/// The machine's one-line sources file; its `sources.list.d` is read by
/// apt as usual, since only the file is replaced.
const SYSTEM_SOURCES: &str = "/etc/apt/sources.list";
/// The machine's deb822 and one-line source folders, searched for its
/// Debian mirror.
const SYSTEM_SOURCE_PARTS: &str = "/etc/apt/sources.list.d";
/// The key Debian's archive signs every suite with, backports included.
pub const DEBIAN_KEYRING: &str = "/usr/share/keyrings/debian-archive-keyring.gpg";
/// The mirror used where the machine's sources name none for its release.
const DEFAULT_MIRROR: &str = "http://deb.debian.org/debian";

/// How long fetched lists are used before [`PrivateApt::refresh`] fetches
/// them again: a day, as Debian's own daily apt timer does.
const LISTS_MAX_AGE: std::time::Duration = std::time::Duration::from_secs(24 * 60 * 60);

/// apt with lists of its own in a folder.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PrivateApt {
    dir: PathBuf,
    /// Whether the machine's sources are read (else only `extra_sources`).
    machines: bool,
    /// Source lines added to the machine's, one-line format.
    extra_sources: Vec<String>,
}

impl PrivateApt {
    /// apt over the machine's sources, with its lists in `dir`.
    pub fn machines_sources(dir: PathBuf) -> Self {
        Self { dir, machines: true, extra_sources: Vec::new() }
    }

    /// apt over the machine's sources and Debian's `suite` (such as
    /// `bookworm-backports`) from the machine's Debian mirror, with its
    /// lists in `dir`.
    pub fn with_suite(dir: PathBuf, suite: &str) -> Self {
        Self { dir, machines: true, extra_sources: vec![suite_source_line(suite)] }
    }

    /// apt over the one-line source `lines` alone, not the machine's
    /// (a test's archive, or one it cannot reach), with its lists in `dir`.
    pub fn sources_only(dir: PathBuf, lines: &[&str]) -> Self {
        Self { dir, machines: false, extra_sources: lines.iter().map(|line| line.to_string()).collect() }
    }

    /// `program` (`apt-get`, `apt-cache`) reading these lists and sources.
    pub fn command(&self, program: &str) -> Command {
        self.command_as(program, is_root())
    }

    /// [`Self::command`] for a process that runs as root (`as_root`) or
    /// not. As root, apt fetches as its `_apt` user (it hands that user the
    /// `partial` folders it downloads into), unless `_apt` cannot reach
    /// the folder (one under a home of mode 0700, for one): apt would then
    /// fail on every file, so it fetches as root there.
    fn command_as(&self, program: &str, as_root: bool) -> Command {
        let mut command = Command::new(program);
        if as_root && !others_can_reach(&self.dir) {
            command.args(["-o", "APT::Sandbox::User=root"]);
        }
        let mut folders = vec![
            ("Dir::Etc::sourcelist", self.sources_file()),
            ("Dir::State::Lists", self.lists_dir()),
            ("Dir::Cache", self.dir.join("cache")),
        ];
        if !self.machines {
            folders.push(("Dir::Etc::sourceparts", self.dir.join("sources.list.d")));
        }
        for (option, path) in folders {
            command.arg("-o").arg(format!("{option}={}", path.display()));
        }
        command
    }

    /// The folder of the fetched lists (each suite's `InRelease`, signed,
    /// and the `Packages` lists it gives the SHA-256 of).
    pub fn lists_dir(&self) -> PathBuf {
        self.dir.join("lists")
    }

    /// Fetches the lists, unless they were fetched less than a day ago:
    /// the day counts from the last update that fetched every list.
    pub fn refresh(&self) -> Result<()> {
        let stamp = self.dir.join("lists-fetched");
        let fresh = std::fs::metadata(&stamp)
            .and_then(|metadata| metadata.modified())
            .is_ok_and(|fetched| fetched.elapsed().is_ok_and(|age| age < LISTS_MAX_AGE));
        if fresh && self.sources_file().is_file() {
            return Ok(());
        }
        self.update()?;
        std::fs::write(&stamp, "").with_context(|| format!("failed to write {}", stamp.display()))
    }

    /// Fetches the lists now (`apt-get update` into the folder). Fails if
    /// any list could not be fetched (`apt-get update` itself exits 0 then,
    /// saying only `W: Failed to fetch`: `--error-on=any` makes it fail),
    /// or if no list came.
    pub fn update(&self) -> Result<()> {
        for folder in ["lists/partial", "cache/archives/partial", "sources.list.d"] {
            let path = self.dir.join(folder);
            std::fs::create_dir_all(&path).with_context(|| format!("failed to create {}", path.display()))?;
        }
        let mut sources = if self.machines { system_sources_file() } else { String::new() };
        for line in &self.extra_sources {
            sources.push_str(line);
            sources.push('\n');
        }
        std::fs::write(self.sources_file(), sources)
            .with_context(|| format!("failed to write {}", self.sources_file().display()))?;
        let mut update = self.command("apt-get");
        update.args(["update", "--error-on=any"]);
        run_streaming(&mut update).context("apt-get could not fetch every list")?;
        let lists = std::fs::read_dir(self.lists_dir())
            .with_context(|| format!("failed to list {}", self.lists_dir().display()))?
            .filter_map(|entry| entry.ok())
            .filter(|entry| entry.file_name().to_string_lossy().ends_with("Release"))
            .count();
        ensure!(lists > 0, "apt-get update left no Release file in {}", self.lists_dir().display());
        Ok(())
    }

    /// Downloads the `.deb` of `package` (its candidate) into `folder`
    /// (`apt-get download`, which needs no root). As root, `folder` is
    /// handed to apt's `_apt` user first where that user can reach it, so
    /// that apt fetches as `_apt` there too (apt does not hand it the
    /// working folder it downloads into).
    pub fn download(&self, package: &str, folder: &Path) -> Result<()> {
        if is_root() && others_can_reach(folder) && others_can_reach(&self.dir) {
            if let Some(apt_user) = apt_user_id() {
                std::os::unix::fs::chown(folder, Some(apt_user), None)
                    .with_context(|| format!("failed to hand {} to apt's _apt user", folder.display()))?;
            }
        }
        let mut download = self.command("apt-get");
        download.args(["download", package]).current_dir(folder);
        run_streaming(&mut download).with_context(|| format!("apt-get could not download {package}"))
    }

    /// The version apt would install of `package` (its candidate), if any.
    pub fn candidate(&self, package: &str) -> Result<Option<String>> {
        let mut policy = self.command("apt-cache");
        policy.args(["policy", package]);
        Ok(candidate_in_policy(&output_of(&mut policy)?))
    }

    /// The sources file these lists come from, for a person to read.
    pub fn sources_file(&self) -> PathBuf {
        self.dir.join("sources.list")
    }
}

/// Whether a user other than the owners can reach `folder` (or, if it is
/// not there yet, the nearest folder above it that is): every folder from
/// `/` down lets others through (`o+x`).
fn others_can_reach(folder: &Path) -> bool {
    let existing = folder.ancestors().find(|folder| folder.exists());
    let Some(real) = existing.and_then(|folder| folder.canonicalize().ok()) else { return false };
    real.ancestors().all(|folder| std::fs::metadata(folder).is_ok_and(|metadata| metadata.mode() & 0o001 != 0))
}

/// The user id of apt's `_apt` user, if the machine has one.
fn apt_user_id() -> Option<u32> {
    output_of(Command::new("id").args(["-u", "_apt"])).ok()?.trim().parse().ok()
}

/// The one-line apt source of Debian's `suite` (such as
/// `bookworm-backports`) from the machine's Debian mirror, signed by
/// Debian's archive key where the machine has its keyring.
pub fn suite_source_line(suite: &str) -> String {
    let mirror = debian_mirror(&system_sources_text()).unwrap_or_else(|| DEFAULT_MIRROR.to_string());
    let signed_by =
        if Path::new(DEBIAN_KEYRING).is_file() { format!(" [signed-by={DEBIAN_KEYRING}]") } else { String::new() };
    format!("deb{signed_by} {mirror} {suite} main")
}

/// The machine's one-line sources file, or nothing where it has none.
fn system_sources_file() -> String {
    std::fs::read_to_string(SYSTEM_SOURCES).map(|text| text + "\n").unwrap_or_default()
}

/// Every source file of the machine, concatenated (for finding its mirror).
fn system_sources_text() -> String {
    let mut text = system_sources_file();
    if let Ok(entries) = std::fs::read_dir(SYSTEM_SOURCE_PARTS) {
        let mut paths: Vec<PathBuf> = entries.filter_map(|entry| entry.ok().map(|entry| entry.path())).collect();
        paths.sort();
        for path in paths {
            let enabled = path.extension().is_some_and(|extension| extension == "list" || extension == "sources");
            if enabled {
                text.push_str(&std::fs::read_to_string(&path).unwrap_or_default());
                text.push('\n');
            }
        }
    }
    text
}

/// The first Debian mirror in `sources` (one-line `deb URI ...` or deb822
/// `URIs:` lines) that is not the security archive.
fn debian_mirror(sources: &str) -> Option<String> {
    let uris = sources.lines().flat_map(|line| {
        let line = line.trim();
        let words: Vec<&str> = if let Some(uris) = line.strip_prefix("URIs:") {
            uris.split_whitespace().collect()
        } else if let Some(rest) = line.strip_prefix("deb ") {
            rest.split_whitespace().filter(|word| word.contains("://")).take(1).collect()
        } else {
            Vec::new()
        };
        words.into_iter().map(str::to_string).collect::<Vec<_>>()
    });
    uris.filter(|uri| uri.trim_end_matches('/').ends_with("/debian")).find(|uri| !uri.contains("security"))
}

/// The `Candidate:` of `apt-cache policy` output, unless it is `(none)`.
fn candidate_in_policy(policy: &str) -> Option<String> {
    let candidate = policy.lines().find_map(|line| line.trim().strip_prefix("Candidate:"))?.trim();
    (candidate != "(none)" && !candidate.is_empty()).then(|| candidate.to_string())
}

#[cfg(test)]
mod tests {
    use std::os::unix::fs::PermissionsExt;

    use super::*;
    use crate::process::command_line;

    #[test]
    fn the_mirror_is_the_machines_debian_archive_not_its_security_one() {
        let deb822 = "Types: deb\nURIs: http://deb.debian.org/debian-security\nSuites: bookworm-security\n\n\
                      Types: deb\nURIs: http://mirror.example/debian/\nSuites: bookworm bookworm-updates\n";
        assert_eq!(debian_mirror(deb822).as_deref(), Some("http://mirror.example/debian/"));
        let one_line = "# a comment\ndeb [arch=amd64] https://ftp.example.org/debian bookworm main\n";
        assert_eq!(debian_mirror(one_line).as_deref(), Some("https://ftp.example.org/debian"));
        assert_eq!(debian_mirror("deb https://deb.nodesource.com/node_20.x nodistro main\n"), None);
    }

    #[test]
    fn the_candidate_is_read_from_apt_cache_policy() {
        let policy =
            "shim-signed:\n  Installed: (none)\n  Candidate: 1.51~1+deb12u1+16.1-2~deb12u1\n  Version table:\n";
        assert_eq!(candidate_in_policy(policy).as_deref(), Some("1.51~1+deb12u1+16.1-2~deb12u1"));
        assert_eq!(candidate_in_policy("shim-signed:\n  Installed: (none)\n  Candidate: (none)\n"), None);
        assert_eq!(candidate_in_policy(""), None);
    }

    #[test]
    fn the_lists_and_cache_are_the_folders_and_apt_fetches_as_root_only_where_apt_cannot_reach_them() {
        let dir = tempfile::tempdir().unwrap();
        let folder = dir.path().join("apt");
        let apt = PrivateApt::with_suite(folder.clone(), "bookworm-backports");
        let f = folder.display();
        let lists =
            format!("-o Dir::Etc::sourcelist={f}/sources.list -o Dir::State::Lists={f}/lists -o Dir::Cache={f}/cache");
        assert_eq!(command_line(&apt.command_as("apt-get", false)), format!("apt-get {lists}"));
        std::fs::set_permissions(dir.path(), std::fs::Permissions::from_mode(0o700)).unwrap();
        assert_eq!(
            command_line(&apt.command_as("apt-get", true)),
            format!("apt-get -o APT::Sandbox::User=root {lists}"),
            "as root, in a folder apt's _apt user cannot reach, apt fetches as root"
        );
        std::fs::set_permissions(dir.path(), std::fs::Permissions::from_mode(0o755)).unwrap();
        assert_eq!(
            command_line(&apt.command_as("apt-get", true)),
            format!("apt-get {lists}"),
            "as root, where _apt can reach the lists, apt drops to _apt"
        );
        assert!(apt.extra_sources[0].ends_with(" bookworm-backports main"), "{:?}", apt.extra_sources);
    }

    #[test]
    fn an_update_that_fetched_nothing_fails_and_leaves_the_lists_stale() {
        let dir = tempfile::tempdir().unwrap();
        // Port 9 (discard) of this machine: nothing answers there.
        let apt = PrivateApt::sources_only(dir.path().join("apt"), &["deb http://127.0.0.1:9/debian bookworm main"]);
        let error = apt.refresh().unwrap_err();
        assert!(format!("{error:#}").contains("apt-get could not fetch every list"), "{error:#}");
        assert!(!dir.path().join("apt/lists-fetched").exists(), "an update that fetched nothing made the lists fresh");
        let error = apt.refresh().unwrap_err();
        assert!(
            format!("{error:#}").contains("apt-get could not fetch every list"),
            "the next build did not try again"
        );
        let nothing = PrivateApt::sources_only(dir.path().join("none"), &[]);
        let error = nothing.refresh().unwrap_err();
        assert!(error.to_string().contains("apt-get update left no Release file"), "{error:#}");
        assert!(!dir.path().join("none/lists-fetched").exists(), "an update of no source made the lists fresh");
    }
}
