//! Finding, planning and installing what a command needs, for the image
//! build (`boot/image`), the harness (`tests`) and the xtask alike: the
//! pinned nightly and the other Rust pieces ([`toolchain`]), Debian's
//! packages with apt ([`packages`]: backports for one install where the
//! machine needs it, never a removal) and apt lists of its own
//! ([`apt`]), the emulators and their firmware ([`emulators`]), the
//! browser ([`browser`]), the lab's C libraries ([`libraries`]) and
//! Python's virt-firmware ([`virt_firmware`]); with the child processes
//! they run ([`process`]) and where in the workspace they write
//! ([`workspace`]).
//!
//! It lives under `boot/` beside the image build, its first user: the
//! pinned nightly and Debian's signing tools are what building an image
//! takes. Under `xtask/` it would make the folders import each other
//! (`boot/image` would use `xtask/`, and the xtask uses `boot/image`);
//! here `xtask/` and `tests/` use `boot/` and `boot/` uses neither. It
//! depends on no crate of the workspace, so the image build, the harness
//! and the commands all use it and it uses none of them.
//!
//! Machines here set `RUSTUP_AUTO_INSTALL=0`, so nothing installs
//! itself: each `ensure_*` looks first, installs what is missing saying
//! so, and where it cannot (not root, no apt) fails with the commands to
//! run. A command runs its `ensure_*` together ([`missing::ensure_all`]):
//! a user who is not root then stops once, with the commands for every
//! package the command misses. Debian packages come with their
//! dependencies but without their recommendations: exactly the packages
//! named here, each for the reason its constant says.
//!
//! ```no_run
//! # fn main() -> anyhow::Result<()> {
//! use install::emulators::{ensure_ovmf, ensure_qemu};
//! install::missing::ensure_all(&[ensure_qemu, ensure_ovmf])?;
//! install::toolchain::ensure_toolchain()?;
//! # Ok(())
//! # }
//! ```

pub mod apt;
pub mod browser;
pub mod distribution;
pub mod emulators;
pub mod files;
pub mod lab_art;
pub mod libraries;
pub mod missing;
pub mod once;
pub mod packages;
pub mod process;
pub mod toolchain;
pub mod virt_firmware;
pub mod workspace;
