//! The third-party art in the lab's corpus: the country flags of Debian's
//! `iso-flags-svg` (Linux Mint's flags, dedicated to the public domain by
//! their author, Debian's copyright file says), many of them with coats of
//! arms of hundreds to thousands of vertices in many contours. The art is
//! installed from Debian, never committed; `lab` and `test` (which runs
//! the lab's tests) ensure it ([`ensure_lab_art`]).

use std::path::Path;
use std::sync::OnceLock;

use anyhow::Result;

use crate::once::{once_per_process, Failure};
use crate::packages::ensure_debian_packages;

/// The Debian package of the flags.
pub const FLAGS_PACKAGE: &str = "iso-flags-svg";
/// Where it puts the flags drawn in 4:3, one SVG file a country, named by
/// its ISO 3166 code (`bt.svg`).
pub const FLAGS_DIR: &str = "/usr/share/iso-flags-svg/country-4x3";
/// Makes sure the flags are there: installs Debian's [`FLAGS_PACKAGE`]
/// when [`FLAGS_DIR`] is missing ([`ensure_debian_packages`]: with apt-get
/// as root, else failing with the exact commands to run).
pub fn ensure_lab_art() -> Result<()> {
    static DONE: OnceLock<Result<(), Failure>> = OnceLock::new();
    once_per_process(&DONE, || {
        let found = || Path::new(FLAGS_DIR).is_dir();
        ensure_debian_packages("the flag set iso-flags-svg (for the lab's third-party family)", &[FLAGS_PACKAGE], found)
    })
}
