//! The C libraries the lab's peers build and link with, found by
//! pkg-config: Cairo (the `cairo-rs` peer), Allegro 4 (`polygon()`), SDL2
//! with its gfx add-on (`filledPolygonRGBA`) and GD
//! (`gdImageFilledPolygon`), each with its headers and `.pc` file, and
//! pkg-config, which finds them. `lab`, `test` and `lint` build the lab,
//! and ensure them all first ([`ensure_lab_libraries`]).

use std::process::Command;
use std::sync::OnceLock;

use anyhow::Result;

use crate::missing::ensure_all;
use crate::once::{once_per_process, Failure};
use crate::packages::ensure_debian_packages;

/// The Debian packages the lab's Cairo peer (`cairo-rs` over the system
/// libcairo) builds with.
const CAIRO_PACKAGES: [&str; 2] = ["libcairo2-dev", "pkg-config"];

/// The Debian packages of the lab's C peers.
const PEER_PACKAGES: [&str; 5] = ["liballegro4-dev", "libsdl2-dev", "libsdl2-gfx-dev", "libgd-dev", "pkg-config"];
/// Their pkg-config names, all of which must be found.
const PEER_PKG_CONFIG: [&str; 4] = ["allegro", "sdl2", "SDL2_gfx", "gdlib"];

/// Makes sure the C libraries of every peer of the lab are there, as it
/// needs to build ([`ensure_cairo`], [`ensure_peer_libraries`]): a user
/// who is not root is told the packages of both at once.
pub fn ensure_lab_libraries() -> Result<()> {
    ensure_all(&[ensure_cairo, ensure_peer_libraries])
}

/// Makes sure libcairo's headers are there for `pkg-config --exists cairo`,
/// as the lab's Cairo peer needs to build: installs Debian's
/// `libcairo2-dev` (and `pkg-config`) ([`ensure_debian_packages`]: with
/// apt-get as root, else failing with the exact commands to run).
fn ensure_cairo() -> Result<()> {
    static DONE: OnceLock<Result<(), Failure>> = OnceLock::new();
    once_per_process(&DONE, || {
        let found = || Command::new("pkg-config").args(["--exists", "cairo"]).status().is_ok_and(|s| s.success());
        ensure_debian_packages("libcairo (for the lab's Cairo peer)", &CAIRO_PACKAGES, found)
    })
}

/// Makes sure the C libraries of the lab's Allegro, SDL2_gfx and GD peers
/// are there for `pkg-config --exists`, as the lab needs to build:
/// installs their Debian `-dev` packages as [`ensure_cairo`] installs
/// Cairo's.
fn ensure_peer_libraries() -> Result<()> {
    static DONE: OnceLock<Result<(), Failure>> = OnceLock::new();
    once_per_process(&DONE, || {
        let found =
            || Command::new("pkg-config").arg("--exists").args(PEER_PKG_CONFIG).status().is_ok_and(|s| s.success());
        ensure_debian_packages("Allegro 4, SDL2_gfx and GD (for the lab's C peers)", &PEER_PACKAGES, found)
    })
}
