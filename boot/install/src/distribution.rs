//! Which distribution the host is (`/etc/os-release`), what it calls
//! Debian's packages, and which Debian backports suite a package's
//! version comes from.

/// The Debian packages Ubuntu has only as snaps: its `chromium-browser`
/// and `chromium-chromedriver` packages install the snap.
const UBUNTU_SNAPS: [&str; 2] = ["chromium", "chromium-driver"];

/// The Debian packages Ubuntu has in its universe component, which a
/// machine may not have enabled.
const UBUNTU_UNIVERSE: [&str; 4] = ["bochs", "bochs-term", "bochsbios", "vgabios"];

/// The Debian release numbers Debian's backports versions carry
/// (`~bpo12+1` is bookworm's), and their code names.
const RELEASES: [(u32, &str); 5] = [(10, "buster"), (11, "bullseye"), (12, "bookworm"), (13, "trixie"), (14, "forky")];

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
    /// where they cannot be installed here with apt, what to do instead.
    pub fn packages(&self, what: &str, packages: &[&str]) -> Result<Vec<String>, String> {
        let names = || packages.iter().map(|package| package.to_string()).collect();
        match self {
            Distribution::Debian { .. } => Ok(names()),
            Distribution::Ubuntu if packages.iter().any(|package| UBUNTU_SNAPS.contains(package)) => Err(format!(
                "{what} is not installed, and Ubuntu has {} only as a snap (its chromium-browser and \
                 chromium-chromedriver packages install the snap), which is not installed for you: a snap needs \
                 snapd running, which containers often lack, and sees a /tmp of its own, where the runs' folders \
                 are not",
                packages.join(" ")
            )),
            Distribution::Ubuntu => Ok(names()),
            Distribution::Other(name) => Err(format!(
                "{what} is not installed, and packages are installed only on Debian and Ubuntu (and their \
                 derivatives), not on {name}: install it with your package manager (Debian's packages are {}), \
                 then run again",
                packages.join(" ")
            )),
        }
    }

    /// What to say with a failed install of `packages`: on Ubuntu, that
    /// some are in its universe component, which may not be enabled.
    pub fn install_hint(&self, packages: &[String]) -> &'static str {
        let in_universe =
            *self == Distribution::Ubuntu && packages.iter().any(|p| UBUNTU_UNIVERSE.contains(&p.as_str()));
        if in_universe {
            " (on Ubuntu they are in universe: `sudo add-apt-repository universe`)"
        } else {
            ""
        }
    }

    /// The backports suite (`bookworm-backports`) of the first of
    /// `packages` (`NAME VERSION` each) whose version is a Debian backport
    /// (`~bpoNN`), on a Debian host: the host's own release's, where its
    /// number matches (or is unknown), else the release the number names.
    pub fn backports_of<'a>(&self, packages: impl IntoIterator<Item = &'a str>) -> Option<String> {
        let Distribution::Debian { codename } = self else {
            return None;
        };
        let release = packages.into_iter().find_map(|package| {
            let (_, after) = package.split_once("~bpo")?;
            after.split(|c: char| !c.is_ascii_digit()).next()?.parse::<u32>().ok()
        })?;
        let named = RELEASES.iter().find(|(number, _)| *number == release).map(|(_, name)| *name);
        let host_number = codename.as_deref().and_then(|host| RELEASES.iter().find(|(_, name)| *name == host));
        let name = match (host_number, named) {
            (Some((number, host)), _) if *number == release => *host,
            (None, _) => codename.as_deref().or(named)?,
            (Some(_), named) => named?,
        };
        Some(format!("{name}-backports"))
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// Package names as the installer holds them.
    pub(crate) fn names(packages: &[&str]) -> Vec<String> {
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
    fn ubuntu_is_told_of_its_snaps_and_universe_and_other_systems_what_to_install() {
        let ubuntu = Distribution::Ubuntu;
        assert_eq!(ubuntu.packages("Bochs", &["bochs", "bochsbios"]), Ok(names(&["bochs", "bochsbios"])));
        assert!(ubuntu.install_hint(&names(&["bochs"])).contains("add-apt-repository universe"));
        assert_eq!(ubuntu.install_hint(&names(&["ovmf"])), "");
        let debian = Distribution::Debian { codename: None };
        assert_eq!(debian.install_hint(&names(&["bochs"])), "");
        let chromium = ubuntu.packages("Chromium", &["chromium", "chromium-driver"]).unwrap_err();
        assert!(chromium.contains("only as a snap"), "{chromium}");
        let fedora = Distribution::Other("Fedora Linux 40".into());
        let error = fedora.packages("QEMU", &["qemu-system-x86"]).unwrap_err();
        assert!(error.contains("not on Fedora Linux 40") && error.contains("qemu-system-x86"), "{error}");
    }

    #[test]
    fn a_backport_names_the_backports_suite_it_came_from() {
        let bookworm = Distribution::Debian { codename: Some("bookworm".into()) };
        let suite = |packages: &[&str], host: &Distribution| host.backports_of(packages.iter().copied());
        assert_eq!(
            suite(&["qemu-utils 1:10.0.2+ds-2+deb13u1~bpo12+1"], &bookworm).as_deref(),
            Some("bookworm-backports")
        );
        assert_eq!(suite(&["a 1.0", "linux-image 6.12~bpo12+1"], &bookworm).as_deref(), Some("bookworm-backports"));
        let trixie = Distribution::Debian { codename: Some("trixie".into()) };
        assert_eq!(suite(&["x 2~bpo13+1"], &trixie).as_deref(), Some("trixie-backports"));
        assert_eq!(suite(&["x 2~bpo12+1"], &trixie).as_deref(), Some("bookworm-backports"), "a bookworm backport");
        let unnamed = Distribution::Debian { codename: None };
        assert_eq!(suite(&["x 2~bpo12+1"], &unnamed).as_deref(), Some("bookworm-backports"));
        assert_eq!(suite(&["qemu-utils 1:7.2+dfsg-7+deb12u18"], &bookworm), None, "not a backport");
        assert_eq!(suite(&["x 2~bpo12+1"], &Distribution::Ubuntu), None, "Debian's backports only");
    }
}
