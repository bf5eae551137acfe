//! What the runner runs: every test binary `cargo test` builds for a
//! selection, each run as `cargo test` runs it (from its package's folder,
//! with the test binaries' arguments), and the doc tests through `cargo
//! test --doc`.

use std::collections::HashMap;
use std::io::BufReader;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::thread::JoinHandle;

use anyhow::{bail, Context, Result};
use boot_image::cargo::NIGHTLY_ONLY;
use boot_image::IMAGE_ENV;
use cargo_metadata::{Message, MetadataCommand};
use install::workspace;
use install::{command_line, output_of};

use super::order::expected_seconds;
use super::selection::{cargo_part, DocTests, Selection};

/// One thing the runner starts: a test binary, or the doc tests.
#[derive(Debug)]
pub struct Unit {
    /// What cargo's `Running` line names: the target's source (with
    /// `unittests` before a library's or a program's) and the binary.
    pub title: String,
    /// Its package and target, as messages and the runner's order name it.
    pub package: String,
    pub target: String,
    /// The program and its arguments, without `--test-threads`.
    pub program: PathBuf,
    pub args: Vec<String>,
    /// The folder `cargo test` runs it from: its package's.
    pub dir: PathBuf,
    /// How many tests it runs, if its listing said (never for the doc
    /// tests).
    pub tests: Option<usize>,
    /// How to run it alone.
    pub alone: String,
}

impl Unit {
    /// The seconds it took alone when the order was measured; 0 if it was
    /// not measured (a short one).
    pub fn expected_seconds(&self) -> u32 {
        expected_seconds(&self.package, &self.target)
    }

    /// The test threads its arguments fix (`--test-threads N`), if any.
    pub fn fixed_threads(&self) -> Option<usize> {
        let at = self.args.iter().position(|arg| arg == "--test-threads" || arg.starts_with("--test-threads="))?;
        let value = match self.args[at].split_once('=') {
            Some((_, value)) => value,
            None => self.args.get(at + 1)?,
        };
        value.parse().ok()
    }

    /// The command that runs it with `threads` test threads (unless its
    /// arguments fix them), booting `image`.
    pub fn command(&self, threads: usize, image: &Path) -> Command {
        let mut command = Command::new(&self.program);
        command.args(&self.args).current_dir(&self.dir);
        if self.fixed_threads().is_none() {
            command.arg(format!("--test-threads={threads}"));
        }
        command.env("CARGO_MANIFEST_DIR", &self.dir).env(IMAGE_ENV, image).stdin(Stdio::null());
        command
    }
}

/// `cargo test` with `args`, run by the cargo (the stable toolchain) that
/// runs the xtask: over every host crate of the workspace, unless `args`
/// name packages (with `--workspace`, cargo would take every package
/// whatever `-p` says).
pub fn cargo_test(args: &[String]) -> Command {
    let mut command = install::host();
    command.arg("test");
    let names_packages = cargo_part(args)
        .iter()
        .any(|arg| arg.starts_with("--package") || (arg.starts_with("-p") && !arg.starts_with("--")));
    if !names_packages {
        command.arg("--workspace");
        for package in NIGHTLY_ONLY {
            command.args(["--exclude", package]);
        }
    }
    command.args(args);
    command
}

/// The test binaries of a selection being built: `cargo test --no-run`
/// (its progress and errors stream to the user), its JSON messages read
/// by a thread.
pub struct Build {
    selection: Selection,
    cargo: Option<Building>,
}

/// `cargo test --no-run` running: the process, its command line, and the
/// thread that reads the binaries from its messages.
struct Building {
    child: Child,
    line: String,
    reader: JoinHandle<Result<Vec<Binary>>>,
}

impl Build {
    /// Starts building what `selection` runs (nothing, for the doc tests
    /// alone: they build as they run).
    pub fn start(selection: &Selection) -> Result<Self> {
        let cargo = (selection.doc_tests != DocTests::Only).then(|| start_build(&selection.cargo)).transpose()?;
        Ok(Self { selection: selection.clone(), cargo })
    }

    /// Stops the build, for a run that fails before it needs it.
    pub fn stop(self) {
        if let Some(Building { mut child, .. }) = self.cargo {
            // It may have ended already; it is reaped either way.
            let _ = child.kill();
            let _ = child.wait();
        }
    }

    /// Waits for the build and returns every test binary it built, and
    /// the doc tests if the selection runs them, as units.
    pub fn finish(self) -> Result<Vec<Unit>> {
        let mut units = Vec::new();
        if let Some(Building { mut child, line, reader }) = self.cargo {
            let binaries = reader.join().unwrap_or_else(|panic| std::panic::resume_unwind(panic));
            let status = child.wait().with_context(|| format!("waiting for `{line}`"))?;
            if !status.success() {
                bail!("`{line}` failed with {status}");
            }
            let packages = package_names()?;
            for binary in binaries? {
                let package = packages
                    .get(&binary.dir)
                    .with_context(|| format!("no workspace package in {}", binary.dir.display()))?
                    .clone();
                units.push(binary.into_unit(package, &self.selection.test_args));
            }
        }
        if self.selection.doc_tests != DocTests::No {
            units.push(doc_tests(&self.selection));
        }
        Ok(units)
    }
}

/// Starts `cargo test --no-run` over `cargo_args`, and a thread that
/// reads the test binaries from its JSON messages.
fn start_build(cargo_args: &[String]) -> Result<Building> {
    let mut command = cargo_test(cargo_args);
    command.args(["--no-run", "--message-format=json-render-diagnostics"]).stdout(Stdio::piped());
    let line = command_line(&command);
    eprintln!("running {line}");
    let mut child = command.spawn().with_context(|| format!("failed to start `{line}`"))?;
    let stdout = child.stdout.take().expect("piped above");
    let reading = line.clone();
    let reader = std::thread::spawn(move || {
        let mut binaries = Vec::new();
        for message in Message::parse_stream(BufReader::new(stdout)) {
            let Message::CompilerArtifact(artifact) = message.with_context(|| format!("reading `{reading}`"))? else {
                continue;
            };
            let (Some(executable), true) = (artifact.executable, artifact.profile.test) else { continue };
            let manifest = PathBuf::from(artifact.manifest_path);
            binaries.push(Binary {
                target: artifact.target.name,
                kinds: artifact.target.kind.iter().map(ToString::to_string).collect(),
                source: artifact.target.src_path.into(),
                executable: executable.into(),
                dir: manifest.parent().context("a manifest path without a folder")?.to_path_buf(),
            });
        }
        Ok(binaries)
    });
    Ok(Building { child, line, reader })
}

/// A test binary cargo built.
struct Binary {
    /// The target's name and kinds (`lib`, `bin`, `test`).
    target: String,
    kinds: Vec<String>,
    source: PathBuf,
    executable: PathBuf,
    /// Its package's folder.
    dir: PathBuf,
}

impl Binary {
    fn into_unit(self, package: String, test_args: &[String]) -> Unit {
        let relative = |path: &Path, to: &Path| path.strip_prefix(to).unwrap_or(path).display().to_string();
        let unit_tests = !self.kinds.iter().any(|kind| kind == "test");
        let source = relative(&self.source, &self.dir);
        let title = format!(
            "{}{source} ({})",
            if unit_tests { "unittests " } else { "" },
            relative(&self.executable, workspace::root())
        );
        let only = if self.kinds.iter().any(|kind| kind == "bin") {
            "--bins".to_string()
        } else if unit_tests {
            "--lib".to_string()
        } else {
            format!("--test {}", self.target)
        };
        let tests = count_tests(&self.executable, &self.dir, test_args);
        Unit {
            title,
            alone: format!("cargo xtask test -- -p {package} {only}"),
            package,
            target: self.target,
            program: self.executable,
            args: test_args.to_vec(),
            dir: self.dir,
            tests,
        }
    }
}

/// The workspace's packages by folder.
fn package_names() -> Result<HashMap<PathBuf, String>> {
    let metadata = MetadataCommand::new()
        .current_dir(workspace::root())
        .no_deps()
        .exec()
        .context("failed to read the workspace's packages (cargo metadata)")?;
    let folder = |package: &cargo_metadata::Package| {
        PathBuf::from(&package.manifest_path).parent().map(Path::to_path_buf).unwrap_or_default()
    };
    Ok(metadata.packages.iter().map(|package| (folder(package), package.name.to_string())).collect())
}

/// How many tests `executable` runs with `test_args`, from its own
/// listing; `None` if it would not list them.
fn count_tests(executable: &Path, dir: &Path, test_args: &[String]) -> Option<usize> {
    let mut list = Command::new(executable);
    list.args(test_args).args(["--list", "--format", "terse"]).current_dir(dir);
    let listing = output_of(&mut list).ok()?;
    Some(listing.lines().filter(|line| line.ends_with(": test")).count())
}

/// The doc tests of the selection's packages, as `cargo test --doc`.
fn doc_tests(selection: &Selection) -> Unit {
    let mut args = selection.cargo.clone();
    args.push("--doc".into());
    let command = cargo_test(&args);
    let cargo_args: Vec<String> = command.get_args().map(|arg| arg.to_string_lossy().into_owned()).collect();
    let mut unit_args = cargo_args;
    unit_args.push("--".into());
    unit_args.extend(selection.test_args.iter().cloned());
    Unit {
        title: "the doc tests (cargo test --doc)".into(),
        package: "(workspace)".into(),
        target: "doc".into(),
        program: command.get_program().into(),
        args: unit_args,
        dir: workspace::root().to_path_buf(),
        tests: None,
        alone: "cargo xtask test -- --doc".into(),
    }
}
