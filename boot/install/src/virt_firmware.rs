//! virt-firmware (PyPI), whose `virt-fw-vars` writes the Secure Boot
//! tests' MOK lists into OVMF variable stores, installed with pip into a
//! Python virtual environment in the state folder (`target/`, or root's
//! own when root runs over a folder other users can change:
//! [`workspace::state_dir`]).

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

use anyhow::{Context, Result};

use crate::once::{install_turn, once_per_process, Failure};
use crate::packages::ensure_debian_packages;
use crate::process::run_streaming;
use crate::workspace;

/// What pip installs, each at one version with the SHA-256 of every
/// wheel it may take (read from PyPI on 2026-11-28): virt-firmware 24.11,
/// the release Debian 13 packages, which needs only `cryptography`,
/// `pefile` and `setuptools` (later releases also need `crypt_r` on Python
/// 3.13, a C extension that does not build there without Python's
/// headers); setuptools 81.0.0, the last release with the
/// `pkg_resources` it imports (82.0 removed it; Python 3.11's venv brings
/// an older one, 3.12's and later none); and their dependencies. `cffi`
/// has a wheel per Python release: those of 3.11 (Debian 12), 3.12 and
/// 3.13 (Debian 13). pip takes wheels only (`--only-binary :all:`) and
/// refuses any file whose hash is not here (`--require-hashes`).
pub const REQUIREMENTS: &str = "\
virt-firmware==24.11 --hash=sha256:42566b77421aaa0db528867d1cef6bfaabae52366969ebdd369852a8da66b4d1
setuptools==81.0.0 --hash=sha256:fdd925d5c5d9f62e4b74b30d6dd7828ce236fd6ed998a08d81de62ce5a6310d6
pefile==2024.8.26 --hash=sha256:76f8b485dcd3b1bb8166f1128d395fa3d87af26360c2358fb75b80019b957c6f
cryptography==50.0.2 --hash=sha256:9dab55f57c74c3cad24c323bacbbd04be4705ba6eb0d92e920b1fc4837ed5079
cffi==2.1.1 \\
    --hash=sha256:34e261f78cb6ceaaa36f42f2613f4380d94d9c759a9c73c769ee6e0247364632 \\
    --hash=sha256:c1453022f490d2459a11819d83ad1d586e9ff65a12ac3e705ffebd46d3685dcf \\
    --hash=sha256:a931079504ecc49efed7744c476a5c343a92fabf66dec2db95edb1b2fdc770e2
pycparser==3.12 --hash=sha256:a076f3f489b39b43ed13563a1dafe42447445bec2e294154ec5c57fcdda4c85e
";

/// Makes sure `virt-fw-vars` is there and returns its path: [`REQUIREMENTS`]
/// installed from PyPI with pip into a Python virtual environment in the
/// state folder (Python's `venv` module, Debian's `python3-venv`,
/// installed by [`ensure_debian_packages`]), again whenever the
/// requirements change.
pub fn ensure_virt_fw_vars() -> Result<PathBuf> {
    static DONE: OnceLock<Result<PathBuf, Failure>> = OnceLock::new();
    once_per_process(&DONE, || {
        let venv = workspace::state_dir()?.join("virt-firmware");
        let program = venv.join("bin").join("virt-fw-vars");
        let installed = venv.join("requirements.installed");
        if up_to_date(&venv) {
            return Ok(program);
        }
        // Debian's python3 has the `venv` module but not `ensurepip`, which
        // `venv` needs to put pip into the environment: python3-venv adds
        // it. (`python3 -m venv --help` succeeds without it.)
        let has_venv = || {
            Command::new("python3").args(["-c", "import ensurepip, venv"]).output().is_ok_and(|o| o.status.success())
        };
        ensure_debian_packages("Python's venv module (for virt-firmware)", &["python3-venv"], has_venv)?;
        // Another test binary may be installing it at this moment (after
        // the package's install, which takes its own turn).
        let _turn = install_turn()?;
        if up_to_date(&venv) {
            return Ok(program);
        }
        eprintln!(
            "install: virt-firmware 24.11 from PyPI into {} (its virt-fw-vars writes the Secure Boot tests' MOK \
             lists), every wheel checked against its pinned SHA-256",
            venv.display()
        );
        run_streaming(Command::new("python3").args(["-m", "venv"]).arg(&venv))?;
        let requirements = venv.join("requirements.txt");
        std::fs::write(&requirements, REQUIREMENTS)
            .with_context(|| format!("failed to write {}", requirements.display()))?;
        run_streaming(&mut virt_firmware_install_command(&venv, &requirements))?;
        std::fs::write(&installed, REQUIREMENTS).with_context(|| format!("failed to write {}", installed.display()))?;
        Ok(program)
    })
}

/// Whether the virtual environment `venv` has `virt-fw-vars`, installed
/// from exactly [`REQUIREMENTS`] (a changed pin or hash installs again).
fn up_to_date(venv: &Path) -> bool {
    let installed = std::fs::read_to_string(venv.join("requirements.installed"));
    venv.join("bin").join("virt-fw-vars").is_file() && installed.is_ok_and(|text| text == REQUIREMENTS)
}

/// pip installing `requirements` into `venv`: wheels only, each checked
/// against its hash.
fn virt_firmware_install_command(venv: &Path, requirements: &Path) -> Command {
    let mut install = Command::new(venv.join("bin").join("pip"));
    install.args(["install", "--quiet", "--require-hashes", "--only-binary", ":all:", "--requirement"]);
    install.arg(requirements);
    install
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::process::command_line;

    #[test]
    fn pip_takes_only_wheels_whose_hashes_are_pinned() {
        assert_eq!(
            command_line(&virt_firmware_install_command(
                Path::new("/t/virt-firmware"),
                Path::new("/t/virt-firmware/requirements.txt")
            )),
            "/t/virt-firmware/bin/pip install --quiet --require-hashes --only-binary :all: \
             --requirement /t/virt-firmware/requirements.txt"
        );
    }

    #[test]
    fn a_venv_installed_from_other_requirements_is_installed_again() {
        let venv = tempfile::tempdir().unwrap();
        std::fs::create_dir(venv.path().join("bin")).unwrap();
        std::fs::write(venv.path().join("bin/virt-fw-vars"), "").unwrap();
        let installed = venv.path().join("requirements.installed");
        std::fs::write(&installed, REQUIREMENTS.replace("virt-firmware==24.11", "virt-firmware==24.7")).unwrap();
        assert!(!up_to_date(venv.path()), "a venv of another pin was taken as up to date");
        std::fs::write(&installed, REQUIREMENTS).unwrap();
        assert!(up_to_date(venv.path()));
        std::fs::remove_file(venv.path().join("bin/virt-fw-vars")).unwrap();
        assert!(!up_to_date(venv.path()), "a venv without virt-fw-vars was taken as up to date");
    }

    #[test]
    fn every_requirement_is_one_version_with_a_sha256() {
        let joined = REQUIREMENTS.replace("\\\n", " ");
        let lines: Vec<&str> = joined.lines().collect();
        for name in
            ["virt-firmware==24.11", "setuptools==81.0.0", "cryptography==", "pefile==", "cffi==", "pycparser=="]
        {
            assert!(lines.iter().any(|line| line.starts_with(name)), "{name} is not pinned");
        }
        for line in lines {
            let (pin, hashes) = line.split_once(" --hash=sha256:").unwrap_or_else(|| panic!("no hash: {line}"));
            assert!(pin.contains("==") && !pin.contains(['>', '<', '~', '*']), "{pin}");
            for hash in hashes.split("--hash=sha256:") {
                let hash = hash.trim();
                assert!(hash.len() == 64 && hash.chars().all(|c| c.is_ascii_hexdigit()), "{line}");
            }
        }
    }
}
