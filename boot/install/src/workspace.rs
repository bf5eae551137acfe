//! Where the installs and the builds read and write in the workspace, and
//! where root keeps what it runs when the workspace is not its alone.

use std::os::unix::fs::{MetadataExt, PermissionsExt};
use std::path::{Path, PathBuf};

use anyhow::{ensure, Context, Result};

use crate::process::is_root;

/// Where root keeps its state ([`state_dir`]) when the target folder is
/// not root's alone.
const ROOTS_STATE: &str = "/var/cache/polylab";

/// The workspace root: this crate lives in its `boot/install/` folder.
pub fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .and_then(Path::parent)
        .expect("the install crate is two folders inside the workspace")
}

/// The host target directory: `CARGO_TARGET_DIR` when set, as cargo does,
/// else `target/` in the workspace.
pub fn target_dir() -> PathBuf {
    match std::env::var_os("CARGO_TARGET_DIR") {
        Some(dir) => root().join(dir),
        None => root().join("target"),
    }
}

/// Where the pinned nightly builds the kernel and the image writer: a
/// directory of its own, so the stable host builds and the nightly builds
/// never invalidate each other's artifacts.
pub fn nightly_target_dir() -> PathBuf {
    target_dir().join("nightly")
}

/// Where a process keeps what it later runs or trusts: the turns' lock
/// files, virt-firmware's virtual environment, Debian's packages the image
/// takes shim, MokManager and sbsign from, and their apt lists. The target
/// folder, but for root only if no other user can change it
/// ([`only_root_can_change`]); else, for root, `/var/cache/polylab`
/// (made mode 0755, root's: what is there is public, and apt's `_apt`
/// user must be able to reach its lists).
pub fn state_dir() -> Result<PathBuf> {
    state_dir_for(&target_dir(), is_root(), Path::new(ROOTS_STATE))
}

/// [`state_dir`] for a process with target folder `target`, root or not
/// (`as_root`), whose own folder for root is `roots`.
fn state_dir_for(target: &Path, as_root: bool, roots: &Path) -> Result<PathBuf> {
    if !as_root || only_root_can_change(target) {
        return Ok(target.to_path_buf());
    }
    std::fs::create_dir_all(roots).with_context(|| format!("failed to create {}", roots.display()))?;
    std::fs::set_permissions(roots, std::fs::Permissions::from_mode(0o755))
        .with_context(|| format!("failed to make {} mode 755", roots.display()))?;
    ensure!(
        only_root_can_change(roots),
        "{} is where root keeps what it runs when the target folder {} is not root's alone, but users other than \
         root can change it: make it root's and writable by root only (`chown root: {0}; chmod 755 {0}`)",
        roots.display(),
        target.display()
    );
    Ok(roots.to_path_buf())
}

/// Whether only root can change `path`: it (or, if it is not there yet,
/// the nearest folder above it that is) is root's and writable by root
/// only, and so is every folder above it, or sticky, as `/tmp` is (where
/// no other user can move root's entries). Symlinks are followed
/// (`canonicalize`): the folders that hold them are checked too.
pub fn only_root_can_change(path: &Path) -> bool {
    let existing = path.ancestors().find(|folder| folder.exists());
    let Some(real) = existing.and_then(|folder| folder.canonicalize().ok()) else { return false };
    let roots_alone = |folder: &Path, sticky_will_do: bool| {
        std::fs::metadata(folder).is_ok_and(|metadata| {
            let others_write = metadata.mode() & 0o022 != 0;
            let sticky = metadata.mode() & 0o1000 != 0;
            metadata.uid() == 0 && (!others_write || (sticky_will_do && sticky))
        })
    };
    roots_alone(&real, false) && real.ancestors().skip(1).all(|folder| roots_alone(folder, true))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn root_keeps_its_state_in_a_folder_of_its_own_when_others_can_change_the_target_folder() {
        let dir = tempfile::tempdir().unwrap();
        let (target, roots) = (dir.path().join("target"), dir.path().join("roots"));
        std::fs::create_dir(&target).unwrap();
        std::fs::set_permissions(&target, std::fs::Permissions::from_mode(0o777)).unwrap();
        assert_eq!(state_dir_for(&target, false, &roots).unwrap(), target, "a user keeps its state in target/");
        assert!(!only_root_can_change(&target.join("not-yet-made")), "made in a folder anyone can write");
        // What follows is root's (root's folder must be root's).
        if is_root() {
            assert_eq!(state_dir_for(&target, true, &roots).unwrap(), roots);
            assert_eq!(std::fs::metadata(&roots).unwrap().permissions().mode() & 0o7777, 0o755);
            std::fs::set_permissions(&target, std::fs::Permissions::from_mode(0o755)).unwrap();
            assert_eq!(state_dir_for(&target, true, &roots).unwrap(), target, "the target folder is root's alone");
        }
    }
}
