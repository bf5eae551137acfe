//! `cargo xtask record`: frames of a show entry drawn by the kernel with
//! `SHOW`, read back with `DUMP` (framebuffer and DAC), written as an
//! animated GIF paced like the demo; or a scene file or an SVG, uploaded
//! and drawn by every method in turn (`DRAW`), a frame each, captioned on
//! the host with the method and how many pixels it sets otherwise than
//! `exact`.

use std::fs::{self, Permissions};
use std::io::{BufWriter, Write};
use std::os::unix::fs::PermissionsExt;
use std::path::Path;

use anyhow::{bail, ensure, Context, Result};
use harness::checks::show_matches_host_render;
use harness::client::pack_for_upload;
use harness::picture::compare::{compare_images, compare_palettes, differing_pixel_count};
use harness::render::render;
use harness::sources::{show_entry, SceneFile};
use harness::{Console, Dump, Qemu, QemuOptions, TimeBase};
use indicatif::{ProgressBar, ProgressStyle};
use protocol::ShowReply;
use raster::{MethodId, Size, SpanSink, SCREEN};
use scenes::palette::{to_rgb8, ENTRIES};
use scenes::show::{self, draw_caption, Entry, FRAMES_PER_SECOND};
use tempfile::NamedTempFile;

use crate::opt::RecordOpt;

/// Centiseconds between two GIF frames `step` show frames apart, so the
/// GIF plays at the show's pace: `100 * step / FRAMES_PER_SECOND`, rounded,
/// at least 1 (GIF viewers treat 0 as "as fast as you like").
fn delay(step: u32) -> u16 {
    let centiseconds = (100 * u64::from(step) + u64::from(FRAMES_PER_SECOND / 2)) / u64::from(FRAMES_PER_SECOND);
    centiseconds.clamp(1, u64::from(u16::MAX)) as u16
}

pub fn record(opt: &RecordOpt) -> Result<()> {
    // Everything that can be checked is checked before spending a boot.
    if let Some(file) = opt.drawing.svg_file()? {
        return record_every_method(&file, opt);
    }
    let name = opt.drawing.scene.as_deref().context("no scene: give --scene ENTRY|FILE or --svg FILE")?;
    if show::entry(name).is_none() && Path::new(name).is_file() {
        return record_every_method(&SceneFile::read(Path::new(name))?, opt);
    }
    let entry = show_entry(name)?;
    let count = opt.frames.context("--frames N: how many frames of the show entry to record")?;
    let frames = Frames { start: opt.start, step: opt.step, count };
    let recording = Recording::new(entry, frames, opt.method, !opt.no_verify, &opt.out)?;
    // Instruction counting: the cycles in the labels and the summary count
    // emulated instructions, the same in every run (`SHOW` is not paced by
    // the clock, so the frames are the same either way).
    let mut qemu = Qemu::boot(QemuOptions { clock: TimeBase::InstructionCount, ..QemuOptions::default() })?;
    let shown = recording.film(&mut qemu.console)?;
    print!("{}", summary(&shown));
    qemu.quit()?;
    println!("{}", opt.out.display());
    Ok(())
}

/// Seconds each method's frame stays up in the recording of a scene file.
const SECONDS_A_METHOD: u16 = 2;

/// `file` uploaded and drawn by every method in turn (or by `--method`
/// alone), each dump checked against the host render unless
/// `--no-verify`, then captioned and written as a frame of
/// [`SECONDS_A_METHOD`].
fn record_every_method(file: &SceneFile, opt: &RecordOpt) -> Result<()> {
    pack_for_upload(&file.scene)?;
    let mut partial = Some(partial_file_for(&opt.out)?);
    let methods = opt.method.map_or(MethodId::ALL.to_vec(), |method| vec![method]);
    let exact = render(&file.scene, MethodId::Exact);
    let mut qemu = Qemu::boot(QemuOptions::default())?;
    let console = &mut qemu.console;
    let name = console.upload(&file.scene)?.name;
    let mut gif: Option<Gif<BufWriter<NamedTempFile>>> = None;
    for method in methods {
        console.clear(0)?;
        let drawn = console.draw_uploaded(&name, method)?;
        let mut dump = console.dump()?;
        if !opt.no_verify {
            let at = format!("{name}.{method}.record");
            compare_images(&at, &render(&file.scene, method), &dump.image())?;
            compare_palettes(&at, &file.scene.dac(), &dump.palette)?;
        }
        let off = differing_pixel_count(&exact, &dump.image());
        let refused = match drawn.refused {
            0 => String::new(),
            n => format!(", {n} polygons refused"),
        };
        println!("{method}: {off} pixels otherwise than exact{refused}");
        draw_caption(&mut Pixels(&mut dump.pixels), &file.scene.name, method.name(), &format!("{off} px off"));
        match gif.as_mut() {
            Some(gif) => gif.add(&dump)?,
            None => {
                let out = BufWriter::new(partial.take().context("the GIF is started once")?);
                gif = Some(Gif::new(out, &dump, 100 * SECONDS_A_METHOD)?);
            }
        }
    }
    let partial = gif.context("no method to record")?.finish()?.into_inner().context("failed to write the GIF")?;
    partial.persist(&opt.out).with_context(|| format!("failed to rename the GIF to {}", opt.out.display()))?;
    qemu.quit()?;
    println!("{}", opt.out.display());
    Ok(())
}

/// A dump's pixels as a target the caption is drawn into.
struct Pixels<'a>(&'a mut [u8]);

impl SpanSink for Pixels<'_> {
    fn size(&self) -> Size {
        SCREEN
    }

    fn span(&mut self, y: i32, x_start: i32, x_end: i32, color: u8) {
        if SCREEN.holds_span(y, x_start, x_end) {
            let row = (y * SCREEN.width) as usize;
            self.0[row + x_start as usize..row + x_end as usize].fill(color);
        }
    }
}

/// Which frames of an entry to film: `count` of them from `start`, every
/// `step`-th, wrapping around the entry's frames.
#[derive(Clone, Copy, Debug)]
pub struct Frames {
    pub start: u32,
    pub step: u32,
    pub count: u32,
}

/// Frames of one show entry to film into an animated GIF.
pub struct Recording<'a> {
    entry: &'static Entry,
    /// Frame numbers in the order filmed, each `step` after the last.
    frames: Vec<u32>,
    step: u32,
    /// The method for every frame; `None`, the entry's own.
    method: Option<MethodId>,
    /// Check every dump against the host render and the show's palette.
    verify: bool,
    /// Where the GIF goes once complete, and where it is written until then.
    out: &'a Path,
    partial: NamedTempFile,
}

impl<'a> Recording<'a> {
    /// A recording of `frames` of `entry` into `out`. Checks `out` now, so
    /// a bad path fails before QEMU boots.
    pub fn new(
        entry: &'static Entry,
        frames: Frames,
        method: Option<MethodId>,
        verify: bool,
        out: &'a Path,
    ) -> Result<Self> {
        let partial = partial_file_for(out)?;
        let numbers = frame_numbers(entry, frames.start, frames.step, frames.count).collect();
        Ok(Self { entry, frames: numbers, step: frames.step, method, verify, out, partial })
    }

    /// Films the frames through `console` (`SHOW`, `DUMP`) into the
    /// partial file, renamed to `out` once complete, with a progress bar;
    /// returns the kernel's replies.
    pub fn film(self, console: &mut Console) -> Result<Vec<ShowReply<'static>>> {
        let Self { out, partial, .. } = self;
        let Some((&first, rest)) = self.frames.split_first() else { bail!("no frames to record") };
        let bar = ProgressBar::new(self.frames.len() as u64).with_style(
            ProgressStyle::with_template("{elapsed_precise} [{bar:40}] {pos}/{len} frames {msg}")
                .expect("the progress template is valid")
                .progress_chars("=> "),
        );
        let name = self.entry.name;
        let mut shown = Vec::with_capacity(self.frames.len());
        let mut record_frame = |frame: u32| -> Result<Dump> {
            bar.set_message(format!("{name} frame {frame}"));
            let (reply, dump) = shoot(console, self.entry, frame, self.method, self.verify)
                .with_context(|| format!("{name} frame {frame}"))?;
            shown.push(reply);
            bar.inc(1);
            Ok(dump)
        };
        let mut gif = Gif::new(BufWriter::new(partial), &record_frame(first)?, delay(self.step))?;
        for &frame in rest {
            gif.add(&record_frame(frame)?)?;
        }
        bar.finish_and_clear();
        let partial = gif.finish()?.into_inner().context("failed to write the GIF")?;
        partial.persist(out).with_context(|| format!("failed to rename the GIF to {}", out.display()))?;
        Ok(shown)
    }
}

/// A temporary file beside `out`, which must name a `.gif`: written first,
/// renamed to `out` once complete (the rename stays on one file system),
/// deleted if dropped before, so a failure leaves nothing half-written.
/// Creating it proves `out`'s directory writable before QEMU boots.
fn partial_file_for(out: &Path) -> Result<NamedTempFile> {
    ensure!(
        out.extension().is_some_and(|ext| ext == "gif"),
        "--out {}: the recording is an animated GIF; name a FILE.gif",
        out.display()
    );
    ensure!(!out.is_dir(), "--out {} is a directory; name a FILE.gif", out.display());
    let dir = out.parent().filter(|dir| !dir.as_os_str().is_empty()).unwrap_or(Path::new("."));
    fs::create_dir_all(dir).with_context(|| format!("cannot create the directory {}", dir.display()))?;
    tempfile::Builder::new()
        .prefix(".record-")
        .suffix(".gif.partial")
        // What `File::create` asks for: the umask decides.
        .permissions(Permissions::from_mode(0o666))
        .tempfile_in(dir)
        .with_context(|| format!("cannot write in {}", dir.display()))
}

/// The `count` frame numbers recorded: from `start`, every `step`-th,
/// wrapping around the entry's frames.
fn frame_numbers(entry: &Entry, start: u32, step: u32, count: u32) -> impl Iterator<Item = u32> {
    let frames = u64::from(entry.frames);
    (0..u64::from(count)).map(move |i| ((u64::from(start) + i * u64::from(step)) % frames) as u32)
}

/// Frame `frame` of `entry` shown by the kernel and dumped, with the
/// kernel's reply; with `verify`, checked against the host render and the
/// show's palette first.
fn shoot(
    console: &mut Console,
    entry: &Entry,
    frame: u32,
    method: Option<MethodId>,
    verify: bool,
) -> Result<(ShowReply<'static>, Dump)> {
    if verify {
        return show_matches_host_render(console, entry.name, frame, method);
    }
    let reply = console.show(entry.name, frame, method)?;
    Ok((reply, console.dump()?))
}

/// What the kernel reported over the recording, a line per method in the
/// order first met: frames, the median and the largest rdtsc ticks of a
/// frame's draw (emulated instructions), and the median allocations per
/// frame.
pub fn summary(shown: &[ShowReply]) -> String {
    let mut methods: Vec<MethodId> = Vec::new();
    for reply in shown {
        if !methods.contains(&reply.method) {
            methods.push(reply.method);
        }
    }
    let mut text = String::new();
    for method in methods {
        let of_method = || shown.iter().filter(move |reply| reply.method == method);
        let median = |mut values: Vec<u64>| {
            values.sort_unstable();
            values[values.len() / 2]
        };
        let cycles: Vec<u64> = of_method().map(|reply| reply.cycles).collect();
        let (frames, most) = (cycles.len(), cycles.iter().max().copied().unwrap_or(0));
        let cycles = median(cycles);
        let allocs = median(of_method().map(|reply| reply.allocs).collect());
        text += &format!(
            "{method}: {frames} frame{}, draw cycles median {cycles} max {most} (rdtsc ticks: emulated instructions), allocations per frame median {allocs}\n",
            if frames == 1 { "" } else { "s" }
        );
    }
    text
}

/// An animated GIF of dumps that loops forever, `delay` centiseconds a frame.
/// The first dump's DAC is the global palette; a later dump whose DAC
/// differs carries its own.
struct Gif<W: Write> {
    encoder: gif::Encoder<W>,
    palette: [[u8; 3]; ENTRIES],
    delay: u16,
}

impl<W: Write> Gif<W> {
    /// Starts the GIF on `out` with `first` as its first frame.
    fn new(out: W, first: &Dump, delay: u16) -> Result<Self> {
        let (width, height) = (SCREEN.width as u16, SCREEN.height as u16);
        let mut encoder = gif::Encoder::new(out, width, height, &to_rgb8(&first.palette))?;
        encoder.set_repeat(gif::Repeat::Infinite)?;
        let mut gif = Self { encoder, palette: first.palette, delay };
        gif.add(first)?;
        Ok(gif)
    }

    fn add(&mut self, dump: &Dump) -> Result<()> {
        let mut frame =
            gif::Frame::from_indexed_pixels(SCREEN.width as u16, SCREEN.height as u16, dump.pixels.clone(), None);
        frame.delay = self.delay;
        if dump.palette != self.palette {
            frame.palette = Some(to_rgb8(&dump.palette).to_vec());
        }
        self.encoder.write_frame(&frame).context("failed to encode a GIF frame")
    }

    /// Writes the trailer and hands the output back.
    fn finish(self) -> Result<W> {
        self.encoder.into_inner().context("failed to finish the GIF")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use scenes::palette::VGA_DEFAULT;
    use scenes::show::{self, PALETTE};

    use crate::opt::{parse_command, Action};

    fn parse(args: &[&str]) -> Result<RecordOpt, clap::Error> {
        parse_command("record", args).map(|action| match action {
            Action::Record(opt) => opt,
            other => panic!("parsed as {other:?}"),
        })
    }

    #[test]
    fn arguments_default_to_every_frame_from_the_first_with_verification() {
        let opt = parse(&["--scene", "race", "--frames", "3", "--out", "r.gif"]).unwrap();
        assert_eq!((opt.start, opt.step, opt.method, opt.no_verify), (0, 1, None, false));
        let race = show::entry("race").unwrap();
        let wrapped: Vec<u32> = frame_numbers(race, race.frames - 1, 2, 3).collect();
        assert_eq!(wrapped, [race.frames - 1, 1, 3]);
        let still = show::entry("abrash38-1").unwrap();
        assert_eq!(frame_numbers(still, 5, 1, 2).collect::<Vec<_>>(), [0, 0]);
    }

    #[test]
    fn no_frames_or_no_step_is_refused_by_the_parser() {
        for bad in [["--frames", "0", "--step", "1"], ["--frames", "1", "--step", "0"]] {
            let error = parse(&[&["--scene", "race", "--out", "r.gif"][..], &bad[..]].concat()).unwrap_err();
            assert_eq!(error.kind(), clap::error::ErrorKind::ValueValidation, "{error}");
        }
    }

    #[test]
    fn bad_names_and_outputs_are_refused_before_any_boot() {
        let opt = |scene: &str, out: &str| parse(&["--scene", scene, "--frames", "1", "--out", out]).unwrap();
        let error = |opt: RecordOpt| format!("{:#}", record(&opt).unwrap_err());
        let unknown_scene = error(opt("nope", "/tmp/x.gif"));
        assert!(unknown_scene.starts_with("unknown show entry `nope`; valid entries: abrash38-1"), "{unknown_scene}");
        let unknown_method = parse(&["--scene", "race", "--frames", "1", "--out", "x.gif", "--method", "nope"]);
        let unknown_method = unknown_method.unwrap_err().to_string();
        assert!(unknown_method.contains("unknown method; the methods are abrash_float, "), "{unknown_method}");
        let not_gif = error(opt("race", "/tmp/x.png"));
        assert!(not_gif.contains("the recording is an animated GIF"), "{not_gif}");
        let dir = tempfile::tempdir().unwrap();
        let directory = dir.path().join("d.gif");
        fs::create_dir(&directory).unwrap();
        let directory = error(opt("race", directory.to_str().unwrap()));
        assert!(directory.ends_with("d.gif is a directory; name a FILE.gif"), "{directory}");
        let unwritable = error(opt("race", "/proc/polylab/x.gif"));
        assert!(unwritable.starts_with("cannot create the directory /proc/polylab"), "{unwritable}");
        let no_frames = error(parse(&["--scene", "race", "--out", "x.gif"]).unwrap());
        assert_eq!(no_frames, "--frames N: how many frames of the show entry to record");
        let bad_svg = crate::source::svg_fixture("bad/text.svg");
        let bad_svg = error(parse(&["--svg", bad_svg.to_str().unwrap(), "--out", "/tmp/x.gif"]).unwrap());
        assert!(bad_svg.contains("bad/text.svg"), "{bad_svg}");
        let svg = crate::source::svg_fixture("holes.svg");
        let not_gif = error(parse(&["--svg", svg.to_str().unwrap(), "--out", "/tmp/x.png"]).unwrap());
        assert!(not_gif.contains("the recording is an animated GIF"), "{not_gif}");
    }

    /// A scene file filmed by every method: one frame each, each dump the
    /// host render before its caption, which names the method.
    #[test]
    fn an_svg_is_filmed_drawn_by_every_method_in_turn() -> Result<()> {
        let dir = tempfile::tempdir()?;
        let out = dir.path().join("holes.gif");
        let svg = crate::source::svg_fixture("holes.svg");
        record(&parse(&["--svg", svg.to_str().unwrap(), "--out", out.to_str().unwrap()]).unwrap())?;
        let mut decoder = gif::DecodeOptions::new();
        decoder.set_color_output(gif::ColorOutput::Indexed);
        let mut decoder = decoder.read_info(fs::File::open(&out)?)?;
        let mut frames = 0;
        while let Some(frame) = decoder.read_next_frame()? {
            assert_eq!((frame.width, frame.height, frame.delay), (320, 200, 200));
            frames += 1;
        }
        assert_eq!(frames, MethodId::ALL.len());
        Ok(())
    }

    #[test]
    fn a_failed_recording_leaves_nothing_behind() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("sub").join("x.gif");
        drop(partial_file_for(&out).unwrap());
        assert_eq!(fs::read_dir(out.parent().unwrap()).unwrap().count(), 0);
    }

    fn dump(fill: u8, palette: [[u8; 3]; ENTRIES]) -> Dump {
        let pixels = (0..SCREEN.width * SCREEN.height).map(|i| (i as u8).wrapping_mul(fill)).collect();
        Dump { pixels, palette }
    }

    #[test]
    fn the_delay_keeps_the_show_s_pace_whatever_the_step() {
        assert_eq!([delay(1), delay(2), delay(7), delay(35)], [3, 6, 20, 100]);
        assert_eq!(delay(u32::MAX), u16::MAX);
    }

    #[test]
    fn the_summary_gives_each_method_its_median_and_largest_cycles() {
        let reply = |method: MethodId, cycles: u64, allocs: u64| ShowReply {
            entry: "race",
            frame: 0,
            method,
            cycles,
            allocs,
            polygons: 1,
            refused: 0,
            strays: 0,
        };
        let (wgt, exact) = (MethodId::Wgt, MethodId::Exact);
        let shown = [reply(wgt, 30, 2), reply(exact, 5, 0), reply(wgt, 10, 2), reply(wgt, 20, 4)];
        assert_eq!(
            summary(&shown),
            "wgt: 3 frames, draw cycles median 20 max 30 (rdtsc ticks: emulated instructions), allocations per frame median 2\n\
             exact: 1 frame, draw cycles median 5 max 5 (rdtsc ticks: emulated instructions), allocations per frame median 0\n"
        );
    }

    #[test]
    fn the_gif_decodes_to_the_dumps_in_their_palettes_looping_at_the_show_s_pace() {
        let dumps = [dump(1, PALETTE), dump(3, PALETTE), dump(7, VGA_DEFAULT)];
        let mut gif = Gif::new(Vec::new(), &dumps[0], delay(1)).unwrap();
        for dump in &dumps[1..] {
            gif.add(dump).unwrap();
        }
        let bytes = gif.finish().unwrap();
        let mut options = gif::DecodeOptions::new();
        options.set_color_output(gif::ColorOutput::Indexed);
        let mut decoder = options.read_info(bytes.as_slice()).unwrap();
        assert_eq!((decoder.width(), decoder.height()), (320, 200));
        assert_eq!(decoder.global_palette(), Some(&to_rgb8(&PALETTE)[..]));
        let mut decoded = Vec::new();
        while let Some(frame) = decoder.read_next_frame().unwrap() {
            assert_eq!((frame.left, frame.top, frame.width, frame.height, frame.delay), (0, 0, 320, 200, 3));
            decoded.push((frame.buffer.to_vec(), frame.palette.clone()));
        }
        assert_eq!(decoder.repeat(), gif::Repeat::Infinite);
        let expected: Vec<_> = dumps
            .iter()
            .zip([None, None, Some(to_rgb8(&VGA_DEFAULT).to_vec())])
            .map(|(dump, palette)| (dump.pixels.clone(), palette))
            .collect();
        assert_eq!(decoded, expected);
    }
}
