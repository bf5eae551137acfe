//! `cargo xtask run`: the demo, in a window or headless, under the
//! firmware, on the display card and from the boot medium asked for, from
//! the entry or scene file and with the method asked for.

use std::path::{Path, PathBuf};

use anyhow::{bail, Result};
use boot_image::build_image;
use harness::checks::{screen_matches_dump, show_matches_host_render, source_matches_host_render};
use harness::client::pack_for_upload;
use harness::sources::{entry_names, SceneFile, SceneSource};
use harness::workspace::target_dir;
use harness::{Display, Medium, Qemu, QemuOptions, TimeBase};
use install::ensure_all;
use protocol::{Command, Firmware};
use raster::MethodId;
use scenes::show::{self, Entry, ENTRIES_IN_ORDER};

use crate::opt::RunOpt;
use crate::record::{summary, Frames, Recording};
use crate::source::SceneArgs;

/// Show frames from one recorded frame to the next when running headless:
/// a loop of 256 frames becomes a GIF of 64.
const HEADLESS_STEP: u32 = 4;

/// What `--scene` or `--svg` names.
enum OnScreen {
    /// The whole show (neither), or one entry of it.
    Show(Option<&'static Entry>),
    /// A scene file or an SVG, drawn once and left on the screen.
    File(SceneFile),
}

impl OnScreen {
    /// The SVG imported; or the show entry `--scene` names, or else the
    /// scene file at that path; an error listing the entries when it is
    /// neither. Checked before QEMU starts.
    fn find(drawing: &SceneArgs) -> Result<Self> {
        if let Some(file) = drawing.svg_file()? {
            return Ok(OnScreen::File(file));
        }
        let Some(name) = drawing.scene.as_deref() else { return Ok(OnScreen::Show(None)) };
        if let Some(entry) = show::entry(name) {
            return Ok(OnScreen::Show(Some(entry)));
        }
        if Path::new(name).is_file() {
            return SceneFile::read(Path::new(name)).map(OnScreen::File);
        }
        bail!("`{name}` is neither an entry of the show nor a scene file; the entries are {}", entry_names())
    }
}

pub fn run(opt: &RunOpt) -> Result<()> {
    // Everything that can be refused is refused before QEMU starts.
    let shown = OnScreen::find(&opt.drawing)?;
    if let OnScreen::File(file) = &shown {
        pack_for_upload(&file.scene)?;
    }
    let medium = if opt.usb { Medium::UsbStick } else { Medium::Disk };
    if !opt.vga.proven_under(opt.firmware) {
        eprintln!(
            "xtask: note: the adapter matrix does not cover --vga {} under --firmware {}; running it anyway",
            opt.vga.name(),
            opt.firmware.name()
        );
    }
    let has_display =
        ["DISPLAY", "WAYLAND_DISPLAY"].iter().any(|var| std::env::var_os(var).is_some_and(|v| !v.is_empty()));
    let display = if has_display && !opt.headless { Display::Window } else { Display::Headless };
    let options = QemuOptions { firmware: opt.firmware, adapter: opt.vga, medium, display, ..QemuOptions::default() };
    // What QEMU needs, installed before the image builds: a user who is
    // not root is told every missing package at once.
    ensure_all(&options.needs())?;
    if display == Display::Window {
        in_a_window(&shown, opt.method, options)
    } else {
        let out = opt.out.clone().unwrap_or_else(|| target_dir().join("run"));
        headless(&shown, opt.method, options, &out)
    }
}

/// QEMU in a window until it closes. With nothing asked for, the kernel
/// plays its demo with nobody talking to it (pages change on a timer, or
/// on a key press); an entry or a method is asked for with `DEMO`, which
/// plays the demo from that entry and stays on it; a scene file is
/// uploaded, drawn and stays on the screen.
fn in_a_window(shown: &OnScreen, method: Option<MethodId>, options: QemuOptions) -> Result<()> {
    let mut qemu = match (shown, method) {
        (OnScreen::Show(None), None) => Qemu::spawn(&build_image()?, options)?,
        (OnScreen::Show(entry), method) => {
            let mut qemu = Qemu::boot(options)?;
            qemu.console.ok(&Command::Demo { entry: entry.map(|entry| entry.name), method })?;
            qemu
        }
        (OnScreen::File(file), method) => {
            let mut qemu = Qemu::boot(options)?;
            qemu.console.draw_scene(&file.scene, file.scene.method_or(method))?;
            qemu
        }
    };
    eprintln!("xtask: the demo runs in the QEMU window; close it to finish");
    qemu.wait_until_closed()
}

/// No display: plays the show (or the one entry) through `SHOW` as the
/// demo would, entry by entry, into `out`: a still as `<entry>.png`, an
/// animation as `<entry>.gif` (every [`HEADLESS_STEP`]-th frame of one
/// loop); or draws the scene file into `<name>.png`. Every picture is the
/// kernel's dump, checked against the host render, and a still's (or the
/// file's) against QEMU's screendump too; each path and the cycles are
/// printed. QEMU counts instructions ([`headless_clock`]).
fn headless(shown: &OnScreen, method: Option<MethodId>, options: QemuOptions, out: &Path) -> Result<()> {
    eprintln!("xtask: headless (no display, or --headless): writing the pictures into {}", out.display());
    let mut qemu = Qemu::boot(QemuOptions { clock: headless_clock(options.firmware), ..options })?;
    let png = |name: &str| -> PathBuf { out.join(format!("{name}.png")) };
    match shown {
        OnScreen::Show(entry) => {
            let entries = entry.map_or(ENTRIES_IN_ORDER, std::slice::from_ref);
            for entry in entries {
                if entry.is_animated() {
                    let path = out.join(format!("{}.gif", entry.name));
                    let frames = Frames { start: 0, step: HEADLESS_STEP, count: entry.frames.div_ceil(HEADLESS_STEP) };
                    let shown = Recording::new(entry, frames, method, true, &path)?.film(&mut qemu.console)?;
                    println!("{}", path.display());
                    print!("{}", summary(&shown));
                } else {
                    let (shown, dump) = show_matches_host_render(&mut qemu.console, entry.name, 0, method)?;
                    screen_matches_dump(entry.name, &dump, &qemu.screendump()?, &qemu.ready.video)?;
                    write_png(&dump.image(), &png(entry.name))?;
                    print!("{}", summary(&[shown]));
                }
            }
        }
        OnScreen::File(file) => {
            let method = file.scene.method_or(method);
            let source = SceneSource::File(file.clone());
            let dump = source_matches_host_render(&mut qemu.console, &source, method)?;
            screen_matches_dump(source.name(), &dump, &qemu.screendump()?, &qemu.ready.video)?;
            write_png(&dump.image(), &png(source.name()))?;
        }
    }
    qemu.quit()?;
    Ok(())
}

/// The guest's clock for a headless run under `firmware`. Under the BIOS,
/// instructions, as for `record`: `SHOW` is not paced by the clock, and
/// the cycles the labels and the summary give are then emulated
/// instructions, the same from run to run. Under OVMF, the host's time:
/// OVMF busy-waits on the ACPI PM timer for seconds while it boots
/// (sampled: most of it in PEI, polling a TPM's registers at 0xFED40000
/// that are not there until each wait times out), and at one instruction
/// per nanosecond those seconds are billions of emulated instructions:
/// 110 s of QEMU's CPU time before the kernel ran, against 5.5 s on the
/// host's clock, so that the boot missed READY's deadline on a loaded
/// machine.
fn headless_clock(firmware: Firmware) -> TimeBase {
    match firmware {
        Firmware::Bios => TimeBase::InstructionCount,
        Firmware::Uefi => TimeBase::RealTime,
    }
}

/// Writes `image` to `path` (creating its folder) and prints the path.
fn write_png(image: &harness::Image, path: &Path) -> Result<()> {
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir)?;
    }
    image.write_png(path)?;
    println!("{}", path.display());
    Ok(())
}

#[cfg(test)]
mod tests {
    use std::fs;

    use super::*;
    use crate::opt::{parse_command, Action};
    use crate::source::svg_fixture;
    use harness::render::render_show;
    use harness::Adapter;

    fn parse(args: &[&str]) -> Result<RunOpt, clap::Error> {
        parse_command("run", args).map(|action| match action {
            Action::Run(opt) => opt,
            other => panic!("parsed as {other:?}"),
        })
    }

    /// `cargo xtask run --headless ARGS --out DIR`: what it wrote, by name.
    fn run_headless(args: &[&str], out: &Path) -> Result<Vec<String>> {
        let out_arg = out.to_str().expect("a UTF-8 temporary path");
        let opt = parse(&[args, &["--headless", "--out", out_arg]].concat())?;
        run(&opt)?;
        let mut names: Vec<String> = fs::read_dir(out)?
            .map(|entry| entry.map(|e| e.file_name().to_string_lossy().into_owned()))
            .collect::<std::io::Result<_>>()?;
        names.sort();
        Ok(names)
    }

    #[test]
    fn defaults_are_the_whole_show_under_the_bios_on_the_standard_vga_from_the_disk() {
        let opt = parse(&[]).unwrap();
        assert_eq!(
            (opt.drawing.scene, opt.drawing.svg, opt.method, opt.firmware, opt.vga, opt.usb, opt.out),
            (None, None, None, Firmware::Bios, Adapter::Std, false, None)
        );
    }

    #[test]
    fn unknown_names_are_refused_with_the_valid_ones_before_qemu_starts() {
        let vga = parse(&["--vga", "qxl"]).unwrap_err().to_string();
        assert!(
            vga.contains(
                "unknown display adapter `qxl`; the adapters are std, cirrus, vmware, qxl-vga, virtio-vga, ati-vga, \
                 bochs-display, ramfb, virtio-gpu, none"
            ),
            "{vga}"
        );
        let firmware = parse(&["--firmware", "efi"]).unwrap_err().to_string();
        assert!(firmware.contains("unknown firmware `efi`; the firmwares are bios, uefi"), "{firmware}");
        let method = parse(&["--method", "fastest"]).unwrap_err().to_string();
        assert!(method.contains("unknown method; the methods are abrash_float, "), "{method}");
        let scene = run(&parse(&["--scene", "no-such-entry", "--headless"]).unwrap()).unwrap_err().to_string();
        assert!(scene.starts_with("`no-such-entry` is neither an entry of the show nor a scene file"), "{scene}");
        assert!(scene.ends_with(", race, world"), "{scene}");
    }

    #[test]
    fn headless_runs_count_instructions_under_the_bios_only() {
        assert_eq!(headless_clock(Firmware::Bios), TimeBase::InstructionCount);
        assert_eq!(headless_clock(Firmware::Uefi), TimeBase::RealTime);
    }

    #[test]
    fn an_animation_with_one_method_on_the_cirrus_card_is_filmed_alone() -> Result<()> {
        let dir = tempfile::tempdir()?;
        let written = run_headless(&["--scene", "lamothe-rotate", "--method", "exact", "--vga", "cirrus"], dir.path())?;
        assert_eq!(written, ["lamothe-rotate.gif"]);
        Ok(())
    }

    #[test]
    fn a_page_with_one_method_boots_from_the_usb_stick_under_uefi_on_ramfb() -> Result<()> {
        let dir = tempfile::tempdir()?;
        let args = ["--scene", "abrash38-2", "--method", "wgt", "--usb", "--firmware", "uefi", "--vga", "ramfb"];
        let written = run_headless(&args, dir.path())?;
        assert_eq!(written, ["abrash38-2.png"]);
        // The PNG is the kernel's dump, which `run` checked against the
        // host render and QEMU's screendump (the whole ramfb framebuffer,
        // the frame scaled and centred in it); here it is read back from
        // disk.
        let page = show::entry("abrash38-2").expect("a page of the show");
        let expected = render_show(page, 0, MethodId::Wgt, 0);
        let written = harness::Image::read_png(&dir.path().join("abrash38-2.png"))?;
        harness::picture::compare::compare_image_rows("run.abrash38-2.wgt", &expected, &written, 0..188)?;
        Ok(())
    }

    #[test]
    fn a_scene_file_is_drawn_and_kept_with_the_method_asked_for() -> Result<()> {
        let dir = tempfile::tempdir()?;
        let file = dir.path().join("mine.scene");
        fs::write(&file, "clear 1\npoly color=14 10,10 300.5,20 160,190.25 | 100,60 200,60 150,150\n")?;
        let out = dir.path().join("out");
        let written = run_headless(&["--scene", file.to_str().unwrap(), "--method", "abrash_aet"], &out)?;
        assert_eq!(written, ["mine.png"]);
        Ok(())
    }

    #[test]
    fn svgs_are_drawn_and_kept_checked_against_the_host_render() -> Result<()> {
        let dir = tempfile::tempdir()?;
        let strokes = svg_fixture("strokes.svg");
        let written = run_headless(&["--svg", strokes.to_str().unwrap()], &dir.path().join("strokes"))?;
        assert_eq!(written, ["strokes.png"]);
        // The left star alone, in the VGA palette, with the edge tables.
        let rules = svg_fixture("rules.svg");
        let args = ["--svg", rules.to_str().unwrap(), "--view-box", "0,0,160,200", "--palette", "vga"];
        let written = run_headless(&[&args[..], &["--method", "abrash_aet"]].concat(), &dir.path().join("rules"))?;
        assert_eq!(written, ["rules.png"]);
        Ok(())
    }

    #[test]
    fn a_bad_svg_is_refused_before_qemu_starts_and_nothing_is_written() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("out");
        let nan = svg_fixture("bad/nan.svg");
        let error = format!("{:#}", run_headless(&["--svg", nan.to_str().unwrap()], &out).unwrap_err());
        assert!(error.contains("not imported: <path id=\"broken\"> at line 3: bad path data: "), "{error}");
        assert!(!out.exists());
    }

    #[test]
    fn the_import_options_go_with_svg_only() {
        assert!(parse(&["--svg", "a.svg", "--palette", "vga", "--view-box", "0,0,5,5", "--tolerance", "1"]).is_ok());
        for option in [["--tolerance", "0.5"], ["--view-box", "0,0,1,1"], ["--palette", "vga"]] {
            for scene in [&["--scene", "abrash38-1"][..], &[]] {
                let args = [scene, &option[..]].concat();
                let error = run(&parse(&args).unwrap()).unwrap_err().to_string();
                assert_eq!(error, "--tolerance, --view-box and --palette go with --svg", "{args:?}");
            }
        }
    }

    #[test]
    fn bad_import_options_are_refused_by_the_parser() {
        let error = parse(&["--svg", "a.svg", "--view-box", "0,0,5"]).unwrap_err().to_string();
        assert!(error.contains("bad view box `0,0,5` (expected four numbers, X,Y,W,H)"), "{error}");
        let error = parse(&["--svg", "a.svg", "--palette", "ega"]).unwrap_err().to_string();
        assert!(error.contains("unknown palette `ega`; the palettes are own, vga"), "{error}");
        let error = parse(&["--svg", "a.svg", "--tolerance", "fine"]).unwrap_err().to_string();
        assert!(error.contains("invalid value 'fine' for '--tolerance <PX>'"), "{error}");
    }
}
