//! The explorer page (`cargo xtask explore`): the engine (the `explorer`
//! crate in `../engine`) built for `wasm32-unknown-unknown`, beside the
//! hand-written page in `../web`, written to a folder and served on
//! 127.0.0.1. The browser tests (`tests/tests/explorer.rs`) serve it the
//! same way.

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::thread::JoinHandle;

use anyhow::{anyhow, Context, Result};
use tiny_http::{Header, Response, Server};

use install::run_streaming;
use install::workspace;
use install::{ensure_wasm_target, WASM_TARGET};

/// The hand-written files of the page, in `xtask/explorer/web`.
const WEB_FILES: [&str; 3] = ["index.html", "explorer.js", "explorer.css"];
/// The module's name beside them, as the script fetches it.
pub const MODULE: &str = "explorer.wasm";
/// Where the page looks for the lab's results.
pub const RESULTS: &str = "results.json";
/// Where the page looks for a scene to open when its address names none.
pub const SCENE: &str = "scene.scene";

/// Where the wasm build goes: a directory of its own, so it never waits on
/// (or invalidates) the host build's lock and artifacts.
fn wasm_target_dir() -> PathBuf {
    workspace::target_dir().join("wasm")
}

fn wasm_build_command() -> std::process::Command {
    let mut command = install::host();
    command.args(["build", "--package", "explorer", "--lib", "--release", "--target", WASM_TARGET]);
    // The workspace keeps line tables in release builds for profiling; the
    // page has no use for them and they would triple the module.
    command.args(["--config", "profile.release.strip=\"debuginfo\""]);
    command.arg("--target-dir").arg(wasm_target_dir());
    command
}

/// Builds the engine for wasm32 (adding the target to the toolchain when
/// missing) and returns the module's path.
pub fn build_module() -> Result<PathBuf> {
    ensure_wasm_target()?;
    run_streaming(&mut wasm_build_command()).context("failed to build the explorer's wasm module")?;
    Ok(wasm_target_dir().join(WASM_TARGET).join("release").join(MODULE))
}

/// Writes the page into `out`: the module just built, the hand-written
/// files, `results` (a lab `results.json`) as `results.json` and `scene`
/// (a scene file's text) as `scene.scene` when given.
pub fn write_page(out: &Path, results: Option<&Path>, scene: Option<&str>) -> Result<()> {
    let module = build_module()?;
    std::fs::create_dir_all(out).with_context(|| format!("failed to create {}", out.display()))?;
    let copy = |from: &Path, name: &str| -> Result<()> {
        std::fs::copy(from, out.join(name))
            .map(drop)
            .with_context(|| format!("failed to copy {} to {}", from.display(), out.display()))
    };
    copy(&module, MODULE)?;
    let web = workspace::root().join("xtask/explorer/web");
    for name in WEB_FILES {
        copy(&web.join(name), name)?;
    }
    match results {
        Some(results) => copy(results, RESULTS)?,
        None => remove_old(out, RESULTS)?,
    }
    match scene {
        Some(text) => std::fs::write(out.join(SCENE), text)
            .with_context(|| format!("failed to write {SCENE} in {}", out.display()))?,
        None => remove_old(out, SCENE)?,
    }
    Ok(())
}

/// Removes `name` from `out` if an earlier run left it there: it would be
/// shown as if it had been given this time.
fn remove_old(out: &Path, name: &str) -> Result<()> {
    match std::fs::remove_file(out.join(name)) {
        Err(error) if error.kind() != std::io::ErrorKind::NotFound => {
            Err(error).with_context(|| format!("failed to remove an old {name} in {}", out.display()))
        }
        _ => Ok(()),
    }
}

/// `cargo xtask explore`: writes the page to `out` and prints the folder,
/// or with no `out` writes it under `target/explorer` and serves it until
/// the process is stopped, printing its address.
pub fn explore(out: Option<&Path>, results: Option<&Path>, scene: Option<&str>) -> Result<()> {
    let dir = out.map_or_else(|| workspace::target_dir().join("explorer"), Path::to_path_buf);
    write_page(&dir, results, scene)?;
    if out.is_some() {
        println!("{}", dir.display());
        return Ok(());
    }
    let server = PageServer::start(&dir)?;
    eprintln!("serving {} on 127.0.0.1 until stopped (Ctrl-C)", dir.display());
    println!("{}", server.url());
    server.serve_forever();
    Ok(())
}

/// The page's folder served over HTTP on 127.0.0.1 (a port the system
/// picks), until dropped. Only the page's own files are served.
pub struct PageServer {
    server: Arc<Server>,
    url: String,
    thread: Option<JoinHandle<()>>,
}

impl PageServer {
    pub fn start(dir: &Path) -> Result<Self> {
        let server = Arc::new(Server::http("127.0.0.1:0").map_err(|error| anyhow!("failed to listen: {error}"))?);
        let address = server.server_addr().to_ip().context("the server has no IP address")?;
        let url = format!("http://{address}/");
        let dir = dir.to_path_buf();
        let serving = Arc::clone(&server);
        let thread = std::thread::spawn(move || {
            for request in serving.incoming_requests() {
                let (status, content_type, body) = match page_file(request.url()) {
                    Some((name, content_type)) => match std::fs::read(dir.join(name)) {
                        Ok(body) => (200, content_type, body),
                        Err(_) => (404, "text/plain", format!("{name} is not here").into_bytes()),
                    },
                    None => (404, "text/plain", b"not a file of the page".to_vec()),
                };
                let headers = [("Content-Type", content_type), ("Cache-Control", "no-store")]
                    .map(|(name, value)| Header::from_bytes(name, value).expect("valid header"));
                let mut response = Response::from_data(body).with_status_code(status);
                for header in headers {
                    response.add_header(header);
                }
                // A client that went away is no reason to stop serving.
                let _ = request.respond(response);
            }
        });
        Ok(Self { server, url, thread: Some(thread) })
    }

    /// The page's address, `http://127.0.0.1:PORT/`.
    pub fn url(&self) -> &str {
        &self.url
    }

    /// Serves until the process is stopped.
    pub fn serve_forever(mut self) {
        if let Some(thread) = self.thread.take() {
            // The thread only ends when the server is unblocked, which only
            // Drop does.
            let _ = thread.join();
        }
    }
}

impl Drop for PageServer {
    fn drop(&mut self) {
        self.server.unblock();
        if let Some(thread) = self.thread.take() {
            let _ = thread.join();
        }
    }
}

/// The page file a request path names, with its content type; `None` for
/// anything else (no directories, no other files of the folder).
fn page_file(url: &str) -> Option<(&str, &'static str)> {
    let path = url.split(['?', '#']).next().unwrap_or("");
    let name = match path.trim_start_matches('/') {
        "" => "index.html",
        name => name,
    };
    let content_type = match name {
        "index.html" => "text/html; charset=utf-8",
        "explorer.js" => "text/javascript; charset=utf-8",
        "explorer.css" => "text/css; charset=utf-8",
        MODULE => "application/wasm",
        RESULTS => "application/json",
        SCENE => "text/plain; charset=utf-8",
        _ => return None,
    };
    Some((name, content_type))
}

#[cfg(test)]
mod tests {
    use super::*;
    use install::command_line;

    #[test]
    fn the_module_is_built_for_wasm32_in_its_own_target_dir() {
        let line = command_line(&wasm_build_command());
        assert!(
            line.ends_with(&format!(
                " build --package explorer --lib --release --target wasm32-unknown-unknown \
                 --config 'profile.release.strip=\"debuginfo\"' --target-dir {}",
                wasm_target_dir().display()
            )),
            "{line}"
        );
    }

    #[test]
    fn only_the_page_files_are_served() {
        assert_eq!(page_file("/"), Some(("index.html", "text/html; charset=utf-8")));
        assert_eq!(page_file("/?x=1#scene=abrash38-3"), Some(("index.html", "text/html; charset=utf-8")));
        assert_eq!(page_file("/explorer.wasm"), Some(("explorer.wasm", "application/wasm")));
        assert_eq!(page_file("/results.json"), Some(("results.json", "application/json")));
        assert_eq!(page_file("/scene.scene"), Some(("scene.scene", "text/plain; charset=utf-8")));
        assert_eq!(page_file("/../Cargo.toml"), None);
        assert_eq!(page_file("/web/index.html"), None);
    }
}
