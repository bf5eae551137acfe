//! `cargo xtask check --serial DEVICE [--out DIR]`: the harness's checks on
//! a machine at the other end of a serial cable (`harness::serial_check`),
//! with a progress bar, every retry said as it happens, and
//! `DIR/report.md` and `DIR/report.json` written at the end. Exits
//! non-zero if any picture differs.

use std::path::absolute;
use std::time::Duration;

use anyhow::{bail, Context, Result};
use harness::cable::open_console;
use harness::serial_check::{self, write_reports, CheckOptions, Progress, Scope};
use indicatif::{ProgressBar, ProgressStyle};

use crate::opt::CheckOpt;

pub fn check(opt: &CheckOpt) -> Result<()> {
    let out = absolute(&opt.out).with_context(|| format!("bad output directory {}", opt.out.display()))?;
    let device = opt.serial.display().to_string();
    let mut scope = if opt.quick { Scope::quick() } else { Scope::full() };
    scope.files = opt.files.read()?.into_iter().map(|file| file.scene).collect();
    let mut console = open_console(&opt.serial, opt.retries)?;
    let options = CheckOptions { scope, repeats: opt.repeats, wait: Duration::from_secs(opt.wait) };
    eprintln!(
        "check: {device}: {} pictures, VGACHECK, BENCH of {} scenes; each step retried at most {} times",
        options.scope.pictures(),
        options.scope.benched().len(),
        opt.retries
    );
    let bar = ProgressBar::new(0);
    bar.set_style(
        ProgressStyle::with_template("check [{bar:30}] {pos}/{len} {elapsed_precise} (eta {eta})  {msg}")
            .expect("the template is valid")
            .progress_chars("=> "),
    );
    let mut said = 0;
    let report = serial_check::run(&mut console, &device, &options, |progress: &Progress| {
        bar.set_length(progress.total as u64);
        bar.set_position(progress.done as u64);
        let retries = progress.stats.map_or(0, |stats| stats.retries);
        bar.set_message(format!("{} (retries so far: {retries})", progress.step));
        let log = progress.stats.map_or(&[][..], |stats| &stats.log[..]);
        for trouble in log.get(said..).unwrap_or_default() {
            bar.println(format!("check: retrying after {trouble}"));
        }
        said = log.len();
    });
    bar.finish_and_clear();
    let report = report?;
    let (md, json) = write_reports(&report, &out)?;
    println!(
        "{} pictures compared, {} differ; {} steps retried; {:.1} s",
        report.pictures.len(),
        report.differing().count(),
        report.stats.retries,
        report.elapsed.as_secs_f64()
    );
    println!("{}", md.display());
    println!("{}", json.display());
    let differing: Vec<String> = report
        .differing()
        .map(|picture| format!("{} with {}: {} pixels", picture.scene, picture.method, picture.differing_pixels))
        .collect();
    if !differing.is_empty() {
        bail!("{} pictures differ from the host render:\n{}", differing.len(), differing.join("\n"));
    }
    Ok(())
}
