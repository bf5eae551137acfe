//! Children that go when the harness goes. Every program the harness
//! starts for a run (QEMU, Bochs, chromedriver with the Chromium it
//! starts, a fuzzer under cargo-fuzz) runs in a process group of its own,
//! watched by a watchdog process that also knows the run's scratch folder.
//!
//! Cleanup in `Drop` runs only when the harness ends in an orderly way; a
//! SIGKILL (a CI timeout, the OOM killer) skips it and left QEMU playing
//! the show, with its folder in the temporary directory. Linux's
//! parent-death signal (`PR_SET_PDEATHSIG`) does not cover this well: it
//! reaches only the direct child (not Chromium under chromedriver, nor the
//! fuzz target under cargo-fuzz), it fires when the *thread* that started
//! the child ends (the harness starts children from test threads and from
//! once-per-process initialisers, which end at other times than the
//! child's owner), and it removes no folder.
//!
//! The watchdog is `sh` running [`WATCHDOG`]: it reads orders (the
//! group to kill, the folder to remove) from a pipe whose writing end only
//! the harness holds (close-on-exec, so no other child inherits it). When
//! the harness drops its [`Supervised`], or dies however it dies, the
//! kernel closes that end; the watchdog reads end-of-file, kills the
//! whole process group with SIGKILL and removes the folder. It runs in a
//! process group of its own and ignores the terminal's signals, so a
//! Ctrl-C or a signal to the harness's own group leaves it to do its work.
//! No `unsafe` is needed: std sets the process group (`setpgid` in the
//! child before `exec`).
//!
//! Run folders come from `tempfile`: an unpredictable name, created
//! exclusively (an existing folder or symlink of that name is never
//! used), mode 0700, so no other user of a shared machine can prepare or
//! read them.

use std::fs::Permissions;
use std::io::Write;
use std::os::unix::fs::PermissionsExt;
use std::os::unix::process::CommandExt;
use std::path::Path;
use std::process::{Child, ChildStdin, Command, Stdio};
use std::time::{Duration, Instant};

use anyhow::{bail, Context, Result};
use tempfile::TempDir;

use install::command_line;

/// The watchdog's script. It reads `group N` and `folder PATH` lines until
/// end-of-file, then kills process group N and removes PATH (a second try
/// after a second, in case a process of the group was still writing
/// there when the signal came).
const WATCHDOG: &str = r#"trap '' HUP INT QUIT TERM PIPE
while IFS= read -r order; do
  case $order in
    "group "*) group=${order#group } ;;
    "folder "*) folder=${order#folder } ;;
  esac
done
if [ -n "${group:-}" ]; then kill -s KILL -- "-$group" 2>/dev/null; fi
if [ -n "${folder:-}" ]; then rm -rf -- "$folder" 2>/dev/null || { sleep 1; rm -rf -- "$folder"; }; fi
"#;

/// Longest wait for the watchdog to finish its work once told to.
const WATCHDOG_TIMEOUT: Duration = Duration::from_secs(10);

/// Random characters in a run folder's name (62 possible each).
const RANDOM_CHARACTERS: usize = 6;

/// Creates the folder `polylab-KIND-` and `random` random characters in
/// `parent`, exclusively (it fails if anything of that name is there, a
/// folder or a symlink), with mode 0700 (tempfile's folders get 0777 less
/// the umask unless told otherwise).
fn create_run_folder(parent: &Path, kind: &str, random: usize) -> Result<TempDir> {
    tempfile::Builder::new()
        .prefix(&format!("polylab-{kind}-"))
        .rand_bytes(random)
        .permissions(Permissions::from_mode(0o700))
        .tempdir_in(parent)
        .with_context(|| format!("failed to create a run folder in {}", parent.display()))
}

/// One run of a child program: its watchdog, its scratch folder (if it has
/// one) and, once started, the program in its own process group. Dropping
/// it kills the group, reaps the program and removes the folder.
pub struct Supervised {
    /// The writing end of the watchdog's orders; closing it is the order
    /// to clean up.
    orders: Option<ChildStdin>,
    watchdog: Child,
    folder: Option<TempDir>,
    child: Option<Child>,
}

impl Supervised {
    /// A watchdog, and a fresh private folder `polylab-KIND-XXXXXX` in the
    /// system's temporary folder for the run.
    pub fn with_folder(kind: &str) -> Result<Self> {
        let mut run = Self::without_folder()?;
        let folder = create_run_folder(&std::env::temp_dir(), kind, RANDOM_CHARACTERS)?;
        let path =
            folder.path().to_str().filter(|path| !path.contains('\n')).with_context(|| {
                format!("the run folder {} is not UTF-8 without line breaks", folder.path().display())
            })?;
        let order = format!("folder {path}\n");
        run.folder = Some(folder);
        run.order(&order)?;
        Ok(run)
    }

    /// A watchdog alone, for a program that needs no scratch folder.
    pub fn without_folder() -> Result<Self> {
        let mut watchdog = Command::new("sh");
        watchdog.arg("-c").arg(WATCHDOG).process_group(0);
        watchdog.stdin(Stdio::piped()).stdout(Stdio::null()).stderr(Stdio::null());
        let mut watchdog =
            watchdog.spawn().context("failed to start the watchdog (`sh`) that cleans up after a run")?;
        let orders = watchdog.stdin.take();
        Ok(Self { orders, watchdog, folder: None, child: None })
    }

    /// The run's folder.
    ///
    /// # Panics
    /// For a run made [`without_folder`](Self::without_folder).
    pub fn folder(&self) -> &Path {
        self.folder.as_ref().expect("this run was made with a folder").path()
    }

    /// Starts `command` in a process group of its own, under the watchdog.
    /// One program per run.
    pub fn spawn(&mut self, command: &mut Command) -> Result<&mut Child> {
        if self.child.is_some() {
            bail!("this run has started its program already");
        }
        command.process_group(0);
        let child = command.spawn().with_context(|| format!("failed to start `{}`", command_line(command)))?;
        let group = child.id();
        // Held before the order goes out: if the order fails, dropping
        // `self` still kills and reaps the program.
        self.child = Some(child);
        self.order(&format!("group {group}\n"))?;
        Ok(self.child())
    }

    /// The program.
    ///
    /// # Panics
    /// Before [`spawn`](Self::spawn).
    pub fn child(&mut self) -> &mut Child {
        self.child.as_mut().expect("the program was started")
    }

    /// The program's process id, which is its process group's too.
    ///
    /// # Panics
    /// Before [`spawn`](Self::spawn).
    pub fn pid(&self) -> u32 {
        self.child.as_ref().expect("the program was started").id()
    }

    fn order(&mut self, order: &str) -> Result<()> {
        let orders = self.orders.as_mut().expect("orders stay open until drop");
        orders.write_all(order.as_bytes()).and_then(|()| orders.flush()).context("the run's watchdog is gone")
    }
}

impl Drop for Supervised {
    fn drop(&mut self) {
        // End-of-file for the watchdog: it kills the group while the
        // program is not yet reaped (so its number, the group's, cannot
        // have gone to another process) and removes the folder.
        drop(self.orders.take());
        let deadline = Instant::now() + WATCHDOG_TIMEOUT;
        while matches!(self.watchdog.try_wait(), Ok(None)) && Instant::now() < deadline {
            std::thread::sleep(Duration::from_millis(5));
        }
        // Killing an exited process fails harmlessly; waiting reaps it.
        let _ = self.watchdog.kill();
        let _ = self.watchdog.wait();
        if let Some(child) = self.child.as_mut() {
            let _ = child.kill();
            let _ = child.wait();
        }
        // `self.folder` goes last: TempDir removes what may be left.
    }
}

/// The processes of process `group` that are alive (zombies, which a
/// killed process is until its new parent reaps it, do not count), from
/// `/proc`: for checking that a run left nothing behind.
pub fn live_members(group: u32) -> Vec<u32> {
    let Ok(entries) = std::fs::read_dir("/proc") else { return Vec::new() };
    entries
        .filter_map(|entry| entry.ok()?.file_name().to_str()?.parse::<u32>().ok())
        .filter(|pid| {
            let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).unwrap_or_default();
            // `PID (COMMAND) STATE PPID PGRP ...`; the command may hold
            // spaces and parentheses, so fields count from its end.
            let fields: Vec<&str> =
                stat.rsplit_once(") ").map(|(_, rest)| rest.split(' ').collect()).unwrap_or_default();
            fields.len() > 2 && fields[0] != "Z" && fields[2] == group.to_string()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Waits (at most 10 s) until `group` has no live process.
    fn wait_until_gone(group: u32) -> bool {
        let deadline = Instant::now() + Duration::from_secs(10);
        while !live_members(group).is_empty() {
            if Instant::now() > deadline {
                return false;
            }
            std::thread::sleep(Duration::from_millis(20));
        }
        true
    }

    #[test]
    fn a_run_folder_is_private_exclusive_and_unpredictable() {
        let (first, second) = (Supervised::with_folder("test").unwrap(), Supervised::with_folder("test").unwrap());
        let (a, b) = (first.folder().to_path_buf(), second.folder().to_path_buf());
        assert_ne!(a, b);
        for folder in [&a, &b] {
            let name = folder.file_name().unwrap().to_str().unwrap();
            assert!(name.starts_with("polylab-test-"), "{name}");
            assert!(!name.contains(&std::process::id().to_string()), "{name} names the process");
            let mode = std::fs::metadata(folder).unwrap().permissions().mode() & 0o777;
            assert_eq!(mode, 0o700, "{} has mode {mode:o}", folder.display());
        }
        drop((first, second));
        assert!(!a.exists() && !b.exists());
    }

    /// With no random characters the name is known in advance, as an
    /// attacker's guess would be: what is planted there (a folder, a
    /// symlink to a folder of the attacker's) makes the creation fail and
    /// is left as it was; with the name free again it succeeds.
    #[test]
    fn a_run_folder_is_never_a_folder_or_symlink_that_was_there() {
        let parent = tempfile::tempdir().unwrap();
        let (planted, theirs) = (parent.path().join("polylab-test-"), tempfile::tempdir().unwrap());
        std::fs::create_dir(&planted).unwrap();
        let error = create_run_folder(parent.path(), "test", 0).unwrap_err();
        assert!(format!("{error:#}").contains("exists"), "{error:#}");
        assert!(planted.is_dir());
        std::fs::remove_dir(&planted).unwrap();
        std::os::unix::fs::symlink(theirs.path(), &planted).unwrap();
        let mode = || std::fs::metadata(theirs.path()).unwrap().permissions().mode();
        let their_mode = mode();
        let error = create_run_folder(parent.path(), "test", 0).unwrap_err();
        assert!(format!("{error:#}").contains("exists"), "{error:#}");
        assert_eq!(std::fs::read_link(&planted).unwrap(), theirs.path());
        assert_eq!(mode(), their_mode, "the mode of the symlink's folder changed");
        assert_eq!(std::fs::read_dir(theirs.path()).unwrap().count(), 0, "something was made in the symlink's folder");
        std::fs::remove_file(&planted).unwrap();
        let folder = create_run_folder(parent.path(), "test", 0).unwrap();
        assert_eq!(folder.path(), planted);
    }

    #[test]
    fn dropping_a_run_kills_its_whole_group_and_removes_its_folder() {
        let mut run = Supervised::with_folder("test").unwrap();
        let folder = run.folder().to_path_buf();
        // A program that starts a grandchild and reports its number.
        let mut shell = Command::new("sh");
        shell.args(["-c", "sleep 600 & echo $!; exec sleep 600"]).stdout(Stdio::piped()).stderr(Stdio::null());
        let child = run.spawn(&mut shell).unwrap();
        let group = child.id();
        let mut line = String::new();
        std::io::BufRead::read_line(&mut std::io::BufReader::new(child.stdout.take().unwrap()), &mut line).unwrap();
        let grandchild: u32 = line.trim().parse().unwrap();
        assert_eq!(live_members(group).len(), 2, "the program and its grandchild {grandchild} in group {group}");
        drop(run);
        assert!(wait_until_gone(group), "{:?} of group {group} outlived its run", live_members(group));
        assert!(!folder.exists(), "{} outlived its run", folder.display());
    }

    #[test]
    fn a_run_whose_program_fails_to_start_leaves_no_folder() {
        let mut run = Supervised::with_folder("test").unwrap();
        let folder = run.folder().to_path_buf();
        let error = run.spawn(&mut Command::new("/nonexistent/program")).unwrap_err();
        assert!(format!("{error:#}").starts_with("failed to start `/nonexistent/program`"), "{error:#}");
        drop(run);
        assert!(!folder.exists());
    }
}
