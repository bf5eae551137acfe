//! Headless Chromium driven through chromedriver, for the explorer page's
//! tests: the browser is the independent judge of what the page shows.

pub mod webdriver;

use std::net::{SocketAddr, TcpListener};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use anyhow::{bail, Context, Result};
use serde_json::{json, Value};

use crate::supervisor::Supervised;
use install::command_line;
use install::{chromedriver, chromium, ensure_chromium};
use webdriver::Session;

/// Chromium's flags. This machine's network is closed: without the flags
/// that stop its background connections (updates, sync, QUIC probes) it
/// stalls and refuses the driver's connections; the sandbox needs user
/// namespaces that containers and root lack; there is no GPU.
const CHROMIUM_FLAGS: [&str; 8] = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
];
/// Wide enough for the explorer's two panes side by side.
const WINDOW_SIZE: &str = "--window-size=1400,1200";

/// A chromedriver with one headless Chromium session, both ended on drop,
/// with a fresh profile removed on drop.
pub struct Browser {
    // Fields drop in order: the session first (deleting it closes
    // Chromium), then chromedriver's run: its process group (Chromium
    // included, should it outlive the session) killed, its folder (log and
    // Chromium's profile) removed.
    session: Session,
    driver: Supervised,
}

impl Browser {
    /// Starts chromedriver on a free local port and a headless Chromium
    /// session through it, installing both when missing.
    pub fn start() -> Result<Self> {
        ensure_chromium()?;
        let mut driver = Supervised::with_folder("browser")?;
        let run_dir = driver.folder().to_path_buf();
        let port = TcpListener::bind("127.0.0.1:0")?.local_addr()?.port();
        let address = SocketAddr::from(([127, 0, 0, 1], port));
        let mut command = Command::new(chromedriver().context("chromedriver is not there")?);
        command.arg(format!("--port={port}")).arg(format!("--log-path={}", run_dir.join("chromedriver.log").display()));
        command.stdin(Stdio::null()).stdout(Stdio::null()).stderr(Stdio::null());
        eprintln!("harness: running {}", command_line(&command));
        wait_until_ready(address, driver.spawn(&mut command)?)?;
        let mut args: Vec<String> = CHROMIUM_FLAGS.iter().map(|flag| flag.to_string()).collect();
        args.push(format!("--user-data-dir={}", run_dir.join("profile").display()));
        args.push(WINDOW_SIZE.to_string());
        let binary = chromium().context("chromium is not there")?;
        let capabilities = json!({
            "browserName": "chrome",
            "goog:chromeOptions": { "binary": binary, "args": args },
        });
        let session = Session::new(address, capabilities).with_context(|| {
            // The folder goes with the driver: keep the log's end here.
            let log = std::fs::read_to_string(run_dir.join("chromedriver.log")).unwrap_or_default();
            let tail: String =
                log.lines().rev().take(20).collect::<Vec<_>>().into_iter().rev().collect::<Vec<_>>().join("\n");
            format!("chromedriver's log ends:\n{tail}")
        })?;
        session.set_timeouts(Duration::from_secs(20), Duration::from_secs(60))?;
        Ok(Self { session, driver })
    }

    /// chromedriver's process id (its process group's, which Chromium
    /// joins, too).
    pub fn driver_pid(&self) -> u32 {
        self.driver.pid()
    }

    pub fn session(&self) -> &Session {
        &self.session
    }

    /// Polls `script` (a function body) until it returns `true`, failing
    /// after `timeout` with `what` and the script's last value.
    pub fn wait_for(&self, what: &str, script: &str, timeout: Duration) -> Result<()> {
        let start = Instant::now();
        loop {
            let value = self.session.execute(script, vec![])?;
            if value == Value::Bool(true) {
                return Ok(());
            }
            if start.elapsed() > timeout {
                bail!("{what}: not after {timeout:?} (last: {value})");
            }
            std::thread::sleep(Duration::from_millis(100));
        }
    }
}

/// Waits until chromedriver answers `/status` with `ready`.
fn wait_until_ready(address: SocketAddr, driver: &mut Child) -> Result<()> {
    let start = Instant::now();
    loop {
        if let Some(status) = driver.try_wait()? {
            bail!("chromedriver exited with {status} before it was ready");
        }
        if let Ok((200, reply)) = webdriver::request(address, "GET", "/status", None) {
            if reply["value"]["ready"] == Value::Bool(true) {
                return Ok(());
            }
        }
        if start.elapsed() > Duration::from_secs(20) {
            bail!("chromedriver on {address} not ready after 20 s");
        }
        std::thread::sleep(Duration::from_millis(100));
    }
}
