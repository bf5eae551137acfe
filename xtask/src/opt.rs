//! The command line.

use std::path::PathBuf;

use anyhow::Context;
use clap::{ArgGroup, Args, Parser, Subcommand};
use harness::Adapter;
use protocol::{Firmware, BENCH_DEFAULT_REPEATS, BENCH_MAX_REPEATS};
use raster::MethodId;

use crate::source::{SceneArgs, SceneFiles, SvgArgs};

/// The developer's hands: run the demo, build the image, dump, render,
/// record, test.
#[derive(Parser, Debug)]
#[command(name = "xtask", bin_name = "cargo xtask")]
pub struct Cli {
    #[command(subcommand)]
    pub action: Action,
}

#[derive(Subcommand, Debug)]
pub enum Action {
    /// The demo in QEMU: in a window when a display is available; otherwise
    /// headless, playing the show into target/run (or --out): each still as
    /// <entry>.png, each animation as <entry>.gif, a scene file as
    /// <name>.png, every one checked against the host render.
    Run(RunOpt),
    /// Builds the raw image, one file that boots under a BIOS (or CSM),
    /// under UEFI and under UEFI Secure Boot (for QEMU or a USB stick), its
    /// UEFI loader to be enrolled by its hash (or signed with your key,
    /// --enroll key); prints its path last.
    Image(ImageOpt),
    /// Boots the kernel, draws a built-in scene or a scene file, checks the
    /// kernel's dump against the host render and QEMU's screendump, and
    /// writes DIR/NAME.png (the kernel's dump) and DIR/NAME.screen.png
    /// (QEMU's screendump).
    Dump(DumpOpt),
    /// Renders a scene on the host with the same raster code.
    Render(RenderOpt),
    /// Converts an SVG into a scene file: prints what could not be drawn
    /// as the SVG asks and the scene's size; writes nothing on an error.
    Convert(ConvertOpt),
    /// Boots the kernel headless, has it show frames of a show entry
    /// (`SHOW`), dumps each and writes them as an animated GIF; every dump
    /// is checked against the host render unless --no-verify.
    Record(RecordOpt),
    /// Installs what is missing, builds the image once, and runs every test.
    Test(TestOpt),
    /// Checks formatting and runs clippy (warnings are errors) over the host
    /// crates and, with the pinned nightly, the kernel.
    Lint,
    /// Measures every method for speed and accuracy (release build), on the
    /// corpus or on the polygons of --scene FILE or --svg FILE, and writes
    /// results.json, report.md and charts under --out.
    Lab(LabOpt),
    /// Boots the kernel with instruction counting, times every method on
    /// every demo scene with `BENCH` (rdtsc ticks, one per emulated
    /// instruction, apart from the host lab) and writes kernel_bench.md and
    /// kernel_bench.json under --out. With --serial DEVICE, on the machine
    /// at the other end of that serial line instead: TSC ticks and
    /// microseconds.
    Kbench(KbenchOpt),
    /// Runs the harness's checks on a PC booted from the stick, over the
    /// serial cable on DEVICE: every demo page with every method and the
    /// first frame of every show entry against the host render, VGACHECK,
    /// BENCH in the PC's TSC ticks; retries what the line damages; writes
    /// report.md and report.json under --out; fails if any picture differs.
    Check(CheckOpt),
    /// Builds the explorer page (the raster code for wasm32, a hand-written
    /// page), serves it on 127.0.0.1 and prints its address; with --out,
    /// writes it to DIR and stops.
    Explore(ExploreOpt),
    /// Fuzzes with libFuzzer (cargo-fuzz, pinned nightly): every target, or
    /// the one named, for --seconds each; prints executions and coverage
    /// per target and fails on any crash, naming its input. Corpora,
    /// crashes and logs go to target/fuzz.
    Fuzz(FuzzOpt),
    /// Boots the kernel and plays the whole show through SHOW with every
    /// method, --cycles times; after each cycle prints the heap (PING) and
    /// fails if it holds more or its largest free block is smaller than
    /// after the first cycle, or if any frame's figures changed.
    Soak(SoakOpt),
}

#[derive(Args, Debug)]
pub struct RunOpt {
    /// Run headless even when a display is available.
    #[arg(long)]
    pub headless: bool,
    /// Show an entry of the show (a book page or an animation) and stay on
    /// it, or draw a scene file or an SVG and keep it on the screen.
    #[command(flatten)]
    pub drawing: SceneArgs,
    /// Draw every entry (or the scene file) with this method, as the digit
    /// keys do.
    #[arg(long)]
    pub method: Option<MethodId>,
    /// The firmware QEMU boots with: bios (SeaBIOS) or uefi (OVMF).
    #[arg(long, default_value = "bios", value_parser = firmware_named)]
    pub firmware: Firmware,
    /// The display card QEMU emulates: std, cirrus, vmware, qxl-vga,
    /// virtio-vga, ati-vga, bochs-display, ramfb, virtio-gpu or none (the
    /// harness's adapter matrix proves each under one firmware or both).
    #[arg(long, default_value = "std", value_parser = Adapter::named)]
    pub vga: Adapter,
    /// Boot from the emulated USB stick (usb-storage on xHCI), as a PC
    /// boots the image written to a stick.
    #[arg(long)]
    pub usb: bool,
    /// Where a headless run writes its pictures (default target/run).
    #[arg(long)]
    pub out: Option<PathBuf>,
}

#[derive(Args, Debug)]
#[command(group(ArgGroup::new("drawn").args(["scene", "svg"]).required(true)))]
pub struct DumpOpt {
    /// A built-in scene, a scene file or an SVG (a file or an SVG is
    /// uploaded to the kernel whole).
    #[command(flatten)]
    pub drawing: SceneArgs,
    /// Fill method (default: the scene's own, the method its source uses;
    /// exact for scene files and SVGs).
    #[arg(long)]
    pub method: Option<MethodId>,
    /// Directory for the two PNGs.
    #[arg(long)]
    pub out: PathBuf,
}

#[derive(Args, Debug)]
#[command(group(ArgGroup::new("drawn").args(["scene", "svg"]).required(true)))]
pub struct RenderOpt {
    /// A built-in scene, a scene file or an SVG.
    #[command(flatten)]
    pub drawing: SceneArgs,
    /// Fill method (default: the scene's own, the method its source uses;
    /// exact for scene files and SVGs).
    #[arg(long)]
    pub method: Option<MethodId>,
    /// The PNG to write.
    #[arg(long, value_name = "FILE.png")]
    pub out: PathBuf,
}

#[derive(Args, Debug)]
pub struct ConvertOpt {
    /// The SVG to convert.
    #[arg(long, value_name = "IN")]
    pub svg: PathBuf,
    /// The scene file to write; written beside it first, renamed when complete.
    #[arg(long, value_name = "OUT.scene")]
    pub out: PathBuf,
    #[command(flatten)]
    pub import: SvgArgs,
}

#[derive(Args, Debug)]
pub struct RecordOpt {
    /// A show entry (an animation such as lamothe-rotate, race or world, or
    /// a still page), or a scene file or an SVG, filmed drawn by every
    /// method in turn, a frame each.
    #[command(flatten)]
    pub drawing: SceneArgs,
    /// How many frames of a show entry to record.
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..))]
    pub frames: Option<u32>,
    /// The animated GIF to write; written beside it first, renamed when complete.
    #[arg(long, value_name = "FILE.gif")]
    pub out: PathBuf,
    /// Fill method for every frame (default: the entry's own; in the race,
    /// the method whose turn it is; for a scene file or an SVG, every
    /// method in turn).
    #[arg(long)]
    pub method: Option<MethodId>,
    /// The first frame recorded (frame numbers wrap around the entry's frames).
    #[arg(long, default_value_t = 0)]
    pub start: u32,
    /// Frames from one recorded frame to the next.
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..))]
    pub step: u32,
    /// Skip checking each dump against the host render and the show's palette.
    #[arg(long)]
    pub no_verify: bool,
}

#[derive(Args, Debug)]
pub struct ImageOpt {
    /// How a PC with Secure Boot on comes to trust the loader: `hash`
    /// enrolls this build's loader by its SHA-256 (no key at all; each
    /// build is enrolled anew), `key` signs it with your key (made for you
    /// in ~/.config/polylab/secure-boot, encrypted under a passphrase;
    /// enrolled once). docs/secure-boot.md weighs the two.
    #[arg(long, value_enum, default_value_t = EnrollOpt::Hash)]
    pub enroll: EnrollOpt,
    /// With `--enroll key`: sign with this private key (PEM, encrypted)
    /// instead of the one made for you (or set POLYLAB_SECURE_BOOT_KEY).
    #[arg(long, requires = "cert")]
    pub key: Option<PathBuf>,
    /// The key's certificate, PEM or DER (or set POLYLAB_SECURE_BOOT_CERT).
    #[arg(long, requires = "key")]
    pub cert: Option<PathBuf>,
    /// With `--enroll key`: the key's passphrase, the one line of this
    /// file, which must be yours and mode 0600 (else the build asks on
    /// the terminal, or takes POLYLAB_SECURE_BOOT_PASSPHRASE, which stays
    /// in the environment of the processes above this one).
    #[arg(long)]
    pub passphrase_file: Option<PathBuf>,
}

/// `cargo xtask image --enroll`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum EnrollOpt {
    Hash,
    Key,
}

#[derive(Args, Debug)]
pub struct TestOpt {
    /// Tests running at once, across the test binaries (default: three
    /// per core).
    #[arg(long, short, value_parser = clap::value_parser!(u16).range(1..))]
    pub jobs: Option<u16>,
    /// Passed on to `cargo test` (e.g. `-- --test pages`, `-- -- --nocapture`).
    #[arg(trailing_var_arg = true, allow_hyphen_values = true)]
    pub cargo_args: Vec<String>,
}

#[derive(Args, Debug)]
pub struct LabOpt {
    /// A small corpus and short timing, for CI (a few minutes); with
    /// --scene or --svg, the short timing alone.
    #[arg(long)]
    pub quick: bool,
    /// Launches of the whole timing, each a fresh process of the lab, one
    /// after the other; every ratio's interval is across them [default:
    /// 3, or 2 with --quick].
    #[arg(long, value_parser = clap::value_parser!(u16).range(1..))]
    pub launches: Option<u16>,
    /// The build(s) measured: `native` (-C target-cpu=native), `v3`
    /// (x86-64-v3: AVX2, no AVX-512), or `both`, one after the other, each
    /// in DIR/native and DIR/x86-64-v3 with DIR/report.md setting them side
    /// by side.
    #[arg(long, value_enum, default_value_t = LabBuild::Native)]
    pub build: LabBuild,
    /// Where results.json, report.md and the charts go [default:
    /// target/lab, or target/lab-scene with --scene or --svg].
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Measure every method and peer on the polygons of this scene file
    /// instead of the corpus, in families by class; a bad file is refused
    /// before anything is built or written.
    #[arg(long, value_name = "FILE", conflicts_with = "svg")]
    pub scene: Option<PathBuf>,
    /// The same for an SVG file, imported as `svg_import` imports it (its
    /// default options: curves within 0.1 px, its view box fitted to
    /// 320x200).
    #[arg(long, value_name = "FILE")]
    pub svg: Option<PathBuf>,
}

/// What `cargo xtask lab --build` builds the lab as.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum LabBuild {
    Native,
    V3,
    Both,
}

#[derive(Args, Debug)]
pub struct KbenchOpt {
    /// Draws per method and scene; the median is reported.
    #[arg(long, default_value_t = BENCH_DEFAULT_REPEATS, value_parser = bench_repeats())]
    pub repeats: u8,
    /// Where kernel_bench.md and kernel_bench.json go.
    #[arg(long, default_value = "target/lab")]
    pub out: PathBuf,
    /// Bench the kernel on the PC whose COM1 is cabled to this tty
    /// (e.g. /dev/ttyUSB0) rather than under QEMU.
    #[arg(long, value_name = "DEVICE")]
    pub serial: Option<PathBuf>,
    /// With --serial: how many times a step the line damages is retried.
    #[arg(long, default_value_t = DEFAULT_RETRIES)]
    pub retries: u32,
    /// Time every method on these scene files and SVGs (each uploaded
    /// whole) instead of the demo scenes.
    #[command(flatten)]
    pub files: SceneFiles,
}

/// `--repeats`: what the kernel's `BENCH` takes, 1 to its most.
fn bench_repeats() -> impl clap::builder::TypedValueParser<Value = u8> {
    clap::value_parser!(u8).range(1..=i64::from(BENCH_MAX_REPEATS))
}

/// Retries of one step the serial line damaged, by default.
const DEFAULT_RETRIES: u32 = 8;

#[derive(Args, Debug)]
pub struct CheckOpt {
    /// The tty the PC's COM1 is cabled to (/dev/ttyUSB0, /dev/ttyS0, a
    /// pseudo-terminal).
    #[arg(long, value_name = "DEVICE")]
    pub serial: PathBuf,
    /// Where report.md and report.json go.
    #[arg(long, value_name = "DIR", default_value = "target/check")]
    pub out: PathBuf,
    /// How many times a step the line damages is retried (0: the first
    /// damage fails the check).
    #[arg(long, default_value_t = DEFAULT_RETRIES)]
    pub retries: u32,
    /// A quick look instead of the whole check: two pages with two
    /// methods, one animation, one bench scene.
    #[arg(long)]
    pub quick: bool,
    /// BENCH draws per method and scene; the median is reported.
    #[arg(long, default_value_t = BENCH_DEFAULT_REPEATS, value_parser = bench_repeats())]
    pub repeats: u8,
    /// Seconds to wait for the kernel to answer at all (a PC still booting).
    #[arg(long, value_name = "SECONDS", default_value_t = 120)]
    pub wait: u64,
    /// Also check these scene files and SVGs (each uploaded whole, drawn
    /// with every method checked, and timed).
    #[command(flatten)]
    pub files: SceneFiles,
}

#[derive(Args, Debug)]
pub struct ExploreOpt {
    /// Write the page to DIR without serving it (default: serve it from
    /// target/explorer).
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// A lab results.json (from `cargo xtask lab`, e.g. target/lab/results.json)
    /// to copy beside the page, whose figures it then shows.
    #[arg(long, value_name = "FILE")]
    pub results: Option<PathBuf>,
    /// A scene (a built-in page, a scene file or, with --svg, an SVG) the
    /// page opens when its address names none.
    #[command(flatten)]
    pub drawing: SceneArgs,
}

/// The firmware `name` names; otherwise an error listing them.
fn firmware_named(name: &str) -> anyhow::Result<Firmware> {
    Firmware::from_name(name).with_context(|| format!("unknown firmware `{name}`; the firmwares are bios, uefi"))
}

#[derive(Args, Debug)]
pub struct FuzzOpt {
    /// How long each target runs, in seconds.
    #[arg(long, default_value_t = 60, value_parser = clap::value_parser!(u32).range(1..))]
    pub seconds: u32,
    /// One target (scene_file, command, methods, exact_reference,
    /// explorer, svg); all of them, one after the other, if none is named.
    pub target: Option<String>,
}

#[derive(Args, Debug)]
pub struct SoakOpt {
    /// How many times to play the show with every method.
    #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u32).range(2..))]
    pub cycles: u32,
    /// Play every K-th frame of each entry (1: every frame).
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..))]
    pub step: u32,
}

/// `cargo xtask COMMAND ARGS` parsed, for the commands' tests.
#[cfg(test)]
pub fn parse_command(command: &str, args: &[&str]) -> Result<Action, clap::Error> {
    let head = ["cargo xtask", command];
    Cli::try_parse_from(head.iter().chain(args)).map(|cli| cli.action)
}
