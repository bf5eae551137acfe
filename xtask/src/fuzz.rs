//! `cargo xtask fuzz [--seconds N] [TARGET]`: coverage-guided fuzzing with
//! libFuzzer through cargo-fuzz, with the pinned nightly. The targets are
//! the `fuzz` crate's (xtask/fuzz; the cargo-fuzz binaries are in
//! xtask/fuzz/targets); each runs for N seconds, one after the other (one
//! fuzzer at a time: the machine is shared). Everything lives under
//! target/fuzz: the seed corpora and dictionaries, written afresh from the
//! built-in scenes on every run, the corpus each target grows and keeps
//! from run to run, the crash inputs, and each run's log. At the end a
//! table gives per target the executions, libFuzzer's coverage figures
//! (`cov`: code edges reached, `ft`: features, edges with hit counts and
//! compared values) and the corpus size; any crash fails the command,
//! naming its input and how to replay it, and so does a fuzzer that ends
//! without success and saves no input (killed by the OOM killer, say),
//! with the reason.

use std::fmt::Write as _;
use std::fs;
use std::io::{BufRead, BufReader, Write as _};
use std::os::unix::process::ExitStatusExt;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitStatus, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use ::fuzz::{Target, TARGETS};
use anyhow::{bail, Context, Result};
use harness::supervisor::Supervised;
use harness::workspace;
use indicatif::{ProgressBar, ProgressStyle};
use install::ensure_cargo_fuzz;
use install::ensure_toolchain;
use install::pinned;
use install::{command_line, run_streaming};

use crate::opt::FuzzOpt;

/// The cargo-fuzz project, from the workspace root.
pub const FUZZ_DIR: &str = "xtask/fuzz/targets";
/// Longest one input may take before libFuzzer calls it a hang: far above
/// any honest input (the slowest, an explorer scene judged by the
/// reference, takes under a second).
const INPUT_TIMEOUT_SECONDS: u32 = 60;

/// Where a target's files go, under target/fuzz.
struct Places {
    root: PathBuf,
}

impl Places {
    fn new() -> Self {
        Self { root: workspace::target_dir().join("fuzz") }
    }

    fn corpus(&self, target: &Target) -> PathBuf {
        self.root.join("corpus").join(target.name)
    }

    fn seeds(&self, target: &Target) -> PathBuf {
        self.root.join("seeds").join(target.name)
    }

    fn dictionary(&self, target: &Target) -> PathBuf {
        self.root.join("dictionaries").join(format!("{}.dict", target.name))
    }

    fn artifacts(&self, target: &Target) -> PathBuf {
        self.root.join("artifacts").join(target.name)
    }

    fn log(&self, target: &Target) -> PathBuf {
        self.log_of(target.name)
    }

    fn log_of(&self, target: &str) -> PathBuf {
        self.root.join("logs").join(format!("{target}.log"))
    }
}

pub fn fuzz(opt: &FuzzOpt) -> Result<()> {
    let targets: Vec<&Target> = match &opt.target {
        Some(name) => vec![::fuzz::target(name).with_context(|| {
            let names: Vec<&str> = TARGETS.iter().map(|target| target.name).collect();
            format!("unknown fuzz target `{name}`; the targets are {}", names.join(", "))
        })?],
        None => TARGETS.iter().collect(),
    };
    ensure_toolchain()?;
    ensure_cargo_fuzz()?;
    let places = Places::new();
    run_streaming(&mut cargo_fuzz("build", &places)).context("failed to build the fuzz targets")?;
    let mut runs = Vec::new();
    for target in targets {
        runs.push(run(target, opt.seconds, &places)?);
    }
    print!("{}", table(&runs));
    let failures: Vec<String> = runs.iter().filter_map(|run| run.failure_report(&places)).collect();
    if !failures.is_empty() {
        bail!("{} of {} targets failed:\n{}", failures.len(), runs.len(), failures.join("\n"));
    }
    Ok(())
}

/// `cargo +<pinned> fuzz ACTION` on the project, building without a
/// sanitizer (the fuzzed crates are safe Rust: raster and scenes forbid
/// `unsafe`, protocol and the explorer's engine use none where inputs
/// go) but, as cargo-fuzz does by default, optimised with debug assertions
/// and overflow checks, so an arithmetic overflow is a crash.
fn cargo_fuzz(action: &str, places: &Places) -> Command {
    let mut command = pinned("cargo");
    command.args(["fuzz", action, "--fuzz-dir", FUZZ_DIR, "--sanitizer", "none", "--target-dir"]).arg(&places.root);
    command
}

/// Writes `target`'s seeds (afresh) and dictionary, then fuzzes it for
/// `seconds`, showing progress, and reads what libFuzzer said.
fn run(target: &Target, seconds: u32, places: &Places) -> Result<FuzzRun> {
    let seeds = places.seeds(target);
    if seeds.exists() {
        fs::remove_dir_all(&seeds).with_context(|| format!("cannot clear {}", seeds.display()))?;
    }
    for dir in [&seeds, &places.corpus(target), &places.artifacts(target), &places.root.join("logs")] {
        fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    }
    for (name, bytes) in (target.seeds)() {
        fs::write(seeds.join(&name), bytes).with_context(|| format!("cannot write seed {name}"))?;
    }
    let mut command = cargo_fuzz("run", places);
    command.arg(target.name).arg(places.corpus(target)).arg(seeds).arg("--");
    command.arg(format!("-max_total_time={seconds}")).arg(format!("-timeout={INPUT_TIMEOUT_SECONDS}"));
    command.arg("-print_final_stats=1");
    // libFuzzer takes the last -artifact_prefix: ours, not cargo-fuzz's
    // folder in the source tree.
    command.arg(format!("-artifact_prefix={}/", places.artifacts(target).display()));
    let words = (target.dictionary)();
    if !words.is_empty() {
        let dictionary = places.dictionary(target);
        fs::create_dir_all(places.root.join("dictionaries"))?;
        fs::write(&dictionary, ::fuzz::dictionary_file(&words))
            .with_context(|| format!("cannot write {}", dictionary.display()))?;
        command.arg(format!("-dict={}", dictionary.display()));
    }
    eprintln!("xtask: fuzzing {} for {seconds} s: {}", target.name, command_line(&command));
    let (lines, status) = watch(&mut command, target.name, seconds, &places.log(target))?;
    let mut run = FuzzRun::read(target.name, &lines, status);
    run.seconds = seconds;
    if run.executions == 0 && run.failure.is_none() {
        bail!("libFuzzer ran no input of {}; its output is in {}", target.name, places.log(target).display());
    }
    Ok(run)
}

/// Runs `command` (under a watchdog: if the xtask dies, cargo-fuzz and
/// the fuzzer go with it) with its standard error read line by line into
/// `log`, a progress bar over `seconds` showing libFuzzer's latest
/// figures. Returns the lines and how the command exited, for the caller
/// to read.
fn watch(command: &mut Command, name: &str, seconds: u32, log: &Path) -> Result<(Vec<String>, ExitStatus)> {
    let mut run = Supervised::without_folder()?;
    let stderr = run.spawn(command.stderr(Stdio::piped()))?.stderr.take().context("no standard error to read")?;
    let (sender, receiver) = mpsc::channel();
    let reader = std::thread::spawn(move || {
        for line in BufReader::new(stderr).lines().map_while(Result::ok) {
            if sender.send(line).is_err() {
                break;
            }
        }
    });
    let mut file = fs::File::create(log).with_context(|| format!("cannot create {}", log.display()))?;
    let bar = ProgressBar::new(u64::from(seconds)).with_prefix(name.to_string());
    bar.set_style(
        ProgressStyle::with_template("{prefix:>15} [{bar:25}] {pos:>4}/{len} s  {msg}")
            .expect("the template is valid")
            .progress_chars("=> "),
    );
    let started = Instant::now();
    let mut lines = Vec::new();
    loop {
        match receiver.recv_timeout(Duration::from_millis(500)) {
            Ok(line) => {
                writeln!(file, "{line}").with_context(|| format!("cannot write {}", log.display()))?;
                if let Some(figures) = Figures::of(&line) {
                    bar.set_message(figures.to_string());
                }
                lines.push(line);
            }
            Err(mpsc::RecvTimeoutError::Timeout) => {}
            Err(mpsc::RecvTimeoutError::Disconnected) => break,
        }
        bar.set_position(started.elapsed().as_secs().min(u64::from(seconds)));
    }
    bar.finish_and_clear();
    reader.join().map_err(|_| anyhow::anyhow!("the reader of {name}'s output panicked"))?;
    let status = run.child().wait().with_context(|| format!("failed to wait for {name}'s fuzzer"))?;
    Ok((lines, status))
}

/// libFuzzer's figures on one of its status lines (`#N NEW cov: C ft: F
/// corp: U/S ...`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
struct Figures {
    executions: u64,
    cov: u64,
    ft: u64,
    corpus: u64,
}

impl Figures {
    fn of(line: &str) -> Option<Self> {
        let executions = line.strip_prefix('#')?.split_whitespace().next()?.parse().ok()?;
        let after = |key: &str| -> Option<&str> { line.split(key).nth(1)?.split_whitespace().next() };
        let number = |key: &str| after(key)?.parse().ok();
        let corpus = after(" corp: ")?.split('/').next()?.parse().ok()?;
        Some(Self { executions, cov: number(" cov: ")?, ft: number(" ft: ")?, corpus })
    }
}

impl std::fmt::Display for Figures {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} runs, cov {}, ft {}, corpus {}", self.executions, self.cov, self.ft, self.corpus)
    }
}

/// What one target's run came to.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
struct FuzzRun {
    target: String,
    seconds: u32,
    /// Inputs run (libFuzzer's final `number_of_executed_units`, or its
    /// last status line's count).
    executions: u64,
    /// The last status line's figures.
    figures: Figures,
    /// How the run failed, if it did.
    failure: Option<Failure>,
}

#[derive(Clone, Debug, PartialEq, Eq)]
enum Failure {
    /// A check failed (or an input ran out of memory or time): libFuzzer
    /// saved the input, and why.
    Crash { input: String, reason: String },
    /// The fuzzer ended without success and saved no input: how it ended,
    /// and the last error it (or cargo-fuzz) printed, if any.
    Exit { status: String, reason: String },
}

impl FuzzRun {
    fn read(target: &str, lines: &[String], status: ExitStatus) -> Self {
        let figures = lines.iter().rev().find_map(|line| Figures::of(line)).unwrap_or_default();
        let stat = |key: &str| lines.iter().find_map(|line| line.strip_prefix(key)?.trim().parse().ok());
        let executions = stat("stat::number_of_executed_units:").unwrap_or(figures.executions);
        let artifact =
            lines.iter().find_map(|line| Some(line.split("Test unit written to ").nth(1)?.trim().to_string()));
        let first = |marks: &[&str]| lines.iter().find(|line| marks.iter().any(|mark| line.contains(mark))).cloned();
        let reason = first(&["panicked at", "ERROR: libFuzzer"]);
        let failure = match artifact {
            Some(input) => Some(Failure::Crash { input, reason: reason.unwrap_or_default() }),
            None if !status.success() => Some(Failure::Exit {
                status: describe(status),
                // cargo-fuzz says how its fuzzer ended on an `Error:` line.
                reason: reason.or_else(|| first(&["Error:", "error:"])).unwrap_or_default(),
            }),
            None => None,
        };
        Self { target: target.to_string(), seconds: 0, executions, figures, failure }
    }

    /// For a run that failed: the target, why, and for a crash the input
    /// and the command that replays it.
    fn failure_report(&self, places: &Places) -> Option<String> {
        match self.failure.as_ref()? {
            Failure::Crash { input, reason } => {
                let replay = format!(
                    "cargo +{} fuzz run --fuzz-dir {FUZZ_DIR} --sanitizer none --target-dir {} {} {input}",
                    install::PINNED_TOOLCHAIN,
                    places.root.display(),
                    self.target
                );
                Some(format!("  {}: {reason}\n    input: {input}\n    replay: {replay}", self.target))
            }
            Failure::Exit { status, reason } => Some(format!(
                "  {}: the fuzzer {status} and saved no input{}\n    its output: {}",
                self.target,
                if reason.is_empty() { String::new() } else { format!(": {reason}") },
                places.log_of(&self.target).display()
            )),
        }
    }
}

/// How a process ended, in words: its exit code, or the signal that
/// killed it (SIGKILL is what the kernel's OOM killer sends).
fn describe(status: ExitStatus) -> String {
    match (status.code(), status.signal()) {
        (Some(code), _) => format!("exited with status {code}"),
        (None, Some(9)) => "was killed by SIGKILL (the kernel's OOM killer sends it)".to_string(),
        (None, Some(signal)) => format!("was killed by signal {signal}"),
        (None, None) => format!("ended ({status})"),
    }
}

/// The closing table: per target the seconds, executions and their rate,
/// coverage, features, corpus and the outcome.
fn table(runs: &[FuzzRun]) -> String {
    let mut text = format!(
        "{:<16} {:>7} {:>12} {:>9} {:>7} {:>8} {:>7}  result\n",
        "target", "seconds", "executions", "exec/s", "cov", "ft", "corpus"
    );
    for run in runs {
        let rate = run.executions / u64::from(run.seconds.max(1));
        let result = match run.failure {
            Some(Failure::Crash { .. }) => "CRASH",
            Some(Failure::Exit { .. }) => "FAILED",
            None => "ok",
        };
        let Figures { cov, ft, corpus, .. } = run.figures;
        // Writing to a String cannot fail.
        let _ = writeln!(
            text,
            "{:<16} {:>7} {:>12} {rate:>9} {cov:>7} {ft:>8} {corpus:>7}  {result}",
            run.target, run.seconds, run.executions
        );
    }
    text
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::opt::{parse_command, Action};

    const LOG: &str = "INFO: Seed: 1234\n\
        #2\tINITED cov: 812 ft: 1630 corp: 96/22Kb exec/s: 0 rss: 44Mb\n\
        #4096\tpulse  cov: 830 ft: 1702 corp: 101/23Kb lim: 4096 exec/s: 2048 rss: 52Mb\n\
        #52311\tDONE   cov: 845 ft: 1790 corp: 118/25Kb lim: 4096 exec/s: 2615 rss: 60Mb\n\
        Done 52311 runs in 20 second(s)\n\
        stat::number_of_executed_units: 52311\n\
        stat::average_exec_per_sec:     2615\n";

    fn lines(text: &str) -> Vec<String> {
        text.lines().map(String::from).collect()
    }

    /// A process's end as `wait` reports it: an exit code, or a signal.
    fn exited(code: i32) -> ExitStatus {
        ExitStatus::from_raw(code << 8)
    }

    fn killed(signal: i32) -> ExitStatus {
        ExitStatus::from_raw(signal)
    }

    #[test]
    fn a_clean_run_reads_as_its_last_figures_and_executions() {
        let run = FuzzRun::read("methods", &lines(LOG), exited(0));
        assert_eq!(run.executions, 52311);
        assert_eq!(run.figures, Figures { executions: 52311, cov: 845, ft: 1790, corpus: 118 });
        assert_eq!(run.failure, None);
    }

    #[test]
    fn a_crash_names_its_input_and_its_panic() {
        let log = "#2\tINITED cov: 10 ft: 10 corp: 1/1b exec/s: 0 rss: 30Mb\n\
            thread '<unnamed>' panicked at xtask/fuzz/src/methods.rs:33:5:\n\
            ==9== ERROR: libFuzzer: deadly signal\n\
            artifact_prefix='target/fuzz/artifacts/methods/'; Test unit written to target/fuzz/artifacts/methods/crash-ab12\n";
        let run = FuzzRun::read("methods", &lines(log), exited(1));
        let Some(Failure::Crash { input, reason }) = run.failure.clone() else { panic!("{:?}", run.failure) };
        assert_eq!(input, "target/fuzz/artifacts/methods/crash-ab12");
        assert!(reason.contains("panicked at xtask/fuzz/src/methods.rs"), "{reason}");
        let report = run.failure_report(&Places { root: PathBuf::from("target/fuzz") }).unwrap();
        assert!(report.contains("fuzz run --fuzz-dir xtask/fuzz/targets --sanitizer none --target-dir target/fuzz methods target/fuzz/artifacts/methods/crash-ab12"), "{report}");
    }

    #[test]
    fn a_fuzzer_that_fails_without_saving_an_input_fails_the_run_with_the_reason() {
        // The OOM killer's SIGKILL to the fuzzer: cargo-fuzz reports it and
        // exits 1; libFuzzer never got to save an input.
        let log = format!("{LOG}Error: Fuzz target exited with signal: 9 (SIGKILL)\n");
        let run = FuzzRun::read("explorer", &lines(&log), exited(1));
        let failure = Failure::Exit {
            status: "exited with status 1".into(),
            reason: "Error: Fuzz target exited with signal: 9 (SIGKILL)".into(),
        };
        assert_eq!(run.failure, Some(failure));
        let report = run.failure_report(&Places { root: PathBuf::from("target/fuzz") }).unwrap();
        assert_eq!(
            report,
            "  explorer: the fuzzer exited with status 1 and saved no input: Error: Fuzz target exited with signal: \
             9 (SIGKILL)\n    its output: target/fuzz/logs/explorer.log"
        );
        // cargo-fuzz itself killed, with nothing said.
        let run = FuzzRun::read("explorer", &lines(LOG), killed(9));
        let report = run.failure_report(&Places { root: PathBuf::from("target/fuzz") }).unwrap();
        assert!(
            report.contains("was killed by SIGKILL (the kernel's OOM killer sends it) and saved no input"),
            "{report}"
        );
        let mut run = FuzzRun::read("explorer", &lines(LOG), killed(9));
        run.seconds = 20;
        assert!(table(&[run]).lines().nth(1).unwrap().ends_with("FAILED"));
    }

    #[test]
    fn the_table_gives_each_target_its_executions_rate_and_coverage() {
        let mut run = FuzzRun::read("methods", &lines(LOG), exited(0));
        run.seconds = 20;
        let table = table(&[run]);
        assert_eq!(
            table.lines().nth(1).unwrap().split_whitespace().collect::<Vec<_>>(),
            ["methods", "20", "52311", "2615", "845", "1790", "118", "ok"]
        );
    }

    #[test]
    fn the_command_takes_seconds_and_a_target() {
        let Ok(Action::Fuzz(opt)) = parse_command("fuzz", &["--seconds", "20", "methods"]) else { panic!() };
        assert_eq!((opt.seconds, opt.target.as_deref()), (20, Some("methods")));
        assert!(parse_command("fuzz", &["--seconds", "0"]).is_err());
    }

    #[test]
    fn every_target_has_a_cargo_fuzz_binary() {
        let manifest = fs::read_to_string(workspace::root().join(FUZZ_DIR).join("Cargo.toml")).unwrap();
        for target in &TARGETS {
            assert!(manifest.contains(&format!("name = \"{}\"", target.name)), "{}", target.name);
            assert!(workspace::root().join(FUZZ_DIR).join(format!("fuzz_targets/{}.rs", target.name)).exists());
        }
    }
}
