//! `cargo xtask test`: everything, the QEMU harness included. The test
//! binaries run side by side (`schedule.rs`), the longest first
//! (`order.rs`); a run whose arguments the runner does not understand
//! (`selection.rs`) is left to `cargo test`, one binary after another.

mod order;
mod schedule;
mod selection;
mod units;

use anyhow::Result;
use boot_image::process::run_streaming;
use boot_image::toolchain::ensure_toolchain;
use boot_image::{build_image, IMAGE_ENV};
use harness::prerequisites::{
    ensure_bochs, ensure_cairo, ensure_chromium, ensure_ovmf, ensure_peer_libraries, ensure_qemu, ensure_qemu_qxl,
    ensure_secure_boot_ovmf, ensure_virt_fw_vars, ensure_wasm_target,
};

use crate::opt::TestOpt;
use selection::Selection;
use units::cargo_test;

/// Tests run at once beyond one per core: a QEMU test spends part of its
/// time waiting (for QEMU's disk reads at boot, for a reply on the serial
/// line), in which another test's QEMU can run.
const JOBS_BEYOND_CORES: usize = 1;

pub fn test(opt: &TestOpt) -> Result<()> {
    ensure_toolchain()?;
    // A whole run installs what its tests need up front, so that nothing
    // installs in the middle of their output; a chosen few install their
    // own, when they start QEMU, Bochs or a browser (`prerequisites`).
    if is_whole_run(&opt.cargo_args) {
        ensure_qemu()?;
        // The adapter matrix runs QEMU's QXL card, a module of its own in
        // Debian's QEMU 8 and later.
        ensure_qemu_qxl()?;
        // The adapter matrix boots OVMF too, and one test boots Bochs.
        ensure_ovmf()?;
        // The Secure Boot tests boot OVMF's Secure Boot build and write MOK
        // lists into its variable store with virt-fw-vars.
        ensure_secure_boot_ovmf()?;
        ensure_virt_fw_vars()?;
        ensure_bochs()?;
        // The explorer page's tests: its engine is built for wasm32 and
        // run in headless Chromium.
        ensure_wasm_target()?;
        ensure_chromium()?;
    }
    // The lab, a workspace member, builds its peers against libcairo,
    // Allegro 4, SDL2 with SDL2_gfx, and GD: needed before cargo compiles
    // it, which no test can do for itself.
    if builds_the_lab(&opt.cargo_args) {
        ensure_cairo()?;
        ensure_peer_libraries()?;
    }
    let image = build_image()?;
    let Some(selection) = Selection::parse(&opt.cargo_args) else {
        return run_streaming(cargo_test(&opt.cargo_args).env(IMAGE_ENV, image));
    };
    let threads = std::thread::available_parallelism().map_or(1, usize::from);
    let jobs = opt.jobs.map_or(threads + JOBS_BEYOND_CORES, usize::from);
    let mut units = units::units(&selection, &image)?;
    match units.len() {
        0 => anyhow::bail!("`cargo test` built no test binary for {:?}", opt.cargo_args),
        1 => schedule::run_alone(&units.remove(0), threads),
        _ => schedule::run(units, jobs, threads),
    }
}

/// The arguments for cargo itself: those before a `--` (after it they
/// are the test binaries').
fn cargo_part(cargo_args: &[String]) -> &[String] {
    let end = cargo_args.iter().position(|arg| arg == "--").unwrap_or(cargo_args.len());
    &cargo_args[..end]
}

/// Whether `cargo test` runs every test: no package, target or name is
/// chosen.
fn is_whole_run(cargo_args: &[String]) -> bool {
    cargo_part(cargo_args).is_empty()
}

/// Whether `cargo test --workspace ARGS` compiles the lab crate: unless
/// the arguments choose only integration tests by name (`--test NAME`;
/// the lab has none) or only packages other than the lab.
fn builds_the_lab(cargo_args: &[String]) -> bool {
    let args = cargo_part(cargo_args);
    let packages: Vec<&str> = values_of(args, &["--package", "-p"]).collect();
    let other_targets = ["--lib", "--bins", "--benches", "--all-targets", "--doc"];
    let tests_only =
        values_of(args, &["--test"]).next().is_some() && !args.iter().any(|arg| other_targets.contains(&arg.as_str()));
    (packages.is_empty() || packages.contains(&"lab")) && !tests_only
}

/// The values `args` gives any of `flags`, as `FLAG VALUE` or `FLAG=VALUE`.
fn values_of<'a>(args: &'a [String], flags: &'a [&str]) -> impl Iterator<Item = &'a str> {
    args.iter().enumerate().filter_map(move |(at, arg)| {
        flags.iter().find_map(|flag| match arg.strip_prefix(flag)? {
            "" => args.get(at + 1).map(String::as_str),
            value => value.strip_prefix('='),
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use boot_image::process::command_line;

    fn args(line: &str) -> Vec<String> {
        line.split_whitespace().map(String::from).collect()
    }

    #[test]
    fn extra_arguments_go_to_cargo_test() {
        let command = cargo_test(&["--test".into(), "pages".into(), "--".into(), "--nocapture".into()]);
        assert!(
            command_line(&command)
                .ends_with(" test --workspace --exclude kernel --exclude boot --test pages -- --nocapture"),
            "{}",
            command_line(&command)
        );
        assert_eq!(command.get_current_dir(), Some(boot_image::workspace::root()));
    }

    #[test]
    fn only_a_whole_run_installs_everything_up_front() {
        assert!(is_whole_run(&args("")));
        assert!(is_whole_run(&args("-- --nocapture")));
        assert!(!is_whole_run(&args("--test pages")));
        assert!(!is_whole_run(&args("every_page -- --nocapture")));
    }

    #[test]
    fn cairo_is_installed_only_when_the_lab_is_compiled() {
        for chosen in ["--test pages", "--test=pages --test bochs", "-p harness", "--package=xtask --lib"] {
            assert!(!builds_the_lab(&args(chosen)), "{chosen}");
        }
        for all in ["", "-- --test pages", "every_page", "-p lab", "--package=lab", "--test pages --lib"] {
            assert!(builds_the_lab(&args(all)), "{all}");
        }
    }
}
