//! Installing the system packages a run needs: which distribution the host
//! is (`/etc/os-release`), what it calls Debian's packages, and apt-get run
//! so that it waits for another apt instead of failing and never removes a
//! package the user has. Where the harness cannot install (not root,
//! another distribution, a package Ubuntu has only as a snap) it fails
//! with what to do instead, the exact command where there is one.

use std::process::Command;

use anyhow::{bail, Context, Result};

use crate::prerequisites::{find_in_path, CHROMEDRIVER_ENV, CHROMIUM_ENV};
use crate::process::{command_line, output_of, run_streaming};

/// How long apt-get waits for another apt or dpkg (an unattended upgrade,
/// a second test run) to release its lock before it gives up.
const APT_LOCK_TIMEOUT_SECONDS: u32 = 600;

/// The Debian packages Ubuntu has only as snaps: its `chromium-browser`
/// and `chromium-chromedriver` packages install the snap.
const UBUNTU_SNAPS: [&str; 2] = ["chromium", "chromium-driver"];

/// The Debian packages Ubuntu has in its universe component, which a
/// machine may not have enabled.
const UBUNTU_UNIVERSE: [&str; 4] = ["bochs", "bochs-term", "bochsbios", "vgabios"];

/// The host's distribution family, from `/etc/os-release`'s `ID` and
/// `ID_LIKE` (Linux Mint and Pop!_OS are Ubuntu's, Raspberry Pi OS is
/// Debian's).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Distribution {
    Debian {
        /// `VERSION_CODENAME` (`bookworm`), naming its backports.
        codename: Option<String>,
    },
    Ubuntu,
    /// Another, by its `PRETTY_NAME` (or `ID`).
    Other(String),
}

impl Distribution {
    /// This host's, read from `/etc/os-release` (or `/usr/lib/os-release`).
    pub fn of_host() -> Self {
        let text =
            ["/etc/os-release", "/usr/lib/os-release"].iter().find_map(|path| std::fs::read_to_string(path).ok());
        Self::from_os_release(&text.unwrap_or_default())
    }

    /// The family `os_release` (the file's text) names.
    pub fn from_os_release(os_release: &str) -> Self {
        let field = |key: &str| {
            os_release.lines().find_map(|line| {
                let value = line.strip_prefix(key)?.strip_prefix('=')?.trim();
                let unquoted = value.strip_prefix(['"', '\'']).and_then(|v| v.strip_suffix(['"', '\'']));
                Some(unquoted.unwrap_or(value).to_string())
            })
        };
        let id = field("ID").unwrap_or_default();
        let like = field("ID_LIKE").unwrap_or_default();
        let is = |family: &str| id == family || like.split_whitespace().any(|word| word == family);
        if is("ubuntu") {
            Distribution::Ubuntu
        } else if is("debian") {
            Distribution::Debian { codename: field("VERSION_CODENAME").filter(|name| !name.is_empty()) }
        } else {
            let name = field("PRETTY_NAME").or(Some(id)).filter(|name| !name.is_empty());
            Distribution::Other(name.unwrap_or_else(|| "a system without /etc/os-release".to_string()))
        }
    }

    /// What this distribution calls Debian's `packages`, for `what`; or,
    /// where the harness cannot install them here, what to do instead.
    fn packages(&self, what: &str, packages: &[&str]) -> Result<Vec<String>, String> {
        let names = || packages.iter().map(|package| package.to_string()).collect();
        match self {
            Distribution::Debian { .. } => Ok(names()),
            Distribution::Ubuntu if packages.iter().any(|package| UBUNTU_SNAPS.contains(package)) => Err(format!(
                "{what} is not installed, and Ubuntu has Chromium only as a snap (its chromium-browser and \
                 chromium-chromedriver packages install the snap), which the harness does not install: a snap \
                 needs snapd running, which containers often lack, and sees a /tmp of its own, where the runs' \
                 folders are not. Install Chromium or Google Chrome and the chromedriver of the same version \
                 (Chrome for Testing has both), then put them on the PATH as `chromium` and `chromedriver`, or \
                 name them with {CHROMIUM_ENV} and {CHROMEDRIVER_ENV}"
            )),
            Distribution::Ubuntu => Ok(names()),
            Distribution::Other(name) => Err(format!(
                "{what} is not installed, and the harness installs packages only on Debian and Ubuntu (and \
                 their derivatives), not on {name}: install it with your package manager (Debian's packages \
                 are {}), then run again",
                packages.join(" ")
            )),
        }
    }
}

/// Installs Debian's `packages` (or the host's names for them) with
/// apt-get unless `present` says `what` is there already. Without root
/// (or apt-get) fails with the command to run; on another distribution,
/// with what to install. Never removes a package: when apt would, fails
/// naming them and the commands that would resolve it.
pub fn ensure_debian_packages(what: &str, packages: &[&str], present: impl Fn() -> bool) -> Result<()> {
    if present() {
        return Ok(());
    }
    let distribution = Distribution::of_host();
    let packages = distribution.packages(what, packages).map_err(anyhow::Error::msg)?;
    let as_root = output_of(Command::new("id").arg("-u")).is_ok_and(|uid| uid.trim() == "0");
    if !as_root || find_in_path("apt-get").is_none() {
        bail!("{what} is not installed; install it with:\n    {}", by_hand(&packages, as_root, &[]));
    }
    eprintln!("harness: {what} is missing; installing the packages {} with apt-get", packages.join(" "));
    run_streaming(&mut apt_get(["update"]))?;
    let in_universe =
        distribution == Distribution::Ubuntu && packages.iter().any(|p| UBUNTU_UNIVERSE.contains(&p.as_str()));
    let hint = if in_universe { " (on Ubuntu they are in universe: `sudo add-apt-repository universe`)" } else { "" };
    let simulation = output_of(&mut apt_install(&packages, Some("--simulate")))
        .with_context(|| format!("apt-get cannot install {}{hint}", packages.join(" ")))?;
    let removed = removals(&simulation);
    if !removed.is_empty() {
        bail!(refusal(what, &packages, &removed, &distribution, as_root));
    }
    run_streaming(&mut apt_install(&packages, Some("--no-remove")))
        .with_context(|| format!("failed to install {what}{hint}"))?;
    if !present() {
        bail!("{} installed, but {what} is still not found", packages.join(" "));
    }
    Ok(())
}

/// apt-get with `arguments`, waiting up to [`APT_LOCK_TIMEOUT_SECONDS`]
/// for another apt's lock, never asking a question.
fn apt_get<'a>(arguments: impl IntoIterator<Item = &'a str>) -> Command {
    let mut apt = Command::new("apt-get");
    apt.args(["-o", &format!("DPkg::Lock::Timeout={APT_LOCK_TIMEOUT_SECONDS}")]);
    apt.args(arguments).env("DEBIAN_FRONTEND", "noninteractive");
    apt
}

/// `apt-get install` of `packages` and their dependencies, without the
/// packages they merely recommend (for QEMU: its GUI, OVMF, its disk
/// tools and block backends, and what they pull in), which a run needs
/// only as named in `prerequisites`; with `mode` (`--simulate`,
/// `--no-remove`) before the packages.
fn apt_install(packages: &[String], mode: Option<&str>) -> Command {
    let mut install = apt_get(["install", "-y", "--no-install-recommends"]);
    install.args(mode).args(packages);
    install
}

/// The packages (with their versions) a simulated apt-get run would
/// remove: its `Remv NAME [VERSION]` lines.
fn removals(simulation: &str) -> Vec<String> {
    let removal = |removed: &str| match removed.split_once(" [") {
        Some((name, rest)) => format!("{name} {}", rest.split(']').next().unwrap_or_default()),
        None => removed.trim().to_string(),
    };
    simulation.lines().filter_map(|line| line.strip_prefix("Remv ")).map(removal).collect()
}

/// The command a person runs to install `packages`: with `sudo` unless
/// root; `options` go before the packages.
fn by_hand(packages: &[String], as_root: bool, options: &[&str]) -> String {
    let sudo = if as_root { "" } else { "sudo " };
    let mut install = Command::new("apt-get");
    install.args(["install", "--no-install-recommends"]).args(options).args(packages);
    format!("{sudo}apt-get update && {sudo}{}", command_line(&install))
}

/// Why the harness will not install `packages`: apt would remove
/// `removed` (`NAME VERSION` each); and the commands that would resolve it.
fn refusal(what: &str, packages: &[String], removed: &[String], distribution: &Distribution, as_root: bool) -> String {
    let names: Vec<&str> = removed.iter().map(|package| package.split(' ').next().unwrap_or_default()).collect();
    let release = match distribution {
        Distribution::Debian { codename: Some(codename) } if removed.iter().any(|p| p.contains("~bpo")) => {
            format!("{codename}-backports")
        }
        _ => "RELEASE".to_string(),
    };
    let which = if release == "RELEASE" {
        format!(" (`apt-cache policy {}` names it)", names.join(" "))
    } else {
        String::new()
    };
    format!(
        "{what} is not installed, and installing {} would remove {} (so says `apt-get install --simulate`); the \
         harness never removes a package. Either install from the release {} came from{which}, so that the \
         versions fit:\n    {}\nor let apt remove {}, knowingly (it asks first):\n    {}",
        packages.join(" "),
        removed.join(", "),
        names.join(" and "),
        by_hand(packages, as_root, &["-t", &release]),
        names.join(" and "),
        by_hand(packages, as_root, &[])
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(packages: &[&str]) -> Vec<String> {
        packages.iter().map(|p| p.to_string()).collect()
    }

    #[test]
    fn the_family_comes_from_id_and_id_like() {
        let bookworm = "PRETTY_NAME=\"Debian GNU/Linux 12 (bookworm)\"\nVERSION_CODENAME=bookworm\nID=debian\n";
        assert_eq!(Distribution::from_os_release(bookworm), Distribution::Debian { codename: Some("bookworm".into()) });
        let ubuntu = "NAME=\"Ubuntu\"\nID=ubuntu\nID_LIKE=debian\nVERSION_CODENAME=noble\n";
        assert_eq!(Distribution::from_os_release(ubuntu), Distribution::Ubuntu);
        let mint = "NAME=\"Linux Mint\"\nID=linuxmint\nID_LIKE='ubuntu debian'\n";
        assert_eq!(Distribution::from_os_release(mint), Distribution::Ubuntu);
        let raspbian = "ID=raspbian\nID_LIKE=debian\n";
        assert_eq!(Distribution::from_os_release(raspbian), Distribution::Debian { codename: None });
        let fedora = "NAME=\"Fedora Linux\"\nID=fedora\nPRETTY_NAME=\"Fedora Linux 40 (Workstation Edition)\"\n";
        assert_eq!(
            Distribution::from_os_release(fedora),
            Distribution::Other("Fedora Linux 40 (Workstation Edition)".into())
        );
        assert_eq!(Distribution::from_os_release(""), Distribution::Other("a system without /etc/os-release".into()));
    }

    #[test]
    fn ubuntu_is_told_what_to_do_for_chromium_and_other_systems_what_to_install() {
        let ubuntu = Distribution::Ubuntu;
        assert_eq!(ubuntu.packages("Bochs", &["bochs", "bochsbios"]), Ok(names(&["bochs", "bochsbios"])));
        let chromium = ubuntu.packages("Chromium", &["chromium", "chromium-driver"]).unwrap_err();
        assert!(chromium.contains("only as a snap") && chromium.contains(CHROMIUM_ENV), "{chromium}");
        let fedora = Distribution::Other("Fedora Linux 40".into());
        let error = fedora.packages("QEMU", &["qemu-system-x86"]).unwrap_err();
        assert!(error.contains("not on Fedora Linux 40") && error.contains("qemu-system-x86"), "{error}");
    }

    #[test]
    fn apt_waits_for_another_apt_and_installs_without_recommendations_or_removals() {
        assert_eq!(
            command_line(&apt_install(&names(&["qemu-system-x86", "ovmf"]), Some("--no-remove"))),
            "apt-get -o DPkg::Lock::Timeout=600 install -y --no-install-recommends --no-remove qemu-system-x86 ovmf"
        );
        assert_eq!(command_line(&apt_get(["update"])), "apt-get -o DPkg::Lock::Timeout=600 update");
    }

    #[test]
    fn the_command_by_hand_has_sudo_only_for_a_user_other_than_root() {
        let packages = names(&["bochs", "bochsbios"]);
        assert_eq!(
            by_hand(&packages, false, &[]),
            "sudo apt-get update && sudo apt-get install --no-install-recommends bochs bochsbios"
        );
        assert_eq!(
            by_hand(&packages, true, &[]),
            "apt-get update && apt-get install --no-install-recommends bochs bochsbios"
        );
    }

    /// What `apt-get install --simulate qemu-system-x86` printed on a
    /// bookworm machine with qemu-utils from backports.
    const SIMULATION: &str = "NOTE: This is only a simulation!\n\
        Reading package lists...\n\
        The following packages will be REMOVED:\n  qemu-utils\n\
        The following NEW packages will be installed:\n  qemu-system-x86\n\
        Remv qemu-utils [1:8.1.2+ds-1~bpo12+1]\n\
        Inst qemu-system-x86 (1:7.2+dfsg-7+deb12u18 Debian:12.12/stable [amd64])\n\
        Conf qemu-system-x86 (1:7.2+dfsg-7+deb12u18 Debian:12.12/stable [amd64])\n";

    #[test]
    fn a_removal_is_refused_naming_the_package_and_the_commands_that_resolve_it() {
        let removed = removals(SIMULATION);
        assert_eq!(removed, ["qemu-utils 1:8.1.2+ds-1~bpo12+1"]);
        assert!(removals("Inst qemu-system-x86 (1:7.2)\nConf qemu-system-x86 (1:7.2)\n").is_empty());
        let bookworm = Distribution::Debian { codename: Some("bookworm".into()) };
        let message = refusal("QEMU", &names(&["qemu-system-x86"]), &removed, &bookworm, false);
        assert!(message.contains("would remove qemu-utils 1:8.1.2+ds-1~bpo12+1"), "{message}");
        let backports = "sudo apt-get install --no-install-recommends -t bookworm-backports qemu-system-x86";
        assert!(message.contains(backports), "{message}");
        assert!(message.contains("let apt remove qemu-utils, knowingly"), "{message}");
        let elsewhere = refusal("QEMU", &names(&["qemu-system-x86"]), &removed, &Distribution::Ubuntu, true);
        assert!(elsewhere.contains("(`apt-cache policy qemu-utils` names it)"), "{elsewhere}");
        assert!(
            elsewhere
                .contains("\n    apt-get update && apt-get install --no-install-recommends -t RELEASE qemu-system-x86"),
            "{elsewhere}"
        );
    }
}
