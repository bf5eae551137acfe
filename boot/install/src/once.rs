//! Work done once per process (installing, building) whose outcome, success
//! or failure, every later caller shares; and installs taking turns across
//! the processes of one workspace (test binaries run side by side).

use std::fs::File;
use std::os::unix::fs::OpenOptionsExt;
use std::path::Path;
use std::sync::OnceLock;

use anyhow::{anyhow, Context, Result};

use crate::missing::MissingPackages;
use crate::workspace;

/// Runs `work` the first time, and hands every caller its result. Callers
/// arriving while it runs wait for it, so parallel tests never start two
/// builds. A failure is kept as a [`Failure`].
pub fn once_per_process<T: Clone>(cell: &OnceLock<Result<T, Failure>>, work: impl FnOnce() -> Result<T>) -> Result<T> {
    cell.get_or_init(|| work().map_err(Failure::kept)).clone().map_err(Failure::error)
}

/// A failure of work done once, as every later caller gets it: packages
/// missing as themselves, so that `missing::ensure_all` still gathers
/// them when a second step misses what a first did; anything else as
/// its full message (`{:#}`).
#[derive(Clone, Debug)]
pub enum Failure {
    Missing(MissingPackages),
    Message(String),
}

impl Failure {
    fn kept(error: anyhow::Error) -> Self {
        match error.downcast::<MissingPackages>() {
            Ok(missing) => Failure::Missing(missing),
            Err(error) => Failure::Message(format!("{error:#}")),
        }
    }

    fn error(self) -> anyhow::Error {
        match self {
            Failure::Missing(missing) => missing.into(),
            Failure::Message(message) => anyhow!(message),
        }
    }
}

/// Waits for this workspace's other commands and test binaries to finish
/// their installs (apt-get's `update` does not wait for another apt: it
/// fails on the lock of the lists another holds; two pips would write one
/// virtual environment), then holds the turn until the file returned is
/// dropped.
pub(crate) fn install_turn() -> Result<File> {
    turn("install")
}

/// Waits until no other process of this workspace holds the turn `name`,
/// then holds it until the file returned is dropped: work that writes
/// shared files in the target folder (installs, the image build) takes
/// turns, now that test binaries run side by side. The lock file,
/// `NAME.lock`, lies in the state folder ([`workspace::state_dir`]: the
/// target folder, or root's own when root runs over a folder other users
/// can change). A thread must not ask for a turn it holds: it would wait
/// for itself.
pub fn turn(name: &str) -> Result<File> {
    turn_in(&workspace::state_dir()?, name)
}

/// [`turn`] with its lock file, `NAME.lock`, in `dir`. The lock is a file
/// lock (`flock`), which excludes other processes and other opens of the
/// file in this one alike. A symlink at the lock's path is refused
/// (`O_NOFOLLOW`), never followed: root taking a turn over a folder a
/// user can write would otherwise create or lock whatever file it points
/// at.
pub fn turn_in(dir: &Path, name: &str) -> Result<File> {
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let path = dir.join(format!("{name}.lock"));
    let file = File::options()
        .create(true)
        .truncate(false)
        .write(true)
        .custom_flags(libc::O_NOFOLLOW)
        .open(&path)
        .with_context(|| format!("cannot open {} (a symlink there is refused)", path.display()))?;
    file.lock().with_context(|| format!("cannot lock {}", path.display()))?;
    Ok(file)
}

#[cfg(test)]
mod tests {
    use std::process::{Command, Stdio};
    use std::thread;
    use std::time::Duration;

    use super::*;

    #[test]
    fn missing_packages_stay_missing_packages_for_every_caller() {
        static DONE: OnceLock<Result<(), Failure>> = OnceLock::new();
        let packages = ["ovmf".to_string()];
        let missing = || Err(MissingPackages::new("OVMF", &packages, None).into());
        for _ in 0..2 {
            let error = once_per_process(&DONE, missing).unwrap_err();
            assert_eq!(error.downcast_ref(), Some(&MissingPackages::new("OVMF", &packages, None)));
        }
        static FAILED: OnceLock<Result<(), Failure>> = OnceLock::new();
        let failed = || Err(anyhow!("the disk is full").context("failed to install OVMF"));
        for _ in 0..2 {
            let error = once_per_process(&FAILED, failed).unwrap_err();
            assert_eq!(format!("{error:#}"), "failed to install OVMF: the disk is full");
        }
    }

    /// Set, to the lock's folder, in the copy of this test binary the
    /// test below starts.
    const CHILD_DIR: &str = "TURN_TEST_CHILD_DIR";
    const NAME: &str = "once::tests::a_turn_held_by_one_process_makes_another_wait";

    #[test]
    fn a_turn_held_by_one_process_makes_another_wait() {
        if let Some(dir) = std::env::var_os(CHILD_DIR) {
            let dir = Path::new(&dir);
            let _turn = turn_in(dir, "test").unwrap();
            std::fs::write(dir.join("taken"), "").unwrap();
            return;
        }
        let dir = tempfile::tempdir().unwrap();
        let first = turn_in(dir.path(), "test").unwrap();
        let mut child = Command::new(std::env::current_exe().unwrap())
            .args(["--exact", NAME, "--test-threads=1"])
            .env(CHILD_DIR, dir.path())
            .stdout(Stdio::null())
            .spawn()
            .unwrap();
        thread::sleep(Duration::from_millis(1500));
        let taken = dir.path().join("taken").exists();
        drop(first);
        let status = child.wait().unwrap();
        assert!(!taken, "another process took a turn this one held");
        assert!(status.success() && dir.path().join("taken").exists(), "the other process never took the turn");
    }

    #[test]
    fn a_symlink_at_the_locks_path_is_refused_and_its_target_not_made() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("nologin");
        std::os::unix::fs::symlink(&target, dir.path().join("test.lock")).unwrap();
        let error = turn_in(dir.path(), "test").unwrap_err();
        assert!(format!("{error:#}").contains("a symlink there is refused"), "{error:#}");
        assert!(!target.exists(), "the turn created the file the symlink points at");
    }
}
