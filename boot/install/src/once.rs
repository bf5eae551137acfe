//! Work done once per process (installing, building) whose outcome, success
//! or failure, every later caller shares; and installs taking turns across
//! the processes of one workspace (test binaries run side by side).

use std::fs::File;
use std::sync::OnceLock;

use anyhow::{anyhow, Context, Result};

use crate::missing::MissingPackages;
use crate::workspace::target_dir;

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
/// `NAME.lock`, lies in the target folder, the running user's own. A
/// thread must not ask for a turn it holds: it would wait for itself.
pub fn turn(name: &str) -> Result<File> {
    let dir = target_dir();
    std::fs::create_dir_all(&dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let path = dir.join(format!("{name}.lock"));
    let file = File::options()
        .create(true)
        .truncate(false)
        .write(true)
        .open(&path)
        .with_context(|| format!("cannot open {}", path.display()))?;
    file.lock().with_context(|| format!("cannot lock {}", path.display()))?;
    Ok(file)
}

#[cfg(test)]
mod tests {
    use std::sync::mpsc;
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

    #[test]
    fn an_install_waits_while_another_holds_the_turn() {
        let first = install_turn().unwrap();
        let (taken, told) = mpsc::channel();
        let second = thread::spawn(move || {
            let _turn = install_turn().unwrap();
            taken.send(()).unwrap();
        });
        assert!(
            told.recv_timeout(Duration::from_millis(500)).is_err(),
            "a second install took a turn held by the first"
        );
        drop(first);
        told.recv_timeout(Duration::from_secs(60)).expect("the second install never took the turn the first gave up");
        second.join().unwrap();
    }
}
