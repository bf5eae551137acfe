//! The browser the explorer's tests drive and its WebDriver server:
//! Debian's Chromium and chromedriver, unless the variables name others
//! (a path, or a program on the PATH), such as Google Chrome and its
//! chromedriver.

use std::path::PathBuf;
use std::sync::OnceLock;

use anyhow::{anyhow, ensure, Result};

use crate::files::program;
use crate::missing::MissingPackages;
use crate::once::{once_per_process, Failure};
use crate::packages::ensure_debian_packages;

pub const CHROMIUM: &str = "chromium";
pub const CHROMEDRIVER: &str = "chromedriver";
pub const CHROMIUM_ENV: &str = "POLYLAB_CHROMIUM";
pub const CHROMEDRIVER_ENV: &str = "POLYLAB_CHROMEDRIVER";
const CHROMIUM_PACKAGES: [&str; 2] = ["chromium", "chromium-driver"];

/// Where the browser ([`CHROMIUM_ENV`], else `chromium` on the PATH) and
/// its driver ([`CHROMEDRIVER_ENV`], else `chromedriver`) are.
pub fn chromium() -> Option<PathBuf> {
    program(CHROMIUM_ENV, CHROMIUM)
}

pub fn chromedriver() -> Option<PathBuf> {
    program(CHROMEDRIVER_ENV, CHROMEDRIVER)
}

/// Makes sure the browser and its driver are there, installing Debian's
/// `chromium` and `chromium-driver` ([`ensure_debian_packages`]) unless
/// the variables name others, which must then exist. Where that cannot
/// be done here (Ubuntu has Chromium only as a snap), the error says how
/// to name a browser of one's own.
pub fn ensure_chromium() -> Result<()> {
    static DONE: OnceLock<Result<(), Failure>> = OnceLock::new();
    once_per_process(&DONE, || {
        for (env, found) in [(CHROMIUM_ENV, chromium()), (CHROMEDRIVER_ENV, chromedriver())] {
            if let Some(named) = std::env::var_os(env).filter(|named| !named.is_empty()) {
                ensure!(found.is_some(), "{env} names {}, which is not a program", named.to_string_lossy());
            }
        }
        ensure_debian_packages("Chromium (chromium and chromedriver)", &CHROMIUM_PACKAGES, || {
            chromium().is_some() && chromedriver().is_some()
        })
        .map_err(|error| match error.downcast::<MissingPackages>() {
            Ok(missing) => missing.or_instead(own_browser()).into(),
            Err(error) => anyhow!("{error:#}\n{}", own_browser()),
        })
    })
}

/// How to use a browser of one's own instead.
fn own_browser() -> String {
    format!(
        "Or install Chromium or Google Chrome and the chromedriver of the same version (Chrome for Testing has \
         both), then put them on the PATH as `{CHROMIUM}` and `{CHROMEDRIVER}`, or name them with {CHROMIUM_ENV} \
         and {CHROMEDRIVER_ENV}"
    )
}
