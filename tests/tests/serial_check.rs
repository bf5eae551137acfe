//! The check a person runs on their own PC (`cargo xtask check --serial`),
//! run here with no PC: QEMU's COM1 on a pseudo-terminal, which the check
//! opens by its path as it would `/dev/ttyUSB0`. Clean, every picture
//! equals the host render with nothing retried; through a relay that
//! drops, flips and inserts bytes and pauses the line, both ways and at
//! several rates, every picture still equals it and the report counts the
//! retries; with retries off the same relay makes the check fail. A
//! damaged command is refused and changes nothing. Scenes far past a
//! command line, uploaded in chunks, come through the noise whole.

use std::path::Path;
use std::time::Duration;

use anyhow::{ensure, Context, Result};
use boot_image::build_image;
use harness::cable::{open_console, FaultRates, Relay};
use harness::client::TroubleKind;
use harness::large_scenes::{large_file, rings};
use harness::serial_check::{self, write_reports, CheckOptions, CheckReport, Scope};
use harness::{Qemu, QemuOptions, Reply, SerialLine};
use protocol::{Cleared, Command, Sealed, BENCH_DEFAULT_REPEATS};
use raster::MethodId;

/// Retries of a step on a clean line: `cargo xtask check`'s default.
const RETRIES: u32 = 8;

/// How long the check waits for the kernel: QEMU has only just started it.
const WAIT: Duration = Duration::from_secs(120);

/// QEMU with COM1 on a pseudo-terminal, and that terminal's path.
fn qemu_on_a_pty() -> Result<(Qemu, std::path::PathBuf)> {
    let mut qemu = Qemu::spawn(&build_image()?, QemuOptions { serial: SerialLine::Pty, ..QemuOptions::default() })?;
    let pty = qemu.pty()?;
    Ok((qemu, pty))
}

fn check(device: &Path, scope: Scope, retries: u32) -> Result<CheckReport> {
    let mut console = open_console(device, retries)?;
    let options = CheckOptions { scope, repeats: BENCH_DEFAULT_REPEATS, wait: WAIT };
    serial_check::run(&mut console, &device.display().to_string(), &options, |_| {})
}

/// Every picture of `report` equals the host render.
fn every_picture_equal(report: &CheckReport) -> Result<()> {
    let differing: Vec<String> = report.differing().map(|picture| format!("{picture:?}")).collect();
    ensure!(differing.is_empty(), "{} pictures differ:\n{}", differing.len(), differing.join("\n"));
    Ok(())
}

#[test]
fn the_whole_check_over_qemus_pty_finds_every_picture_equal_and_writes_both_reports() -> Result<()> {
    let (_qemu, pty) = qemu_on_a_pty()?;
    let report = check(&pty, Scope::full(), RETRIES)?;
    every_picture_equal(&report)?;
    let full = Scope::full();
    ensure!(
        report.pictures.len() == full.pictures(),
        "{} pictures, expected {}",
        report.pictures.len(),
        full.pictures()
    );
    ensure!(report.vgacheck.0, "VGACHECK answered ERR: {}", report.vgacheck.1);
    protocol::Ready::parse(&report.ready).with_context(|| format!("READY text {:?}", report.ready))?;
    ensure!(report.bench.scenes == full.bench_scenes, "bench scenes {:?}", report.bench.scenes);
    ensure!(report.tsc.source == protocol::ClockSource::Pit, "TSC rate {} not measured against the PIT", report.tsc);
    // A clean pty damages nothing; a loaded machine may still hold a reply
    // back past a deadline, which a retry is for.
    let damaged = report.stats.count(TroubleKind::DamagedReply) + report.stats.count(TroubleKind::Refused);
    ensure!(damaged == 0 && report.line.none(), "a clean pty: {:?}, {}", report.stats, report.line);
    let dir = tempfile::tempdir()?;
    let (md, json) = write_reports(&report, dir.path())?;
    let json: serde_json::Value = serde_json::from_slice(&std::fs::read(json)?)?;
    for field in ["ready", "pictures", "bench", "tsc_hz", "retries", "line"] {
        ensure!(!json[field].is_null(), "report.json has no `{field}`");
    }
    ensure!(json["pictures"].as_array().map(Vec::len) == Some(full.pictures()), "report.json's pictures");
    ensure!(json["bench"].as_array().map(Vec::len) == Some(full.bench_scenes.len() * MethodId::ALL.len()));
    let md = std::fs::read_to_string(md)?;
    ensure!(md.contains(&format!("All {} pictures equal the host render", full.pictures())), "{md}");
    Ok(())
}

/// One rate of line noise: the fault rates each way, the scope checked
/// through it and the retries allowed.
struct Noise {
    name: &'static str,
    to_host: FaultRates,
    to_kernel: FaultRates,
    scope: Scope,
    retries: u32,
}

/// The rates tried, lightest first. A dump is 64,768 bytes, so a rate of
/// one fault of each kind in 200,000 bytes damages about 60% of dumps; the
/// host's lines are some 30 bytes, so one in 150 damages a fifth of them.
fn noises() -> [Noise; 3] {
    [
        Noise {
            name: "light, whole check",
            to_host: FaultRates::one_in(1_000_000.0, 2_000_000.0),
            to_kernel: FaultRates::one_in(2_000.0, 5_000.0),
            scope: Scope::full(),
            retries: RETRIES,
        },
        Noise {
            name: "heavy replies",
            to_host: FaultRates::one_in(200_000.0, 300_000.0),
            to_kernel: FaultRates::NONE,
            scope: Scope::quick(),
            retries: 20,
        },
        Noise {
            name: "heavy commands",
            to_host: FaultRates::one_in(2_000_000.0, 1e12),
            to_kernel: FaultRates::one_in(150.0, 600.0),
            scope: Scope::quick(),
            retries: 20,
        },
    ]
}

#[test]
fn through_line_noise_at_several_rates_every_picture_is_still_equal_and_the_retries_are_counted() -> Result<()> {
    let (_qemu, pty) = qemu_on_a_pty()?;
    let mut failures = Vec::new();
    for (seed, noise) in noises().into_iter().enumerate() {
        let relay = Relay::start(&pty, noise.to_host, noise.to_kernel, seed as u64)?;
        let outcome = check(relay.device(), noise.scope, noise.retries);
        let (to_host, to_kernel) = relay.counts();
        drop(relay);
        let report = outcome.with_context(|| format!("{}: the check failed", noise.name))?;
        let troubles: Vec<String> =
            TroubleKind::ALL.iter().map(|&kind| format!("{} {}", kind.name(), report.stats.count(kind))).collect();
        eprintln!(
            "{}: {} s, relay to host {to_host:?}, to kernel {to_kernel:?}; {} steps retried ({})",
            noise.name,
            report.elapsed.as_secs(),
            report.stats.retries,
            troubles.join(", ")
        );
        if let Err(error) = every_picture_equal(&report) {
            failures.push(format!("{}: {error:#}", noise.name));
        }
        if to_host.faults() == 0 && to_kernel.faults() == 0 {
            failures.push(format!("{}: the relay injected no fault", noise.name));
        }
        if report.stats.retries == 0 {
            failures.push(format!("{}: nothing was retried through the noise", noise.name));
        }
    }
    ensure!(failures.is_empty(), "{}", failures.join("\n"));
    Ok(())
}

/// A command held up on its way in past the host's deadline is sent again
/// under a new number, and the kernel runs both: the late reply to the
/// first must be skipped. For `SHOW` it carries the ticks of a draw the
/// screen no longer shows, so taking it would make the host label its
/// render with other ticks than the kernel's label on the screen.
#[test]
fn a_late_reply_is_skipped_never_taken_for_the_answer_to_a_later_line() -> Result<()> {
    let (_qemu, pty) = qemu_on_a_pty()?;
    let held_up = FaultRates { pause: 1.0 / 200.0, ..FaultRates::NONE };
    let relay = Relay::start(&pty, FaultRates::NONE, held_up, 3)?;
    let mut console = open_console(relay.device(), 20)?;
    // Shorter than the relay's pauses, so a paused command misses it.
    console.set_answer_timeout(Duration::from_millis(500));
    let scope = Scope {
        pages: vec!["abrash38-1"],
        methods: vec![MethodId::Exact],
        show_entries: scenes::show::ENTRIES_IN_ORDER.iter().map(|entry| entry.name).collect(),
        bench_scenes: vec!["abrash38-1"],
        files: Vec::new(),
    };
    let options = CheckOptions { scope, repeats: 1, wait: WAIT };
    let report = serial_check::run(&mut console, "the relay", &options, |_| {})?;
    eprintln!("relay to kernel: {:?}; {:?}", relay.counts().1, report.stats);
    every_picture_equal(&report)?;
    ensure!(report.stats.count(TroubleKind::NoReply) > 0, "no command was held past its deadline");
    ensure!(report.stats.stale_replies > 0, "no late reply came: {:?}", report.stats);
    Ok(())
}

/// A polygon of 2,000 vertices in 40 contours and a scene file of 350 KB,
/// each uploaded in some hundred chunks through noise on both ways, drawn
/// and timed by every method: every picture equals the host render, and
/// damaged chunks were sent again.
#[test]
fn scenes_uploaded_through_line_noise_arrive_whole() -> Result<()> {
    let (_qemu, pty) = qemu_on_a_pty()?;
    let large = scenes::file::parse("large", &large_file(350_000)).map_err(|error| anyhow::anyhow!("{error}"))?;
    let scope = Scope {
        pages: Vec::new(),
        methods: vec![MethodId::Exact, MethodId::AbrashAet],
        show_entries: Vec::new(),
        bench_scenes: Vec::new(),
        files: vec![rings(40, 50), large],
    };
    // Commands of some 1,400 bytes: one fault of each kind in 30,000
    // bytes damages about one chunk in eight.
    let relay = Relay::start(&pty, FaultRates::one_in(300_000.0, 1e12), FaultRates::one_in(30_000.0, 1e12), 5)?;
    let mut console = open_console(relay.device(), RETRIES)?;
    let options = CheckOptions { scope, repeats: 1, wait: WAIT };
    let report = serial_check::run(&mut console, "the relay", &options, |_| {})?;
    let (to_host, to_kernel) = relay.counts();
    eprintln!("relay to host {to_host:?}, to kernel {to_kernel:?}; {} retried", report.stats.retries);
    every_picture_equal(&report)?;
    ensure!(report.pictures.len() == 4, "{} pictures", report.pictures.len());
    ensure!(report.bench.scenes == ["rings", "large"], "bench scenes {:?}", report.bench.scenes);
    ensure!(to_kernel.faults() > 0, "the relay damaged no command");
    ensure!(report.stats.retries > 0, "nothing was retried through the noise: {:?}", report.stats);
    Ok(())
}

#[test]
fn with_retries_off_the_same_noise_fails_the_check() -> Result<()> {
    let (_qemu, pty) = qemu_on_a_pty()?;
    let [_, heavy_replies, _] = noises();
    let relay = Relay::start(&pty, heavy_replies.to_host, heavy_replies.to_kernel, 1)?;
    let error = match check(relay.device(), heavy_replies.scope, 0) {
        Ok(report) => anyhow::bail!("the check passed through the noise with retries off: {:?}", report.stats),
        Err(error) => error,
    };
    ensure!(format!("{error:#}").contains("retries are off"), "the check failed for another reason: {error:#}");
    Ok(())
}

#[test]
fn a_damaged_command_is_refused_and_changes_nothing_while_plain_commands_still_work() -> Result<()> {
    let mut qemu = Qemu::boot(QemuOptions::default())?;
    let sealed = |seq, command: &Command| format!("{}\n", Sealed { seq, command });
    qemu.console.send_bytes(sealed(7, &Command::Clear(9)).as_bytes())?;
    match qemu.console.reply()? {
        Reply::Ok(text) if Cleared::parse(&text)? == Cleared { color: 9 } => {}
        other => anyhow::bail!("sealed CLEAR 9 answered {other:?}"),
    }
    // `CLEAR 9` becomes `CLEAR 1` by one flipped bit: the CRC no longer checks.
    let damaged = sealed(8, &Command::Clear(9)).replace("CLEAR 9", "CLEAR 1");
    qemu.console.send_bytes(damaged.as_bytes())?;
    match qemu.console.reply()? {
        Reply::Err(text) if protocol::ErrorReply::parse(&text)? == protocol::ErrorReply::Damaged => {}
        other => anyhow::bail!("`{}` answered {other:?}, expected ERR for a damaged line", damaged.trim_end()),
    }
    let dump = qemu.console.dump()?;
    ensure!(dump.pixels.iter().all(|&pixel| pixel == 9), "the damaged CLEAR 1 changed the screen");
    qemu.console.clear(3).context("a plain CLEAR after the damaged line")?;
    Ok(())
}
