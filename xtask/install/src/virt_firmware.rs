//! virt-firmware (PyPI), whose `virt-fw-vars` writes the Secure Boot
//! tests' MOK lists into OVMF variable stores, installed with pip into a
//! Python virtual environment under `target/`.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

use anyhow::{Context, Result};

use crate::once::once_per_process;
use crate::packages::ensure_debian_packages;
use crate::process::run_streaming;
use crate::workspace;

/// The release of virt-firmware: the one Debian 13 packages, which needs
/// only `cryptography`, `pefile` and `setuptools`; later releases also
/// need `crypt_r` on Python 3.13 (its cloud-init helper hashes
/// passwords), a C extension that does not build there without Python's
/// headers.
pub const VIRT_FIRMWARE_VERSION: &str = "24.11";
/// The setuptools it imports `pkg_resources` from: the last release that
/// has it (82.0 removed it). Python 3.11's venv brings an older setuptools,
/// Python 3.12's and later none, and pip would then take the newest.
pub const SETUPTOOLS_VERSION: &str = "81.0.0";

/// Makes sure `virt-fw-vars` is there and returns its path: virt-firmware
/// [`VIRT_FIRMWARE_VERSION`] installed from PyPI with pip into a Python
/// virtual environment under `target/` (Python's `venv` module, Debian's
/// `python3-venv`, installed by [`ensure_debian_packages`]).
pub fn ensure_virt_fw_vars() -> Result<PathBuf> {
    static DONE: OnceLock<Result<PathBuf, String>> = OnceLock::new();
    once_per_process(&DONE, || {
        let venv = workspace::target_dir().join("virt-firmware");
        let program = venv.join("bin").join("virt-fw-vars");
        let installed = venv.join(format!("virt-firmware-{VIRT_FIRMWARE_VERSION}-setuptools-{SETUPTOOLS_VERSION}"));
        if program.is_file() && installed.is_file() {
            return Ok(program);
        }
        // Debian's python3 has the `venv` module but not `ensurepip`, which
        // `venv` needs to put pip into the environment: python3-venv adds
        // it. (`python3 -m venv --help` succeeds without it.)
        let has_venv = || {
            Command::new("python3").args(["-c", "import ensurepip, venv"]).output().is_ok_and(|o| o.status.success())
        };
        ensure_debian_packages("Python's venv module (for virt-firmware)", &["python3-venv"], has_venv)?;
        eprintln!(
            "install: virt-firmware {VIRT_FIRMWARE_VERSION} from PyPI into {} (its virt-fw-vars writes the Secure \
             Boot tests' MOK lists)",
            venv.display()
        );
        run_streaming(Command::new("python3").args(["-m", "venv"]).arg(&venv))?;
        run_streaming(&mut virt_firmware_install_command(&venv))?;
        std::fs::write(&installed, "").with_context(|| format!("failed to write {}", installed.display()))?;
        Ok(program)
    })
}

fn virt_firmware_install_command(venv: &Path) -> Command {
    let mut install = Command::new(venv.join("bin").join("pip"));
    install.args(["install", "--quiet", &format!("virt-firmware=={VIRT_FIRMWARE_VERSION}")]);
    install.arg(format!("setuptools=={SETUPTOOLS_VERSION}"));
    install
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::process::command_line;

    #[test]
    fn virt_firmware_is_installed_at_its_pinned_version_into_the_venv() {
        assert_eq!(
            command_line(&virt_firmware_install_command(Path::new("/t/virt-firmware"))),
            "/t/virt-firmware/bin/pip install --quiet virt-firmware==24.11 setuptools==81.0.0"
        );
    }
}
