//! Installing Debian's packages a command needs, with apt-get run so
//! that it waits for another apt instead of failing and never removes a
//! package the user has. Where it cannot install (not root, another
//! distribution, a package Ubuntu has only as a snap) it fails with what
//! to do instead, the exact commands where there are some: for a user
//! who is not root, [`MissingPackages`], which `missing::ensure_all`
//! gathers over a whole command.

use std::os::unix::fs::PermissionsExt;
use std::process::Command;
use std::sync::{Mutex, PoisonError};

use anyhow::{bail, Context, Result};

use crate::apt::PrivateApt;
use crate::distribution::Distribution;
use crate::missing::{by_hand, MissingPackages};
use crate::once::install_turn;
use crate::process::{command_line, find_in_path, is_root, output_of, run_streaming};
use crate::workspace::{self, target_dir};

/// How long apt-get waits for another apt or dpkg (an unattended upgrade,
/// a second test run) to release its lock before it gives up.
const APT_LOCK_TIMEOUT_SECONDS: u32 = 600;

/// Installs Debian's `packages` (or the host's names for them) with
/// apt-get unless `present` says `what` is there already. Never removes a
/// package: where apt would (or cannot install them beside what the
/// machine has), and the machine has packages from its Debian release's
/// backports, the packages come from that suite, for this install only
/// ([`InstallFrom::Suite`]), if that removes nothing and upgrades nothing
/// installed; failing that, it fails naming the packages and commands
/// that would work. Without root fails with [`MissingPackages`], whose
/// message gives the commands to run (none of which reads a file the
/// user can write); without apt-get, or on another distribution, with
/// what to install.
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
    // Held until this install is done: another test binary may be
    // installing the same packages, or others, at this moment.
    let _turn = if as_root { Some(install_turn()?) } else { None };
    if as_root && present() {
        return Ok(());
    }
    if as_root {
        eprintln!("install: {what} is missing; installing the packages {} with apt-get", packages.join(" "));
        run_streaming(&mut apt_get(&InstallFrom::Machine, ["update"]))?;
    }
    let hint = distribution.install_hint(&packages);
    let plan = plan(what, &packages, &distribution, as_root).with_context(|| format!("cannot install {what}{hint}"))?;
    if !as_root {
        return Err(MissingPackages::new(what, &packages, plan.suite()).into());
    }
    run_streaming(&mut apt_install(&plan.from, &packages, Some("--no-remove")))
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
    /// The machine's sources with lists of their own, fetched by a user
    /// who is not root to ask apt what an install would do: never
    /// installed from (the commands printed for root use the machine's).
    MachinesSources(PrivateApt),
    /// The machine's sources plus Debian's `suite` (its release's
    /// backports), preferred (`-t`), with lists of their own in a fresh
    /// folder (root's, in its state folder when it installs,
    /// [`fresh_lists`]): the machine's sources and lists stay as they are,
    /// and nothing another user can write is read by root's apt.
    Suite { apt: PrivateApt, suite: String },
}

/// Where to install from, and the folder of a suite's lists, kept until
/// the install is done.
struct Plan {
    from: InstallFrom,
    _lists: Option<tempfile::TempDir>,
}

impl Plan {
    /// The backports suite it installs from, if any.
    fn suite(&self) -> Option<&str> {
        match &self.from {
            InstallFrom::Suite { suite, .. } => Some(suite),
            InstallFrom::Machine | InstallFrom::MachinesSources(_) => None,
        }
    }
}

/// What apt-get's simulated install would do to the installed packages:
/// remove some (`NAME VERSION` each), or install a newer version of some
/// (`NAME OLD -> NEW` each).
#[derive(Debug, PartialEq, Eq)]
struct Simulation {
    removed: Vec<String>,
    upgraded: Vec<String>,
}

/// Where `packages` can come from without removing a package: the
/// machine's sources if apt's simulation removes nothing there; else the
/// backports suite the machine already has packages from, if its
/// simulation removes nothing and upgrades nothing installed (an upgrade
/// from a suite the machine's sources do not name would never be updated
/// by `apt upgrade` again). Otherwise an error that says what apt would do
/// and which commands would resolve it.
fn plan(what: &str, packages: &[String], distribution: &Distribution, as_root: bool) -> Result<Plan> {
    // Root has just refreshed the machine's lists; a user who is not root
    // cannot, so asks apt over lists of the machine's sources fetched
    // into a folder of its own (on a machine whose lists were never
    // fetched, as in a container, the machine's would know no package).
    let machine_view = if as_root { InstallFrom::Machine } else { InstallFrom::MachinesSources(users_lists(None)?) };
    let first = match simulate(&machine_view, packages) {
        Ok(simulation) if simulation.removed.is_empty() => {
            return Ok(Plan { from: InstallFrom::Machine, _lists: None })
        }
        outcome => outcome,
    };
    let suite = match &first {
        Ok(simulation) => distribution.backports_of(simulation.removed.iter().map(String::as_str)),
        Err(_) => distribution.backports_of(installed_versions().iter().map(String::as_str)),
    };
    let tried = match suite {
        Some(suite) => {
            eprintln!(
                "install: the machine has packages from {suite}, which its apt sources do not name; asking apt \
                 whether {} fits from there (the machine's sources and lists stay as they are)",
                packages.join(" ")
            );
            let (lists, apt) = if as_root {
                let (lists, apt) = fresh_lists(&suite)?;
                (Some(lists), apt)
            } else {
                (None, users_lists(Some(&suite))?)
            };
            let from = InstallFrom::Suite { apt, suite };
            match simulate(&from, packages) {
                Ok(simulation) if simulation.leaves_the_installed_as_they_are() => {
                    return Ok(Plan { from, _lists: lists })
                }
                outcome => Some((from, outcome)),
            }
        }
        None => None,
    };
    bail!(refusal(what, packages, &first, tried.as_ref(), as_root))
}

/// apt over the machine's sources and Debian's `suite`, for root to
/// install from, with lists fetched now into a fresh folder in the state
/// folder ([`workspace::state_dir`], which only root can change when root
/// runs; not `TMPDIR`, which may be a folder a user owns), mode 0755 so
/// that apt's `_apt` user can reach it; the folder lives as long as the
/// returned guard. Nothing another user can write is read by root's apt.
fn fresh_lists(suite: &str) -> Result<(tempfile::TempDir, PrivateApt)> {
    let state = workspace::state_dir()?;
    let lists = tempfile::Builder::new()
        .prefix("apt-")
        .tempdir_in(&state)
        .with_context(|| format!("failed to create a folder for apt's lists in {}", state.display()))?;
    std::fs::set_permissions(lists.path(), std::fs::Permissions::from_mode(0o755))
        .with_context(|| format!("failed to make {} mode 755", lists.path().display()))?;
    let apt = PrivateApt::with_suite(lists.path().to_path_buf(), suite);
    fetch(&apt, suite, lists.path())?;
    Ok((lists, apt))
}

/// apt over the machine's sources (and Debian's `suite`, if any) for a
/// user who is not root to ask what an install would do, never to
/// install from: lists of the user's own in the target folder
/// (`apt-lists/machine`, `apt-lists/SUITE`), fetched once per process, so
/// that a command asking about each of its needs fetches them once.
fn users_lists(suite: Option<&str>) -> Result<PrivateApt> {
    static FETCHED: Mutex<Vec<Option<String>>> = Mutex::new(Vec::new());
    let dir = target_dir().join("apt-lists").join(suite.unwrap_or("machine"));
    let apt = match suite {
        Some(suite) => PrivateApt::with_suite(dir.clone(), suite),
        None => PrivateApt::machines_sources(dir.clone()),
    };
    let mut fetched = FETCHED.lock().unwrap_or_else(PoisonError::into_inner);
    let key = suite.map(str::to_string);
    if !fetched.contains(&key) {
        // Another process of this workspace (a test binary) may be
        // fetching into the same folder.
        let _turn = install_turn()?;
        fetch(&apt, suite.unwrap_or("the machine's sources"), &dir)?;
        fetched.push(key);
    }
    Ok(apt)
}

/// Fetches `apt`'s lists (of `what`) into `dir` now, saying so.
fn fetch(apt: &PrivateApt, what: &str, dir: &std::path::Path) -> Result<()> {
    eprintln!("install: fetching apt's lists of {what} into {}", dir.display());
    apt.update()
}

/// What apt-get's simulated install of `packages` from `from` would do to
/// the installed packages, or apt's error when it cannot install them at
/// all.
fn simulate(from: &InstallFrom, packages: &[String]) -> Result<Simulation> {
    Ok(Simulation::read(&output_of(&mut apt_install(from, packages, Some("--simulate")))?))
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
        InstallFrom::MachinesSources(apt) | InstallFrom::Suite { apt, .. } => apt.command("apt-get"),
    };
    apt.args(["-o", &format!("DPkg::Lock::Timeout={APT_LOCK_TIMEOUT_SECONDS}")]);
    apt.args(arguments).env("DEBIAN_FRONTEND", "noninteractive");
    apt
}

/// `apt-get install` of `packages` and their dependencies from `from`,
/// without the packages they merely recommend (for QEMU: its GUI, OVMF,
/// its disk tools and block backends, and what they pull in), which a run
/// needs only as the `ensure_*` functions name it; with `mode`
/// (`--simulate`, `--no-remove`) before the packages.
fn apt_install(from: &InstallFrom, packages: &[String], mode: Option<&str>) -> Command {
    let mut install = apt_get(from, ["install", "-y", "--no-install-recommends"]);
    if let InstallFrom::Suite { suite, .. } = from {
        install.args(["-t", suite]);
    }
    install.args(mode).args(packages);
    install
}

impl Simulation {
    /// What `simulation` (apt-get's `--simulate` output) does: its `Remv
    /// NAME [VERSION]` lines, and its `Inst NAME [OLD] (NEW ...)` lines,
    /// which install a package that is there at OLD (a new package's
    /// `Inst` line has no `[OLD]`).
    fn read(simulation: &str) -> Self {
        let removal = |removed: &str| match removed.split_once(" [") {
            Some((name, rest)) => format!("{name} {}", rest.split(']').next().unwrap_or_default()),
            None => removed.trim().to_string(),
        };
        let upgrade = |installed: &str| {
            let (name, rest) = installed.split_once(" [")?;
            let (old, rest) = rest.split_once(']')?;
            let new = rest.trim_start().strip_prefix('(')?.split_whitespace().next()?;
            Some(format!("{name} {old} -> {new}"))
        };
        Simulation {
            removed: simulation.lines().filter_map(|line| line.strip_prefix("Remv ")).map(removal).collect(),
            upgraded: simulation.lines().filter_map(|line| line.strip_prefix("Inst ")).filter_map(upgrade).collect(),
        }
    }

    /// Whether it neither removes nor upgrades an installed package: what
    /// an install from a suite the machine's sources do not name must do.
    fn leaves_the_installed_as_they_are(&self) -> bool {
        self.removed.is_empty() && self.upgraded.is_empty()
    }

    /// What it does, in words (after "it would").
    fn said(&self) -> String {
        let mut said = Vec::new();
        if !self.removed.is_empty() {
            said.push(format!("remove {}", self.removed.join(", ")));
        }
        if !self.upgraded.is_empty() {
            said.push(format!("upgrade {}", self.upgraded.join(", ")));
        }
        said.join(" and ")
    }
}

/// `lines`, each indented by four spaces, one a line.
fn indented(lines: &[String]) -> String {
    lines.iter().map(|line| format!("    {line}")).collect::<Vec<_>>().join("\n")
}

/// Why `packages` will not be installed: what apt said of the machine's
/// sources (`first`: what it would do to the installed packages, or its
/// error) and, where it tried one, of a backports suite; and the commands
/// that would resolve it.
fn refusal(
    what: &str,
    packages: &[String],
    first: &Result<Simulation>,
    tried: Option<&(InstallFrom, Result<Simulation>)>,
    as_root: bool,
) -> String {
    let said = |outcome: &Result<Simulation>| match outcome {
        Ok(simulation) => format!("would {}", simulation.said()),
        Err(error) => format!("fails: {error:#}"),
    };
    let mut message = format!(
        "{what} is not installed, and installing {} from the machine's apt sources {} (so says `apt-get install \
         --simulate`); packages are never removed for a run.",
        packages.join(" "),
        said(first)
    );
    if let Some((InstallFrom::Suite { suite, .. }, outcome)) = tried {
        message.push_str(&format!(
            " From {suite}, for this install only, it {} (an upgrade from a suite the machine's sources do not name \
             would never be updated again, so it is not done for a run).",
            said(outcome)
        ));
    }
    let removed: Vec<&str> = match first {
        Ok(simulation) => simulation.removed.iter().filter_map(|package| package.split(' ').next()).collect(),
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
    if let Some((InstallFrom::Suite { suite, .. }, _)) = tried {
        message.push_str(&format!(
            "\nor add {suite} to the machine's apt sources and install from it, knowingly (apt asks first):\n{}",
            indented(&by_hand([(Some(suite.as_str()), packages)], as_root))
        ));
    }
    if !removed.is_empty() {
        message.push_str(&format!(
            "\nor let apt remove {}, knowingly (it asks first):\n{}",
            removed.join(" and "),
            indented(&by_hand([(None, packages)], as_root))
        ));
    }
    message
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::distribution::tests::names;

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

    fn backports() -> InstallFrom {
        let suite = "bookworm-backports".to_string();
        InstallFrom::Suite { apt: PrivateApt::with_suite("/t/apt".into(), &suite), suite }
    }

    #[test]
    fn a_suite_is_installed_from_with_its_own_lists_and_preferred() {
        let install = command_line(&apt_install(&backports(), &names(&["qemu-system-x86"]), Some("--no-remove")));
        let lists = "-o Dir::Etc::sourcelist=/t/apt/sources.list -o Dir::State::Lists=/t/apt/lists \
                     -o Dir::Cache=/t/apt/cache -o DPkg::Lock::Timeout=600 install -y --no-install-recommends \
                     -t bookworm-backports --no-remove qemu-system-x86";
        assert_eq!(install, format!("apt-get {lists}"), "apt's _apt user can reach /t/apt: it fetches as _apt");
        let own_lists = InstallFrom::MachinesSources(PrivateApt::machines_sources("/t/apt".into()));
        let asked = command_line(&apt_install(&own_lists, &names(&["qemu-system-x86"]), Some("--simulate")));
        assert!(asked.contains(" -o Dir::State::Lists=/t/apt/lists ") && !asked.contains(" -t "), "{asked}");
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

    /// A simulated install from backports that upgrades an installed
    /// library (the format of apt-get 2.6's `Inst` lines).
    const UPGRADE: &str = "Inst libslirp0 [4.7.0-1] (4.8.0-1~bpo12+1 Debian Backports:bookworm-backports [amd64]) []\n\
        Inst qemu-system-x86 (1:10.0.2+ds-2+deb13u1~bpo12+1 Debian Backports:bookworm-backports [amd64])\n\
        Conf libslirp0 (4.8.0-1~bpo12+1 Debian Backports:bookworm-backports [amd64])\n";

    #[test]
    fn the_simulations_removals_and_upgrades_are_read_with_their_versions() {
        let removal = Simulation::read(SIMULATION);
        assert_eq!(removal.removed, ["qemu-utils 1:10.0.2+ds-2+deb13u1~bpo12+1"]);
        assert!(removal.upgraded.is_empty(), "a new package is no upgrade: {removal:?}");
        let upgrade = Simulation::read(UPGRADE);
        assert_eq!(upgrade.upgraded, ["libslirp0 4.7.0-1 -> 4.8.0-1~bpo12+1"]);
        assert!(upgrade.removed.is_empty());
        assert!(!removal.leaves_the_installed_as_they_are() && !upgrade.leaves_the_installed_as_they_are());
        assert!(Simulation::read("Inst qemu-system-x86 (1:10.0.2 Debian Backports [amd64])\n")
            .leaves_the_installed_as_they_are());
    }

    #[test]
    fn a_removal_is_refused_naming_the_package_and_the_commands_that_resolve_it() {
        let removed = Ok(Simulation::read(SIMULATION));
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
            message.contains(
                "\n    sudo apt-get update\n    sudo apt-get install --no-install-recommends qemu-system-x86"
            ),
            "{message}"
        );
        let unresolvable = refusal("QXL", &names(&["m"]), &Err(anyhow::anyhow!("held")), None, true);
        assert!(unresolvable.contains("fails: held") && !unresolvable.contains("let apt remove"), "{unresolvable}");
        assert!(unresolvable.contains("\n    apt-get install --no-install-recommends -t RELEASE m"), "{unresolvable}");
    }

    #[test]
    fn an_upgrade_from_backports_is_refused_like_a_removal_and_shown() {
        let removed = Ok(Simulation::read(SIMULATION));
        let tried = (backports(), Ok(Simulation::read(UPGRADE)));
        let message = refusal("QEMU", &names(&["qemu-system-x86"]), &removed, Some(&tried), true);
        assert!(
            message.contains("From bookworm-backports, for this install only, it would upgrade libslirp0 4.7.0-1 -> "),
            "{message}"
        );
        assert!(message.contains("add bookworm-backports to the machine's apt sources"), "{message}");
        assert!(message.contains("| tee /etc/apt/sources.list.d/bookworm-backports.list\n    apt-get update\n"));
    }
}
