//! Running the units side by side: the longest first, as many tests at
//! once as the machine is given (`--jobs`), each unit's output kept and
//! printed whole when it ends, so that the log reads as `cargo test`'s
//! does, one binary after another, with its `test result:` lines.
//!
//! A unit holds as many of the jobs as tests it can still run at once
//! (its test threads, fewer once fewer tests are left: the runner counts
//! the `test NAME ... ok` lines libtest prints as each test ends), and
//! the next unit in order that fits starts as soon as jobs are free.

use std::io::{BufRead, BufReader, Write};
use std::path::Path;
use std::process::{Command, ExitStatus};
use std::sync::mpsc::{channel, Receiver, RecvTimeoutError, Sender};
use std::time::{Duration, Instant};

use anyhow::{bail, Context, Result};
use harness::supervisor::Supervised;
use install::command_line;

use super::units::Unit;

/// How often the runner says what is still running, when nothing ended.
const STILL_RUNNING_EVERY: Duration = Duration::from_secs(120);

/// The test threads `unit` runs with: as its arguments say, else one per
/// test up to `threads`.
fn width(unit: &Unit, threads: usize) -> usize {
    unit.fixed_threads().unwrap_or(unit.tests.unwrap_or(threads).clamp(1, threads))
}

/// What a unit's reader thread reports.
enum Event {
    /// One of its tests ended.
    TestEnded(usize),
    /// It exited (or could not be waited for), with everything it printed.
    Ended { unit: usize, status: std::io::Result<ExitStatus>, output: Vec<u8> },
}

/// A unit that is running.
struct Running {
    started: Instant,
    /// Jobs it holds now.
    holds: usize,
    /// Tests still to end, if known.
    left: Option<usize>,
}

/// How one unit ended.
struct Outcome {
    seconds: f64,
    passed: bool,
}

/// Runs `units`, at most `jobs` tests at once, each unit with as many
/// test threads as it has tests up to `threads`; fails naming every unit
/// that failed.
pub fn run(mut units: Vec<Unit>, image: &Path, jobs: usize, threads: usize) -> Result<()> {
    let started = Instant::now();
    // Longest first, so that the last to end is a short one.
    units.sort_by_key(|unit| std::cmp::Reverse(unit.expected_seconds()));
    let widths: Vec<usize> = units.iter().map(|unit| width(unit, threads)).collect();
    let tests: usize = units.iter().filter_map(|unit| unit.tests).sum();
    eprintln!(
        "xtask: {} test binaries{} ({tests} tests listed), up to {jobs} tests at once, the longest first",
        units.iter().filter(|unit| unit.tests.is_some()).count(),
        if units.iter().any(|unit| unit.tests.is_none()) { " and the doc tests" } else { "" },
    );
    let (sender, events) = channel();
    let mut waiting: Vec<usize> = (0..units.len()).collect();
    let mut running: Vec<Option<Running>> = units.iter().map(|_| None).collect();
    let mut outcomes: Vec<Option<Outcome>> = units.iter().map(|_| None).collect();
    let mut free = jobs;
    while !waiting.is_empty() || running.iter().any(Option::is_some) {
        // The first waiting unit that fits; with nothing running, the
        // first one whatever its width.
        while let Some(at) =
            waiting.iter().position(|&unit| widths[unit].min(jobs) <= free || running.iter().all(Option::is_none))
        {
            let unit = waiting.remove(at);
            let holds = widths[unit].min(free.max(1));
            start(&units[unit], unit, units[unit].command(widths[unit], image), sender.clone())?;
            free = free.saturating_sub(holds);
            running[unit] = Some(Running { started: Instant::now(), holds, left: units[unit].tests });
        }
        match next_event(&events, &units, &running)? {
            Event::TestEnded(unit) => {
                let Some(run) = running[unit].as_mut() else { continue };
                if let Some(left) = run.left.as_mut() {
                    *left = left.saturating_sub(1);
                    let holds = run.holds.min((*left).max(1));
                    free += run.holds - holds;
                    run.holds = holds;
                }
            }
            Event::Ended { unit, status, output } => {
                let run = running[unit].take().expect("a unit ends once");
                free += run.holds;
                let seconds = run.started.elapsed().as_secs_f64();
                let passed = status.as_ref().is_ok_and(ExitStatus::success);
                report(&units[unit], &output, &status, seconds)?;
                outcomes[unit] = Some(Outcome { seconds, passed });
                let left = waiting.len() + running.iter().filter(|run| run.is_some()).count();
                eprintln!(
                    "xtask: {} {} in {seconds:.1} s; {left} to go, {:.0} s in",
                    if passed { "passed:" } else { "FAILED:" },
                    units[unit].title,
                    started.elapsed().as_secs_f64()
                );
            }
        }
    }
    summary(&units, &outcomes, started.elapsed())
}

/// The next event; every [`STILL_RUNNING_EVERY`] without one, says what
/// is running and for how long.
fn next_event(events: &Receiver<Event>, units: &[Unit], running: &[Option<Running>]) -> Result<Event> {
    loop {
        match events.recv_timeout(STILL_RUNNING_EVERY) {
            Ok(event) => return Ok(event),
            Err(RecvTimeoutError::Timeout) => {
                let now: Vec<String> = running
                    .iter()
                    .zip(units)
                    .filter_map(|(run, unit)| {
                        run.as_ref().map(|run| format!("{} ({} s)", unit.title, run.started.elapsed().as_secs()))
                    })
                    .collect();
                eprintln!("xtask: still running: {}", now.join(", "));
            }
            Err(RecvTimeoutError::Disconnected) => bail!("the runner lost its units' reports"),
        }
    }
}

/// Starts `unit` (number `index`) as `command`, in a process group of
/// its own under a watchdog (if the xtask dies, so do the tests), its
/// standard output and error into one pipe, read by a thread that
/// reports to `events`.
fn start(unit: &Unit, index: usize, mut command: Command, events: Sender<Event>) -> Result<()> {
    let (reader, writer) = std::io::pipe().context("failed to make a pipe for a test binary's output")?;
    command.stdout(writer.try_clone()?).stderr(writer);
    let mut run = Supervised::without_folder()?;
    run.spawn(&mut command).with_context(|| format!("failed to start {}", unit.title))?;
    // The pipe's writing ends now belong to the unit alone: the reader
    // sees end-of-file when it (and whatever it started) is gone.
    drop(command);
    std::thread::spawn(move || {
        let mut output = Vec::new();
        let mut lines = BufReader::new(reader);
        let mut line = Vec::new();
        while lines.read_until(b'\n', &mut line).is_ok_and(|read| read > 0) {
            if ends_a_test(&line) {
                // The runner may have stopped listening after an error.
                let _ = events.send(Event::TestEnded(index));
            }
            output.append(&mut line);
        }
        let status = run.child().wait();
        let _ = events.send(Event::Ended { unit: index, status, output });
    });
    Ok(())
}

/// Whether `line` is libtest's line for a test that ended: `test NAME ...
/// ok`, `FAILED` or `ignored` (with its reason after a comma).
fn ends_a_test(line: &[u8]) -> bool {
    let line = String::from_utf8_lossy(line);
    let Some(rest) = line.strip_prefix("test ") else { return false };
    rest.rsplit_once(" ... ").is_some_and(|(_, outcome)| {
        let outcome = outcome.trim_end();
        ["ok", "FAILED"].contains(&outcome) || outcome.starts_with("ignored")
    })
}

/// Prints a unit's whole output under cargo's `Running` line.
fn report(unit: &Unit, output: &[u8], status: &std::io::Result<ExitStatus>, seconds: f64) -> Result<()> {
    let mut stdout = std::io::stdout().lock();
    writeln!(stdout, "     Running {}", unit.title)?;
    stdout.write_all(output)?;
    match status {
        Ok(status) if status.success() => {}
        Ok(status) => writeln!(stdout, "error: {} failed with {status} after {seconds:.1} s", unit.title)?,
        Err(error) => writeln!(stdout, "error: {} could not be waited for: {error}", unit.title)?,
    }
    stdout.flush()?;
    Ok(())
}

/// The time of the whole run and of the slowest units; an error naming
/// every unit that failed and how to run it alone.
fn summary(units: &[Unit], outcomes: &[Option<Outcome>], elapsed: Duration) -> Result<()> {
    let mut times: Vec<(f64, &str)> = units
        .iter()
        .zip(outcomes)
        .filter_map(|(unit, outcome)| Some((outcome.as_ref()?.seconds, unit.title.as_str())))
        .collect();
    times.sort_by(|a, b| b.0.total_cmp(&a.0));
    let slowest: Vec<String> = times.iter().take(8).map(|(seconds, title)| format!("{seconds:.0} s {title}")).collect();
    eprintln!(
        "xtask: every test binary ran in {} min {} s; the slowest: {}",
        elapsed.as_secs() / 60,
        elapsed.as_secs() % 60,
        slowest.join(", ")
    );
    let failed: Vec<String> = units
        .iter()
        .zip(outcomes)
        .filter(|(_, outcome)| outcome.as_ref().is_none_or(|outcome| !outcome.passed))
        .map(|(unit, _)| format!("  {} (alone: {})", unit.title, unit.alone))
        .collect();
    if !failed.is_empty() {
        bail!("{} test binaries failed:\n{}", failed.len(), failed.join("\n"));
    }
    Ok(())
}

/// Runs the one unit of a run with its output streaming to the user.
pub fn run_alone(unit: &Unit, image: &Path, threads: usize) -> Result<()> {
    let mut command = unit.command(width(unit, threads), image);
    command.stdin(std::process::Stdio::inherit());
    eprintln!("     Running {}", unit.title);
    let line = command_line(&command);
    let status = command.status().with_context(|| format!("failed to start `{line}`"))?;
    if !status.success() {
        bail!("{} failed with {status} (alone: {})", unit.title, unit.alone);
    }
    Ok(())
}
