//! Finding the system's files and programs the runs use: where a Debian
//! package puts them, unless an environment variable names others (a file
//! so named must exist, and nothing is installed for it).

use std::ffi::OsString;
use std::path::{Path, PathBuf};

use anyhow::{ensure, Result};

use crate::packages::ensure_debian_packages;
use crate::process::find_in_path;

/// The file the environment variable `env` names, or else `default`
/// (where a Debian package puts it).
pub fn system_file(env: &str, default: &str) -> PathBuf {
    chosen(std::env::var_os(env), default)
}

fn chosen(named: Option<OsString>, default: &str) -> PathBuf {
    named.filter(|named| !named.is_empty()).map_or_else(|| PathBuf::from(default), PathBuf::from)
}

/// The program `env` names (a path, or a name on the PATH), or else
/// `default` on the PATH.
pub fn program(env: &str, default: &str) -> Option<PathBuf> {
    let named = chosen(std::env::var_os(env), default);
    if named.components().count() > 1 {
        return named.is_file().then_some(named);
    }
    find_in_path(named.to_str()?)
}

/// Whether every one of `programs` is on the `PATH`.
pub fn on_path(programs: &[&str]) -> bool {
    programs.iter().all(|program| find_in_path(program).is_some())
}

/// Makes sure `programs` are on the `PATH` and `files` (each an
/// environment variable and Debian's path, [`system_file`]) exist,
/// installing `packages` ([`ensure_debian_packages`]); a file a variable
/// names must exist already.
pub fn ensure_system_files(what: &str, packages: &[&str], programs: &[&str], files: &[(&str, &str)]) -> Result<()> {
    ensure_named_files_exist(files)?;
    let present = || on_path(programs) && files.iter().all(|(env, path)| system_file(env, path).is_file());
    ensure_debian_packages(what, packages, present)
}

/// Fails unless every file an environment variable of `files` names
/// exists: a file the user names is never installed over.
fn ensure_named_files_exist(files: &[(&str, &str)]) -> Result<()> {
    for (env, default) in files {
        let path = system_file(env, default);
        ensure!(path == Path::new(default) || path.is_file(), "{env} names {}, which is not a file", path.display());
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_named_file_or_program_replaces_debians() {
        let debians = "/usr/share/OVMF/OVMF_CODE_4M.fd";
        assert_eq!(chosen(None, debians), Path::new(debians));
        assert_eq!(chosen(Some("".into()), debians), Path::new(debians));
        assert_eq!(chosen(Some("/opt/edk2/code.fd".into()), debians), Path::new("/opt/edk2/code.fd"));
    }
}
