//! `cargo xtask test`: everything, the QEMU harness included. The test
//! binaries run side by side (`schedule.rs`), the longest first
//! (`order.rs`); a run whose arguments the runner does not understand
//! (`selection.rs`) is left to `cargo test`, one binary after another.

mod order;
mod schedule;
mod selection;
mod units;

use anyhow::Result;
use boot_image::{build_image, IMAGE_ENV};
use install::ensure_chromium;
use install::ensure_lab_art;
use install::ensure_lab_libraries;
use install::ensure_toolchain;
use install::ensure_virt_fw_vars;
use install::ensure_wasm_target;
use install::run_streaming;
use install::{ensure_all, Step};
use install::{ensure_bochs, ensure_ovmf, ensure_qemu, ensure_qemu_qxl, ensure_secure_boot_ovmf};

use crate::opt::TestOpt;
use selection::{cargo_part, Selection};
use units::cargo_test;

/// Tests run at once per core, by default. A QEMU test spends much of its
/// time waiting (for a reply, a deadline, a show watched at its pace): run
/// alone with one test thread per core, serial_check kept 0.55 of a core
/// busy over its run, secure_boot 0.37, clock 0.48, loader_refusals 0.54
/// (user and system time over wall time, load 3.4 to 9); a binary's
/// tests run two at a time on this machine, so at two tests per core only
/// two such binaries run at once, about a core's worth of work for two
/// cores. Three per core keeps three of them running.
const JOBS_PER_CORE: usize = 3;

/// What a whole run installs before its tests start (so that nothing
/// installs in the middle of their output; a chosen few install their
/// own, when they start QEMU, Bochs or a browser: `install`), in order.
const WHOLE_RUN: [Step; 8] = [
    ensure_qemu,
    // The adapter matrix runs QEMU's QXL card, a module of its own in
    // Debian's QEMU 8 and later.
    ensure_qemu_qxl,
    // The adapter matrix boots OVMF too, and one test boots Bochs.
    ensure_ovmf,
    // The Secure Boot tests boot OVMF's Secure Boot build and write MOK
    // lists into its variable store with virt-fw-vars.
    ensure_secure_boot_ovmf,
    || ensure_virt_fw_vars().map(drop),
    ensure_bochs,
    // The explorer page's tests: its engine is built for wasm32 and run
    // in headless Chromium.
    ensure_wasm_target,
    ensure_chromium,
];

pub fn test(opt: &TestOpt) -> Result<()> {
    ensure_toolchain()?;
    let run_needs: &[Step] = if is_whole_run(&opt.cargo_args) { &WHOLE_RUN } else { &[] };
    // The lab, a workspace member, builds its peers against libcairo,
    // Allegro 4, SDL2 with SDL2_gfx, and GD: needed before cargo compiles
    // it, which no test can do for itself; its corpus's tests read the
    // flags of its third-party family.
    if builds_the_lab(&opt.cargo_args) {
        ensure_now_or_all_at_once(ensure_lab_needs, run_needs)?;
    }
    let Some(selection) = Selection::parse(&opt.cargo_args) else {
        let image = install_and_build_image(run_needs)?;
        return run_streaming(cargo_test(&opt.cargo_args).env(IMAGE_ENV, image));
    };
    // The test binaries (stable, target/debug) build while the packages
    // install and then the image builds (the pinned nightly, its own
    // target folder): installing mostly waits on the network, and each
    // build has stretches that keep one core busy or none (linking; the
    // bootloader's stages, one after another), which the other fills.
    let build = units::Build::start(&selection)?;
    let image = match install_and_build_image(run_needs) {
        Ok(image) => image,
        Err(error) => {
            build.stop();
            return Err(error);
        }
    };
    let mut units = build.finish()?;
    let threads = std::thread::available_parallelism().map_or(1, usize::from);
    let jobs = opt.jobs.map_or(threads * JOBS_PER_CORE, usize::from);
    match units.len() {
        0 => anyhow::bail!("`cargo test` built no test binary for {:?}", opt.cargo_args),
        1 => schedule::run_alone(&units.remove(0), &image, threads),
        _ => schedule::run(units, &image, jobs, threads),
    }
}

/// Installs what cargo needs before it compiles (`now`), leaving `later`
/// to install once the build has started, while it runs. Where `now`
/// fails, `later` is looked at too, and its missing packages join `now`'s
/// (a user who is not root): the one stop names every package the
/// command misses. `now` keeps its outcome (once per process), so the
/// second look at it fails as the first did.
fn ensure_now_or_all_at_once(now: Step, later: &[Step]) -> Result<()> {
    if let Err(error) = now() {
        ensure_all(&[&[now], later].concat())?;
        return Err(error);
    }
    Ok(())
}

/// What building and testing the lab needs: its peers' C libraries and
/// the flags of its third-party family.
fn ensure_lab_needs() -> Result<()> {
    ensure_all(&[ensure_lab_libraries, ensure_lab_art])
}

/// Installs what the run's tests need (`needs`: [`WHOLE_RUN`] for a whole
/// run), a user who is not root told every missing package at once;
/// then builds the image.
fn install_and_build_image(needs: &[Step]) -> Result<std::path::PathBuf> {
    ensure_all(needs)?;
    build_image()
}

/// Whether `cargo test` runs every test: no package, target or name is
/// chosen.
fn is_whole_run(cargo_args: &[String]) -> bool {
    cargo_part(cargo_args).is_empty()
}

/// Whether `cargo test --workspace ARGS` compiles the lab crate: unless
/// the arguments choose only integration tests by name (`--test NAME`)
/// none of which is the lab's (a file in `xtask/lab/tests/`), or only
/// packages other than the lab.
fn builds_the_lab(cargo_args: &[String]) -> bool {
    let args = cargo_part(cargo_args);
    let packages: Vec<&str> = values_of(args, &["--package", "-p"]).collect();
    let other_targets = ["--lib", "--bins", "--benches", "--all-targets", "--doc"];
    let tests: Vec<&str> = values_of(args, &["--test"]).collect();
    let lab_tests = install::workspace::root().join("xtask/lab/tests");
    let others_only = !tests.is_empty()
        && !args.iter().any(|arg| other_targets.contains(&arg.as_str()))
        && !tests.iter().any(|name| lab_tests.join(format!("{name}.rs")).is_file());
    (packages.is_empty() || packages.contains(&"lab")) && !others_only
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
    use std::sync::atomic::{AtomicUsize, Ordering};

    use super::*;
    use install::command_line;
    use install::MissingPackages;

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
        assert_eq!(command.get_current_dir(), Some(install::workspace::root()));
        // With --workspace, cargo would test every package whatever -p says.
        for chosen in ["-p harness --lib", "--package=raster -- --nocapture"] {
            let line = command_line(&cargo_test(&args(chosen)));
            assert!(line.ends_with(&format!(" test {chosen}")), "{line}");
        }
    }

    #[test]
    fn the_command_line_gives_cargo_and_the_test_binaries_their_parts() {
        let parse = |line: &str| match crate::opt::parse_command("test", &line.split_whitespace().collect::<Vec<_>>()) {
            Ok(crate::opt::Action::Test(opt)) => (opt.jobs, opt.cargo_args),
            other => panic!("{line}: {other:?}"),
        };
        assert_eq!(parse("-- --test pages"), (None, args("--test pages")));
        assert_eq!(parse("--jobs 3 -- --test pages -- --nocapture"), (Some(3), args("--test pages -- --nocapture")));
        assert_eq!(parse("-- -- --nocapture"), (None, args("-- --nocapture")));
        assert!(crate::opt::parse_command("test", &["--jobs", "0"]).is_err());
    }

    #[test]
    fn only_a_whole_run_installs_everything_up_front() {
        assert!(is_whole_run(&args("")));
        assert!(is_whole_run(&args("-- --nocapture")));
        assert!(!is_whole_run(&args("--test pages")));
        assert!(!is_whole_run(&args("every_page -- --nocapture")));
    }

    fn missing(what: &str, package: &str) -> Result<()> {
        Err(MissingPackages::new(what, &[package.to_string()], None).into())
    }

    static LEFT_FOR_LATER: AtomicUsize = AtomicUsize::new(0);

    #[test]
    fn missing_lab_libraries_stop_once_naming_the_whole_runs_missing_packages_too() {
        let lab: Step = || missing("libcairo", "libcairo2-dev");
        let run: [Step; 3] = [|| missing("QEMU", "qemu-system-x86"), || Ok(()), || missing("Bochs", "bochs")];
        let message = format!("{:#}", ensure_now_or_all_at_once(lab, &run).unwrap_err());
        assert!(
            message.contains(
                "\n    sudo apt-get update\n    \
                 sudo apt-get install --no-install-recommends libcairo2-dev qemu-system-x86 bochs"
            ),
            "{message}"
        );
        assert_eq!(message.matches("apt-get install").count(), 1, "{message}");
        // With the lab's libraries there, the run's needs are left to
        // install while the build runs.
        let later: Step = || {
            LEFT_FOR_LATER.fetch_add(1, Ordering::SeqCst);
            missing("QEMU", "qemu-system-x86")
        };
        ensure_now_or_all_at_once(|| Ok(()), &[later]).unwrap();
        assert_eq!(LEFT_FOR_LATER.load(Ordering::SeqCst), 0);
        // Any other failure stops with its own error.
        let broken: Step = || anyhow::bail!("pkg-config crashed");
        let error = ensure_now_or_all_at_once(broken, &run).unwrap_err();
        assert_eq!(format!("{error:#}"), "pkg-config crashed");
    }

    #[test]
    fn cairo_is_installed_only_when_the_lab_is_compiled() {
        for chosen in ["--test pages", "--test=pages --test bochs", "-p harness", "--package=xtask --lib"] {
            assert!(!builds_the_lab(&args(chosen)), "{chosen}");
        }
        let lab_tests = ["--test scene", "--test=pages --test scene"];
        for all in ["", "-- --test pages", "every_page", "-p lab", "--package=lab", "--test pages --lib"]
            .iter()
            .chain(&lab_tests)
        {
            assert!(builds_the_lab(&args(all)), "{all}");
        }
    }
}
