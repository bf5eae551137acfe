//! Installing Debian's packages a command needs, with apt-get run so
//! that it waits for another apt instead of failing and never removes a
//! package the user has. Where it cannot install (not root, another
//! distribution, a package Ubuntu has only as a snap) it fails with what
//! to do instead, the exact command where there is one.

use std::path::Path;
use std::process::Command;

use anyhow::{bail, Context, Result};

use crate::apt::PrivateApt;
use crate::distribution::Distribution;
use crate::process::{command_line, find_in_path, is_root, output_of, run_streaming};
use crate::workspace;

/// How long apt-get waits for another apt or dpkg (an unattended upgrade,
/// a second test run) to release its lock before it gives up.
const APT_LOCK_TIMEOUT_SECONDS: u32 = 600;

/// Installs Debian's `packages` (or the host's names for them) with
/// apt-get unless `present` says `what` is there already. Never removes a
/// package: where apt would (or cannot install them beside what the
/// machine has), and the machine has packages from its Debian release's
/// backports, the packages come from that suite, for this install only
/// ([`InstallFrom::Suite`]); failing that, it fails naming the packages
/// and commands that would work. Without root (or apt-get) fails with the
/// command to run; on another distribution, with what to install.
pub fn ensure_debian_packages(what: &str, packages: &[&str], present: impl Fn() -> bool) -> Result<()> {
    if present() {
        return Ok(());
    }
    let distribution = Distribution::of_host();
    let packages = distribution.packages(what, packages).map_err(anyhow::Error::msg)?;
    if find_in_path("apt-get").is_none() {
        bail!("{what} is not installed, and this machine has no apt-get: install {} yourself", packages.join(" "));
    }
    let as_root = is_root();
    if as_root {
        eprintln!("install: {what} is missing; installing the packages {} with apt-get", packages.join(" "));
        run_streaming(&mut apt_get(&InstallFrom::Machine, ["update"]))?;
    }
    let hint = distribution.install_hint(&packages);
    let from = plan(what, &packages, &distribution, as_root).with_context(|| format!("cannot install {what}{hint}"))?;
    if !as_root {
        bail!("{what} is not installed; install it with:\n    {}", by_hand(&from, &packages, false));
    }
    run_streaming(&mut apt_install(&from, &packages, Some("--no-remove")))
        .with_context(|| format!("failed to install {what}{hint}"))?;
    if !present() {
        bail!("{} installed, but {what} is still not found", packages.join(" "));
    }
    Ok(())
}

/// Where apt takes the packages from.
#[derive(Clone, Debug, PartialEq, Eq)]
enum InstallFrom {
    /// The machine's own sources and lists.
    Machine,
    /// The machine's sources plus Debian's `suite` (its release's
    /// backports), preferred (`-t`), with lists of their own under
    /// `target/apt/`: the machine's sources and lists stay as they are.
    Suite { apt: PrivateApt, suite: String },
}

/// Where `packages` can come from without removing a package: the
/// machine's sources if apt's simulation removes nothing there; else the
/// backports suite the machine already has packages from, if its
/// simulation removes nothing. Otherwise an error that says what apt
/// would do and which commands would resolve it.
fn plan(what: &str, packages: &[String], distribution: &Distribution, as_root: bool) -> Result<InstallFrom> {
    let machine = InstallFrom::Machine;
    let first = match simulate(&machine, packages) {
        Ok(removed) if removed.is_empty() => return Ok(machine),
        outcome => outcome,
    };
    let suite = match &first {
        Ok(removed) => distribution.backports_of(removed.iter().map(String::as_str)),
        Err(_) => distribution.backports_of(installed_versions().iter().map(String::as_str)),
    };
    let tried = match suite {
        Some(suite) => {
            let apt = PrivateApt::with_suite(workspace::target_dir().join("apt").join(&suite), &suite);
            eprintln!(
                "install: the machine has packages from {suite}, which its apt sources do not name; asking apt \
                 whether {} fits from there, with lists of its own in {} (the machine's sources and lists stay as \
                 they are)",
                packages.join(" "),
                apt.sources_file().parent().unwrap_or(Path::new(".")).display()
            );
            apt.update()?;
            let from = InstallFrom::Suite { apt, suite };
            match simulate(&from, packages) {
                Ok(removed) if removed.is_empty() => return Ok(from),
                outcome => Some((from, outcome)),
            }
        }
        None => None,
    };
    bail!(refusal(what, packages, &first, tried.as_ref(), as_root))
}

/// What apt-get's simulated install of `packages` from `from` would
/// remove (`NAME VERSION` each), or apt's error when it cannot install
/// them at all.
fn simulate(from: &InstallFrom, packages: &[String]) -> Result<Vec<String>> {
    Ok(removals(&output_of(&mut apt_install(from, packages, Some("--simulate")))?))
}

/// The installed packages' `NAME VERSION`, from dpkg.
fn installed_versions() -> Vec<String> {
    let query = output_of(Command::new("dpkg-query").args(["-W", "-f", "${Package} ${Version}\n"]));
    query.unwrap_or_default().lines().map(str::to_string).collect()
}

/// apt-get reading `from`'s sources and lists, with `arguments`, waiting
/// up to [`APT_LOCK_TIMEOUT_SECONDS`] for another apt's lock, never asking
/// a question.
fn apt_get<'a>(from: &InstallFrom, arguments: impl IntoIterator<Item = &'a str>) -> Command {
    let mut apt = match from {
        InstallFrom::Machine => Command::new("apt-get"),
        InstallFrom::Suite { apt, .. } => apt.command("apt-get"),
    };
    apt.args(["-o", &format!("DPkg::Lock::Timeout={APT_LOCK_TIMEOUT_SECONDS}")]);
    apt.args(arguments).env("DEBIAN_FRONTEND", "noninteractive");
    apt
}

/// `apt-get install` of `packages` and their dependencies from `from`,
/// without the packages they merely recommend (for QEMU: its GUI, OVMF,
/// its disk tools and block backends, and what they pull in), which a run
/// needs only as the `ensure_*` functions name it; with `mode` (`--simulate`,
/// `--no-remove`) before the packages.
fn apt_install(from: &InstallFrom, packages: &[String], mode: Option<&str>) -> Command {
    let mut install = apt_get(from, ["install", "-y", "--no-install-recommends"]);
    if let InstallFrom::Suite { suite, .. } = from {
        install.args(["-t", suite]);
    }
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

/// The command a person runs to install `packages` from `from`: with
/// `sudo` unless root; the machine's lists refreshed first, a suite's
/// lists as the harness fetched them.
fn by_hand(from: &InstallFrom, packages: &[String], as_root: bool) -> String {
    let sudo = if as_root { "" } else { "sudo " };
    let mut install = match from {
        InstallFrom::Machine => Command::new("apt-get"),
        InstallFrom::Suite { apt, .. } => apt.command("apt-get"),
    };
    install.args(["install", "--no-install-recommends"]);
    if let InstallFrom::Suite { suite, .. } = from {
        install.args(["-t", suite]);
    }
    install.args(packages);
    match from {
        InstallFrom::Machine => format!("{sudo}apt-get update && {sudo}{}", command_line(&install)),
        InstallFrom::Suite { .. } => format!("{sudo}{}", command_line(&install)),
    }
}

/// Why the harness will not install `packages`: what apt said of the
/// machine's sources (`first`: the packages it would remove, or its
/// error) and, where it tried one, of a backports suite; and the commands
/// that would resolve it.
fn refusal(
    what: &str,
    packages: &[String],
    first: &Result<Vec<String>>,
    tried: Option<&(InstallFrom, Result<Vec<String>>)>,
    as_root: bool,
) -> String {
    let said = |outcome: &Result<Vec<String>>| match outcome {
        Ok(removed) => format!("would remove {}", removed.join(", ")),
        Err(error) => format!("fails: {error:#}"),
    };
    let mut message = format!(
        "{what} is not installed, and installing {} from the machine's apt sources {} (so says `apt-get install \
         --simulate`); the harness never removes a package.",
        packages.join(" "),
        said(first)
    );
    if let Some((InstallFrom::Suite { suite, .. }, outcome)) = tried {
        message.push_str(&format!(" From {suite}, for this install only, it {}.", said(outcome)));
    }
    let removed: Vec<&str> = match first {
        Ok(removed) => removed.iter().filter_map(|package| package.split(' ').next()).collect(),
        Err(_) => Vec::new(),
    };
    let names = if removed.is_empty() { packages.join(" ") } else { removed.join(" ") };
    let mut release = Command::new("apt-get");
    release.args(["install", "--no-install-recommends", "-t", "RELEASE"]).args(packages);
    message.push_str(&format!(
        "\nEither install {} from the release {names} came from (`apt-cache policy {names}` names it; it must be in \
         apt's sources):\n    {}{}",
        packages.join(" "),
        if as_root { "" } else { "sudo " },
        command_line(&release)
    ));
    if !removed.is_empty() {
        message.push_str(&format!(
            "\nor let apt remove {}, knowingly (it asks first):\n    {}",
            removed.join(" and "),
            by_hand(&InstallFrom::Machine, packages, as_root)
        ));
    }
    message
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(packages: &[&str]) -> Vec<String> {
        packages.iter().map(|p| p.to_string()).collect()
    }

    #[test]
    fn apt_waits_for_another_apt_and_installs_without_recommendations_or_removals() {
        assert_eq!(
            command_line(&apt_install(
                &InstallFrom::Machine,
                &names(&["qemu-system-x86", "ovmf"]),
                Some("--no-remove")
            )),
            "apt-get -o DPkg::Lock::Timeout=600 install -y --no-install-recommends --no-remove qemu-system-x86 ovmf"
        );
        assert_eq!(
            command_line(&apt_get(&InstallFrom::Machine, ["update"])),
            "apt-get -o DPkg::Lock::Timeout=600 update"
        );
    }

    /// `line` without the option that has apt download as root, which it
    /// has only when the tests run as root.
    fn without_sandbox(line: String) -> String {
        line.replace(" -o APT::Sandbox::User=root", "")
    }

    fn backports() -> InstallFrom {
        let suite = "bookworm-backports".to_string();
        InstallFrom::Suite { apt: PrivateApt::with_suite("/t/apt".into(), &suite), suite }
    }

    #[test]
    fn a_suite_is_installed_from_with_its_own_lists_and_preferred() {
        assert_eq!(
            without_sandbox(command_line(&apt_install(
                &backports(),
                &names(&["qemu-system-x86"]),
                Some("--no-remove")
            ))),
            "apt-get -o Dir::Etc::sourcelist=/t/apt/sources.list -o Dir::State::Lists=/t/apt/lists \
             -o Dir::Cache=/t/apt/cache -o DPkg::Lock::Timeout=600 install -y --no-install-recommends \
             -t bookworm-backports --no-remove qemu-system-x86"
        );
    }

    #[test]
    fn the_command_by_hand_has_sudo_only_for_a_user_other_than_root() {
        let packages = names(&["bochs", "bochsbios"]);
        assert_eq!(
            by_hand(&InstallFrom::Machine, &packages, false),
            "sudo apt-get update && sudo apt-get install --no-install-recommends bochs bochsbios"
        );
        assert_eq!(
            by_hand(&InstallFrom::Machine, &packages, true),
            "apt-get update && apt-get install --no-install-recommends bochs bochsbios"
        );
        assert_eq!(
            without_sandbox(by_hand(&backports(), &names(&["qemu-system-x86"]), false)),
            "sudo apt-get -o Dir::Etc::sourcelist=/t/apt/sources.list -o Dir::State::Lists=/t/apt/lists \
             -o Dir::Cache=/t/apt/cache install --no-install-recommends -t bookworm-backports qemu-system-x86"
        );
    }

    /// What `apt-get install --simulate qemu-system-x86` printed on this
    /// project's bookworm machines, whose qemu-utils came from backports
    /// while backports is not in their sources.
    const SIMULATION: &str = "NOTE: This is only a simulation!\n\
        Reading package lists...\n\
        The following packages will be REMOVED:\n  qemu-utils\n\
        The following NEW packages will be installed:\n  qemu-system-x86\n\
        Remv qemu-utils [1:10.0.2+ds-2+deb13u1~bpo12+1]\n\
        Inst qemu-system-x86 (1:7.2+dfsg-7+deb12u18+b3 Debian:12.15/oldstable [amd64])\n\
        Conf qemu-system-x86 (1:7.2+dfsg-7+deb12u18+b3 Debian:12.15/oldstable [amd64])\n";

    #[test]
    fn the_simulations_removals_are_read_with_their_versions() {
        assert_eq!(removals(SIMULATION), ["qemu-utils 1:10.0.2+ds-2+deb13u1~bpo12+1"]);
    }

    #[test]
    fn a_removal_is_refused_naming_the_package_and_the_commands_that_resolve_it() {
        let removed = Ok(removals(SIMULATION));
        let tried = (backports(), Err(anyhow::anyhow!("unmet dependencies")));
        let message = refusal("QEMU", &names(&["qemu-system-x86"]), &removed, Some(&tried), false);
        assert!(message.contains("would remove qemu-utils 1:10.0.2+ds-2+deb13u1~bpo12+1"), "{message}");
        assert!(message.contains("From bookworm-backports, for this install only, it fails: unmet"), "{message}");
        let release = "`apt-cache policy qemu-utils` names it";
        assert!(message.contains(release), "{message}");
        assert!(
            message.contains("\n    sudo apt-get install --no-install-recommends -t RELEASE qemu-system-x86"),
            "{message}"
        );
        assert!(message.contains("let apt remove qemu-utils, knowingly"), "{message}");
        assert!(
            message
                .contains("\n    sudo apt-get update && sudo apt-get install --no-install-recommends qemu-system-x86"),
            "{message}"
        );
        let unresolvable = refusal("QXL", &names(&["m"]), &Err(anyhow::anyhow!("held")), None, true);
        assert!(unresolvable.contains("fails: held") && !unresolvable.contains("let apt remove"), "{unresolvable}");
        assert!(unresolvable.contains("\n    apt-get install --no-install-recommends -t RELEASE m"), "{unresolvable}");
    }
}
