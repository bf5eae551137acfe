//! The children the harness starts go when it goes, however it goes, and
//! say why when they go first: a harness killed with SIGKILL while QEMU
//! boots and a browser runs leaves no process of theirs and no run folder
//! behind; a QEMU that could not start fails QMP with what it said.

use std::io::{BufRead, BufReader};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use anyhow::{bail, ensure, Context, Result};
use boot_image::build_image;
use harness::browser::Browser;
use harness::supervisor::{live_members, Supervised};
use harness::{Qemu, QemuOptions};

/// The test binary's own name for the harness it starts and kills.
const HARNESS_TO_KILL: &str = "harness_to_be_killed";
/// Longest wait for that harness to have its children running: it may
/// build the image and starts a browser.
const START_TIMEOUT: Duration = Duration::from_secs(600);
/// Longest wait for the children to go once the harness is killed (the
/// watchdogs take milliseconds).
const CLEANUP_TIMEOUT: Duration = Duration::from_secs(20);

/// Not a test of its own: the harness [`a_harness_killed_mid_boot_leaves_no_child_and_no_folder`]
/// runs in a process of its own and kills. Starts QEMU (not waiting for
/// the kernel: killed mid-boot) and a browser (chromedriver, with the
/// Chromium it starts as a grandchild), prints each one's process group,
/// then waits to be killed.
#[test]
#[ignore = "the harness that a_harness_killed_mid_boot_leaves_no_child_and_no_folder starts and kills"]
fn harness_to_be_killed() -> Result<()> {
    let qemu = Qemu::spawn(&build_image()?, QemuOptions::default())?;
    let browser = Browser::start()?;
    // libtest's own line for the test may precede these on the same line.
    println!("\nchild-group {}", qemu.pid());
    println!("child-group {}", browser.driver_pid());
    println!("children-running");
    std::thread::sleep(START_TIMEOUT);
    bail!("not killed within {} s", START_TIMEOUT.as_secs())
}

#[test]
fn a_harness_killed_mid_boot_leaves_no_child_and_no_folder() -> Result<()> {
    // The harness's temporary folder is ours, so that its run folders are
    // the only ones there.
    let temporary = tempfile::tempdir()?;
    let mut command = Command::new(std::env::current_exe()?);
    command.args(["--ignored", "--exact", HARNESS_TO_KILL, "--nocapture", "--test-threads=1"]);
    // Its standard error goes to a log, for the error should it fail.
    let log = temporary.path().join("harness.log");
    command.env("TMPDIR", temporary.path()).stdout(Stdio::piped()).stderr(std::fs::File::create(&log)?);
    let said = || {
        let text = std::fs::read_to_string(&log).unwrap_or_default();
        let lines: Vec<&str> = text.lines().collect();
        format!("the harness's last words:\n{}", lines[lines.len().saturating_sub(20)..].join("\n"))
    };
    let mut run = Supervised::without_folder()?;
    let harness = run.spawn(&mut command)?;
    let lines = BufReader::new(harness.stdout.take().context("stdout is piped")?).lines();
    let (sender, receiver) = std::sync::mpsc::channel();
    std::thread::spawn(move || lines.map_while(Result::ok).for_each(|line| drop(sender.send(line))));
    let mut groups = Vec::new();
    loop {
        let line = receiver
            .recv_timeout(START_TIMEOUT)
            .with_context(|| format!("the harness to kill never said it was running; {}", said()))?;
        match line.strip_prefix("child-group ") {
            Some(group) => groups.push(group.parse::<u32>()?),
            None if line == "children-running" => break,
            None => {}
        }
    }
    // What is to go must be there first, or the check proves nothing.
    let folders = || -> Result<Vec<String>> {
        let names =
            std::fs::read_dir(temporary.path())?.map(|entry| Ok(entry?.file_name().to_string_lossy().into_owned()));
        Ok(names.collect::<Result<Vec<String>>>()?.into_iter().filter(|name| name.starts_with("polylab-")).collect())
    };
    ensure!(folders()?.len() == 2, "QEMU's and the browser's run folders are not there: {:?}", folders()?);
    let driver_group = live_members(groups[1]);
    ensure!(driver_group.len() >= 2, "chromedriver's group {} holds no Chromium: {driver_group:?}", groups[1]);
    for group in &groups {
        ensure!(!live_members(*group).is_empty(), "group {group} has no live process before the kill");
    }
    harness.kill()?;
    harness.wait()?;
    let deadline = Instant::now() + CLEANUP_TIMEOUT;
    loop {
        let left: Vec<(u32, Vec<u32>)> =
            groups.iter().map(|&group| (group, live_members(group))).filter(|(_, pids)| !pids.is_empty()).collect();
        let folders = folders()?;
        if left.is_empty() && folders.is_empty() {
            return Ok(());
        }
        if Instant::now() > deadline {
            bail!(
                "{} s after the SIGKILL, still running (group, processes): {left:?}; folders: {folders:?}",
                CLEANUP_TIMEOUT.as_secs()
            );
        }
        std::thread::sleep(Duration::from_millis(50));
    }
}

#[test]
fn a_screendump_of_a_qemu_that_could_not_start_fails_with_what_it_said() -> Result<()> {
    let mut qemu = Qemu::spawn(std::path::Path::new("/nonexistent/polylab.img"), QemuOptions::default())?;
    let error = format!("{:#}", qemu.screendump().err().context("a screendump of a QEMU that could not start")?);
    let complaint = "Could not open '/nonexistent/polylab.img'";
    ensure!(error.matches(complaint).count() == 1, "the error does not carry QEMU's complaint once: {error}");
    Ok(())
}
