//! The harness's checks run on a machine at the other end of a serial
//! line (`cargo xtask check --serial DEVICE`): the kernel found on the
//! line, every demo page drawn with every method, the first frame of every
//! show entry and the user's own scenes (uploaded whole), each `DUMP`
//! compared with the host render; `VGACHECK`; `BENCH` of every method on
//! every demo scene and the user's scenes in the machine's TSC ticks;
//! the line's losses (`PING`) and what was retried. Every step is retried
//! as a whole when the line damages it (`crate::client`'s sealing), so a picture is
//! judged only on a dump that arrived intact. `report` writes the result
//! for a person and for a program.

pub mod bench_table;
mod report;

use std::time::{Duration, Instant};

use anyhow::{ensure, Context, Result};
use protocol::{Command, LineLosses, TscRate};
use raster::MethodId;
use scenes::palette::{Palette, VGA_DEFAULT};
use scenes::{builtin, show, Scene};

use crate::client::{Console, Dump, LineStats, Reply};
use crate::picture::compare::{compare_images, differing_palette_entries, differing_pixel_count};
use crate::picture::render::{render, render_show};
use crate::sources::{builtin_scene, show_entry};
use crate::Image;
use bench_table::{BenchTable, Benched, TickUnit};
pub use report::write_reports;

/// What the check covers.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Scope {
    /// Demo pages (built-in scenes), each drawn with each of `methods`.
    pub pages: Vec<&'static str>,
    pub methods: Vec<MethodId>,
    /// Show entries whose first frame is shown with the entry's own method.
    pub show_entries: Vec<&'static str>,
    /// Scenes `BENCH` times every method on.
    pub bench_scenes: Vec<&'static str>,
    /// The user's own scenes (a scene file, an SVG), each uploaded whole,
    /// drawn with each of `methods` and timed by `BENCH`.
    pub files: Vec<Scene>,
}

impl Scope {
    /// Everything: what the harness checks under QEMU.
    pub fn full() -> Self {
        let pages = builtin::ALL.map(|page| page.name).to_vec();
        Scope {
            pages: pages.clone(),
            methods: MethodId::ALL.to_vec(),
            show_entries: show::ENTRIES_IN_ORDER.iter().map(|entry| entry.name).collect(),
            bench_scenes: pages,
            files: Vec::new(),
        }
    }

    /// A taste of each part, for a quick look at a line: two pages with the
    /// float and the exact method, one animation, one bench scene.
    pub fn quick() -> Self {
        Scope {
            pages: vec!["abrash38-1", "abrash40-4"],
            methods: vec![MethodId::AbrashFloat, MethodId::Exact],
            show_entries: vec!["lamothe-rotate"],
            bench_scenes: vec!["abrash38-3"],
            files: Vec::new(),
        }
    }

    /// Pictures compared.
    pub fn pictures(&self) -> usize {
        (self.pages.len() + self.files.len()) * self.methods.len() + self.show_entries.len()
    }

    /// Scenes timed by `BENCH`.
    pub fn benched(&self) -> Vec<Benched<'_>> {
        let pages = self.bench_scenes.iter().map(|&page| Benched::Page(page));
        pages.chain(self.files.iter().map(Benched::Uploaded)).collect()
    }
}

/// How the check runs.
#[derive(Clone, Debug)]
pub struct CheckOptions {
    pub scope: Scope,
    /// `BENCH` draws per method and scene; the median is reported.
    pub repeats: u8,
    /// How long to wait for the kernel to answer at all (a PC booting).
    pub wait: Duration,
}

/// One picture compared.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Picture {
    /// The page, the show entry, or the user's scene.
    pub scene: String,
    /// The frame, for a show entry.
    pub frame: Option<u32>,
    pub method: MethodId,
    /// Pixels whose byte differs from the host render's (all of them if the
    /// sizes differ).
    pub differing_pixels: usize,
    /// DAC entries that differ from the palette the picture is drawn in.
    pub differing_palette_entries: usize,
    /// For a picture that differs: where its expected, actual and diff
    /// PNGs were written.
    pub diff: Option<String>,
}

impl Picture {
    pub fn equal(&self) -> bool {
        self.differing_pixels == 0 && self.differing_palette_entries == 0
    }
}

/// Everything the check found.
#[derive(Clone, Debug)]
pub struct CheckReport {
    pub device: String,
    /// The kernel's `READY` text, and whether it came at boot (else the
    /// check asked for it).
    pub ready: String,
    pub ready_at_boot: bool,
    pub pictures: Vec<Picture>,
    /// `VGACHECK`'s answer: whether it was `OK`, and its text.
    pub vgacheck: (bool, String),
    pub bench: BenchTable,
    pub tsc: TscRate,
    /// What the kernel counted as lost on the way in, at the last `PING`.
    pub line: LineLosses,
    /// What the host sent and retried.
    pub stats: LineStats,
    pub retries_allowed: u32,
    pub bytes_received: u64,
    pub elapsed: Duration,
}

impl CheckReport {
    /// The pictures that differ.
    pub fn differing(&self) -> impl Iterator<Item = &Picture> {
        self.pictures.iter().filter(|picture| !picture.equal())
    }
}

/// Where the check is: a step about to run, of how many.
pub struct Progress<'a> {
    pub done: usize,
    pub total: usize,
    pub step: &'a str,
    pub stats: Option<&'a LineStats>,
}

/// Runs the check on the kernel behind `console` (`device` names it in
/// messages and the report), calling `progress` before each step. Fails
/// when the kernel cannot be found or a step fails for good (the line
/// damaged it more often than the console retries, the kernel answered
/// nonsense or failed); a picture that differs is a finding, not a failure.
pub fn run(
    console: &mut Console,
    device: &str,
    options: &CheckOptions,
    mut progress: impl FnMut(&Progress),
) -> Result<CheckReport> {
    let started = Instant::now();
    let scope = &options.scope;
    let total = 4 + scope.pictures() + scope.files.len() * 2 + scope.bench_scenes.len();
    let mut done = 0;
    let mut step = |what: &str, console: &Console| {
        progress(&Progress { done, total, step: what, stats: console.line_stats() });
        done += 1;
    };
    step("waiting for the kernel", console);
    let (ready, ready_at_boot) = console.wait_for_kernel(options.wait, device)?;
    step("CLOCK", console);
    let tsc = console.retrying(Console::tsc_rate)?;
    let mut pictures = Vec::with_capacity(scope.pictures());
    for &page in &scope.pages {
        let scene = builtin_scene(page)?;
        for &method in &scope.methods {
            step(&format!("{page} with {method}"), console);
            let dump = console.retrying(|console| {
                console.draw(page, Some(method))?;
                console.dump()
            })?;
            let expected = render(&scene, method);
            pictures.push(judge(page, None, method, &expected, &dump, &VGA_DEFAULT));
        }
    }
    for scene in &scope.files {
        step(&format!("UPLOAD {}", scene.name), console);
        let name = console.upload(scene)?.name;
        for &method in &scope.methods {
            step(&format!("{} with {method}", scene.name), console);
            let dump = console.retrying(|console| {
                console.clear(0)?;
                console.draw_uploaded(&name, method)?;
                console.dump()
            })?;
            let expected = render(scene, method);
            pictures.push(judge(&scene.name, None, method, &expected, &dump, &scene.dac()));
        }
    }
    for &name in &scope.show_entries {
        let entry = show_entry(name)?;
        let method = entry.method_at(0);
        step(&format!("{name} frame 0"), console);
        let (reply, dump) = console.retrying(|console| Ok((console.show(entry.name, 0, None)?, console.dump()?)))?;
        let said = (reply.entry, reply.frame, reply.method);
        ensure!(said == (entry.name, 0, method), "SHOW {name} 0: the kernel says it showed {said:?}");
        let expected = render_show(entry, 0, method, reply.cycles);
        pictures.push(judge(entry.name, Some(0), method, &expected, &dump, &show::PALETTE));
    }
    step("VGACHECK", console);
    let vgacheck = match console.retrying(|console| console.request(&Command::VgaCheck))? {
        Reply::Ok(text) => (true, text),
        Reply::Err(text) => (false, text),
        other => anyhow::bail!("`VGACHECK` answered {}", other.describe()),
    };
    let bench =
        BenchTable::measure(console, TickUnit::Tsc(tsc), &scope.benched(), options.repeats, |what, console| {
            step(what, console)
        })?;
    step("PING", console);
    let line = console.retrying(Console::ping).context("the last PING")?;
    Ok(CheckReport {
        device: device.to_string(),
        ready,
        ready_at_boot,
        pictures,
        vgacheck,
        bench,
        tsc,
        line,
        stats: console.line_stats().cloned().unwrap_or_default(),
        retries_allowed: console.retries_allowed(),
        bytes_received: console.bytes_received(),
        elapsed: started.elapsed(),
    })
}

/// The kernel's `dump` of `scene` drawn with `method` against the host's
/// `expected` render and the `palette` it is drawn in; a picture that
/// differs gets its PNGs written (`compare_images`).
fn judge(
    scene: &str,
    frame: Option<u32>,
    method: MethodId,
    expected: &Image,
    dump: &Dump,
    palette: &Palette,
) -> Picture {
    let actual = dump.image();
    let name = match frame {
        Some(frame) => format!("check.{scene}.{frame}.{method}"),
        None => format!("check.{scene}.{method}"),
    };
    Picture {
        scene: scene.to_string(),
        frame,
        method,
        differing_pixels: differing_pixel_count(expected, &actual),
        differing_palette_entries: differing_palette_entries(palette, &dump.palette),
        diff: compare_images(&name, expected, &actual).err().map(|error| error.to_string()),
    }
}
