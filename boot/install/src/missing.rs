//! Debian packages a command needs that a user who is not root must
//! install: [`MissingPackages`], the error each `ensure_*` returns for
//! them, and [`ensure_all`], which runs a command's `ensure_*` steps
//! together, so that such a user stops once, with one set of commands for
//! every package the command misses, rather than once for each; and those
//! commands ([`by_hand`], which `packages` also gives where it refuses an
//! install).

use std::fmt;
use std::process::Command;

use anyhow::Result;

use crate::apt::suite_source_line;
use crate::process::command_line;

/// One of a command's `ensure_*` functions, as [`ensure_all`] runs them.
pub type Step = fn() -> Result<()>;

/// Runs `steps` in order. A step that fails for [`MissingPackages`] (a
/// user who is not root; root installs them as the step runs) does not
/// stop the steps after it: when all have run, the packages every step
/// misses are one error, whose commands install them all. Any other
/// failure stops at once, with that error.
pub fn ensure_all(steps: &[Step]) -> Result<()> {
    let mut missing = MissingPackages::default();
    for step in steps {
        if let Err(error) = step() {
            missing.add(error.downcast::<MissingPackages>()?);
        }
    }
    if missing.needs.is_empty() {
        Ok(())
    } else {
        Err(missing.into())
    }
}

/// Debian packages that are not installed, which the running user (not
/// root) must install: for each need, what it is for and its packages,
/// planned from the machine's sources or from one backports suite
/// (`packages::plan`). Its message gives the commands that install them
/// all: one `apt-get update` and one `apt-get install` from the machine's
/// sources, and one from each suite.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct MissingPackages {
    needs: Vec<Need>,
}

/// What one `ensure_*` misses.
#[derive(Clone, Debug, PartialEq, Eq)]
struct Need {
    what: String,
    packages: Vec<String>,
    /// The backports suite they come from; `None`: the machine's sources.
    suite: Option<String>,
    /// What else would do instead, said after the commands.
    instead: Option<String>,
}

impl MissingPackages {
    /// `what` misses `packages`, which come from the machine's sources or,
    /// where `suite` names one, from that backports suite.
    pub fn new(what: &str, packages: &[String], suite: Option<&str>) -> Self {
        let need = Need {
            what: what.to_string(),
            packages: packages.to_vec(),
            suite: suite.map(str::to_string),
            instead: None,
        };
        MissingPackages { needs: vec![need] }
    }

    /// The same, saying after the commands what would do `instead` of
    /// installing them (a program of one's own).
    pub fn or_instead(mut self, instead: String) -> Self {
        for need in &mut self.needs {
            need.instead = Some(instead.clone());
        }
        self
    }

    /// `other`'s needs added, each once (two steps may miss the same,
    /// as QEMU's QXL card misses QEMU when QEMU is not there).
    fn add(&mut self, other: MissingPackages) {
        for need in other.needs {
            if !self.needs.contains(&need) {
                self.needs.push(need);
            }
        }
    }
}

impl fmt::Display for MissingPackages {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.needs.as_slice() {
            [need] => write!(f, "{} is not installed; install it with:", need.what)?,
            needs => {
                write!(f, "these are not installed (each with its Debian packages):")?;
                for need in needs {
                    let from = need.suite.as_ref().map(|suite| format!(" (from {suite})")).unwrap_or_default();
                    write!(f, "\n    {}: {}{from}", need.what, need.packages.join(" "))?;
                }
                write!(f, "\ninstall them all with:")?;
            }
        }
        let installs = self.needs.iter().map(|need| (need.suite.as_deref(), need.packages.as_slice()));
        for line in by_hand(installs, false) {
            write!(f, "\n    {line}")?;
        }
        let mut instead: Vec<&str> = self.needs.iter().filter_map(|need| need.instead.as_deref()).collect();
        instead.dedup();
        for instead in instead {
            write!(f, "\n{instead}")?;
        }
        Ok(())
    }
}

impl std::error::Error for MissingPackages {}

/// The commands a person runs to install `installs` (each its packages
/// and the backports suite they come from, `None` for the machine's
/// sources), one a line, each with `sudo` unless root: each suite's
/// one-line source added to the machine's sources (so that `apt upgrade`
/// keeps what comes from it up to date), never the lists the harness
/// fetched, which the user can write; the machine's lists refreshed once;
/// then one install of the packages from the machine's sources and one
/// from each suite, each package named once.
pub(crate) fn by_hand<'a>(
    installs: impl IntoIterator<Item = (Option<&'a str>, &'a [String])>,
    as_root: bool,
) -> Vec<String> {
    let sudo = if as_root { "" } else { "sudo " };
    let mut by_suite: Vec<(Option<&str>, Vec<&str>)> = Vec::new();
    for (suite, packages) in installs {
        let at = match by_suite.iter().position(|(known, _)| *known == suite) {
            Some(at) => at,
            None => {
                by_suite.push((suite, Vec::new()));
                by_suite.len() - 1
            }
        };
        let named = &mut by_suite[at].1;
        for package in packages {
            if !named.contains(&package.as_str()) {
                named.push(package);
            }
        }
    }
    // The machine's sources first.
    by_suite.sort_by_key(|(suite, _)| suite.is_some());
    let mut lines = Vec::new();
    for suite in by_suite.iter().filter_map(|(suite, _)| *suite) {
        let line = suite_source_line(suite);
        lines.push(format!("echo '{line}' | {sudo}tee /etc/apt/sources.list.d/{suite}.list"));
    }
    lines.push(format!("{sudo}apt-get update"));
    for (suite, packages) in by_suite {
        let mut install = Command::new("apt-get");
        install.args(["install", "--no-install-recommends"]);
        if let Some(suite) = suite {
            install.args(["-t", suite]);
        }
        install.args(packages);
        lines.push(format!("{sudo}{}", command_line(&install)));
    }
    lines
}

#[cfg(test)]
mod tests {
    use std::sync::atomic::{AtomicUsize, Ordering};

    use anyhow::bail;

    use super::*;

    fn missing(what: &str, packages: &[&str], suite: Option<&str>) -> anyhow::Error {
        let packages: Vec<String> = packages.iter().map(|package| package.to_string()).collect();
        MissingPackages::new(what, &packages, suite).into()
    }

    fn qemu() -> Result<()> {
        Err(missing("QEMU", &["qemu-system-x86"], None))
    }

    fn cairo() -> Result<()> {
        Err(missing("libcairo (for the lab's Cairo peer)", &["libcairo2-dev", "pkg-config"], None))
    }

    fn peers() -> Result<()> {
        Err(missing("Allegro 4 and GD (for the lab's C peers)", &["liballegro4-dev", "libgd-dev", "pkg-config"], None))
    }

    #[test]
    fn the_steps_missing_packages_are_one_error_with_one_update_and_one_install() {
        let message = format!("{:#}", ensure_all(&[qemu, cairo, peers]).unwrap_err());
        assert_eq!(
            message,
            "these are not installed (each with its Debian packages):\n    \
             QEMU: qemu-system-x86\n    \
             libcairo (for the lab's Cairo peer): libcairo2-dev pkg-config\n    \
             Allegro 4 and GD (for the lab's C peers): liballegro4-dev libgd-dev pkg-config\n\
             install them all with:\n    \
             sudo apt-get update\n    \
             sudo apt-get install --no-install-recommends qemu-system-x86 libcairo2-dev pkg-config liballegro4-dev \
             libgd-dev"
        );
    }

    #[test]
    fn a_need_from_backports_has_its_own_install_after_the_one_update() {
        fn backports_qemu() -> Result<()> {
            Err(missing("QEMU", &["qemu-system-x86"], Some("bookworm-backports")))
        }
        let error = ensure_all(&[backports_qemu, cairo]).unwrap_err();
        let message = format!("{error:#}");
        let commands: Vec<&str> = message.lines().skip_while(|line| !line.starts_with("install them all")).collect();
        let source = suite_source_line("bookworm-backports");
        assert_eq!(
            commands,
            [
                "install them all with:".to_string(),
                format!("    echo '{source}' | sudo tee /etc/apt/sources.list.d/bookworm-backports.list"),
                "    sudo apt-get update".to_string(),
                "    sudo apt-get install --no-install-recommends libcairo2-dev pkg-config".to_string(),
                "    sudo apt-get install --no-install-recommends -t bookworm-backports qemu-system-x86".to_string(),
            ]
        );
        assert!(message.contains("\n    QEMU: qemu-system-x86 (from bookworm-backports)\n"), "{message}");
    }

    #[test]
    fn one_need_is_said_as_before_and_a_need_two_steps_miss_is_named_once() {
        // QEMU's QXL card and QEMU's window each miss QEMU itself, when
        // QEMU is not there.
        let message = format!("{:#}", ensure_all(&[qemu, qemu]).unwrap_err());
        assert_eq!(
            message,
            "QEMU is not installed; install it with:\n    sudo apt-get update\n    \
             sudo apt-get install --no-install-recommends qemu-system-x86"
        );
        let instead = || -> Result<()> {
            Err(MissingPackages::new("Chromium", &["chromium".to_string()], None)
                .or_instead("Or name a browser of your own".to_string())
                .into())
        };
        let message = format!("{:#}", ensure_all(&[qemu, instead]).unwrap_err());
        assert!(message.ends_with(" qemu-system-x86 chromium\nOr name a browser of your own"), "{message}");
    }

    #[test]
    fn the_commands_by_hand_have_sudo_only_for_a_user_other_than_root() {
        let packages = ["bochs".to_string(), "bochsbios".to_string()];
        assert_eq!(
            by_hand([(None, packages.as_slice())], false),
            ["sudo apt-get update", "sudo apt-get install --no-install-recommends bochs bochsbios"]
        );
        assert_eq!(
            by_hand([(None, packages.as_slice())], true),
            ["apt-get update", "apt-get install --no-install-recommends bochs bochsbios"]
        );
    }

    #[test]
    fn a_suite_by_hand_is_added_to_the_machines_sources_first() {
        let packages = ["qemu-system-x86".to_string()];
        let lines = by_hand([(Some("bookworm-backports"), packages.as_slice())], false);
        let source = suite_source_line("bookworm-backports");
        assert_eq!(
            lines,
            [
                format!("echo '{source}' | sudo tee /etc/apt/sources.list.d/bookworm-backports.list"),
                "sudo apt-get update".to_string(),
                "sudo apt-get install --no-install-recommends -t bookworm-backports qemu-system-x86".to_string(),
            ]
        );
        assert!(source.ends_with(" bookworm-backports main") && source.starts_with("deb "), "{source}");
    }

    static RAN_AFTER_A_FAILURE: AtomicUsize = AtomicUsize::new(0);

    #[test]
    fn any_other_failure_stops_at_once_with_its_own_error() {
        fn refused() -> Result<()> {
            bail!("OVMF_CODE names /nowhere, which is not a file")
        }
        fn after() -> Result<()> {
            RAN_AFTER_A_FAILURE.fetch_add(1, Ordering::SeqCst);
            Ok(())
        }
        let error = ensure_all(&[qemu, refused, after, cairo]).unwrap_err();
        assert_eq!(format!("{error:#}"), "OVMF_CODE names /nowhere, which is not a file");
        assert!(error.downcast_ref::<MissingPackages>().is_none());
        assert_eq!(RAN_AFTER_A_FAILURE.load(Ordering::SeqCst), 0, "a step ran after a failure");
    }

    static RAN: AtomicUsize = AtomicUsize::new(0);

    #[test]
    fn steps_that_install_what_they_need_all_run_in_order_and_nothing_is_missing() {
        // As root each step installs its packages as it runs, one after
        // another, and none is missing at the end.
        fn first() -> Result<()> {
            assert_eq!(RAN.fetch_add(1, Ordering::SeqCst), 0, "the first step ran second");
            Ok(())
        }
        fn second() -> Result<()> {
            assert_eq!(RAN.fetch_add(1, Ordering::SeqCst), 1, "the second step ran first");
            Ok(())
        }
        ensure_all(&[first, second]).unwrap();
        assert_eq!(RAN.load(Ordering::SeqCst), 2);
        ensure_all(&[]).unwrap();
    }
}
