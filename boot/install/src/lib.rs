//! Finding, planning and installing what a command needs, for the image
//! build (`boot/image`), the harness (`xtask/harness`) and the xtask alike: the
//! pinned nightly and the other Rust pieces (`toolchain.rs`), Debian's
//! packages with apt (`packages.rs`: backports for one install where the
//! machine needs it, never a removal) and apt lists of its own
//! (`apt.rs`), the emulators and their firmware (`emulators.rs`), the
//! browser (`browser.rs`), the lab's C libraries (`libraries.rs`) and
//! Python's virt-firmware (`virt_firmware.rs`); with the child processes
//! they run (`process.rs`) and where in the workspace they write
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
//! run. A command runs its `ensure_*` together ([`ensure_all`]):
//! a user who is not root then stops once, with the commands for every
//! package the command misses. Debian packages come with their
//! dependencies but without their recommendations: exactly the packages
//! named here, each for the reason its constant says.
//!
//! ```no_run
//! # fn main() -> anyhow::Result<()> {
//! use install::{ensure_ovmf, ensure_qemu};
//! install::ensure_all(&[ensure_qemu, ensure_ovmf])?;
//! install::ensure_toolchain()?;
//! # Ok(())
//! # }
//! ```

// One face: the modules are private and what the other crates use is
// re-exported here, each item at one path; `workspace` stays a namespace,
// its items called by its name (`workspace::root()`, `workspace::target_dir()`).
mod apt;
mod browser;
mod distribution;
mod emulators;
mod files;
mod lab_art;
mod libraries;
mod missing;
mod once;
mod packages;
mod process;
mod toolchain;
mod virt_firmware;
pub mod workspace;

pub use apt::{PrivateApt, DEBIAN_KEYRING};
pub use browser::{chromedriver, chromium, ensure_chromium};
pub use emulators::{
    ensure_bochs, ensure_ovmf, ensure_qemu, ensure_qemu_qxl, ensure_qemu_window, ensure_secure_boot_ovmf, ovmf_code,
    ovmf_microsoft_vars, ovmf_secure_boot_code, ovmf_vars, BOCHS, BOCHS_BIOS, BOCHS_BIOS_ENV, BOCHS_CIRRUS_VGA_BIOS,
    BOCHS_CIRRUS_VGA_BIOS_ENV, QEMU,
};
pub use files::system_file;
pub use lab_art::{ensure_lab_art, FLAGS_DIR, FLAGS_PACKAGE};
pub use libraries::ensure_lab_libraries;
pub use missing::{ensure_all, MissingPackages, Step};
pub use once::{once_per_process, turn, turn_in, Failure};
pub use packages::ensure_debian_packages;
pub use process::{command_line, find_in_path, is_root, output_of, output_with_input, run_streaming, user_id};
pub use toolchain::{
    ensure_cargo_fuzz, ensure_cxx, ensure_thumb_target, ensure_toolchain, ensure_wasm_target, host, pinned,
    KERNEL_TARGET, PINNED_TOOLCHAIN, THUMB_TARGET, WASM_TARGET,
};
pub use virt_firmware::ensure_virt_fw_vars;
