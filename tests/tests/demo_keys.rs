//! The demo's keys (`docs/demo.md#the-show`), pressed on the PS/2 keyboard with
//! QMP `send-key` while the kernel plays the show: space and Enter move to
//! the next entry, a digit draws every entry with that method, 0 gives
//! each its own method again, Escape starts over. Each step is checked on
//! QEMU's screendump against the host render of the frame, less the
//! bottom label, which carries the cycles the kernel measured.
//!
//! Timing: the harness only polls the screen, for as long as a hang would
//! take ([`HANG`]); no deadline tells a late picture from a missing one.
//! Left to itself the demo turns a still page after 3 s, and that timer
//! could bring the next page as Space or Enter would: so the key test
//! first asks the demo to stay on its first page (`DEMO abrash38-1`, the
//! one line sent over serial), and only a key moves it on. Escape, the
//! last key, also lets the timer run again: its page is one the timer
//! could not bring from where the show was, and so is the page after it,
//! which a host too busy to look within the first page's 3 s sees instead.

use std::ops::Range;
use std::sync::{Mutex, MutexGuard, PoisonError};
use std::time::{Duration, Instant};

use anyhow::{bail, ensure, Context, Result};
use harness::checks::{as_on_screen, SCREEN_SCALE};
use harness::picture::compare::{compare_image_rows, images_match_in_rows};
use harness::render::render_show;
use harness::sources::show_entry;
use harness::{Image, Qemu, QemuOptions, Reply};
use protocol::{Command, DemoReply, ErrorReply};
use raster::MethodId;
use scenes::show::{ENTRIES_IN_ORDER, FRAMES_PER_SECOND, STILL_FRAMES};

/// The first row of the bottom label (method and cycles), whose glyphs
/// sit on rows 191 to 198 ringed by black from row 190: the cycles differ
/// from frame to frame, so the rows from here down are not compared. The
/// top label (the entry's name, and no frame counter on a still) is.
const BOTTOM_LABEL_ROW: u32 = 188;

/// The rows of QEMU's 640x400 screen that are compared: those above the
/// bottom label.
const COMPARED_ROWS: Range<u32> = 0..BOTTOM_LABEL_ROW * SCREEN_SCALE;

/// How long the screen may take to show what it must: only a demo that
/// hangs, or ignores what it was asked, takes this long.
const HANG: Duration = Duration::from_secs(30);

/// How long a still page stays up when the timer runs: the page's frames
/// at the show's rate.
fn page_lasts() -> Duration {
    Duration::from_millis(u64::from(STILL_FRAMES) * 1000 / u64::from(FRAMES_PER_SECOND))
}

/// The tests here watch a running demo, whose frames are timed by the
/// wall clock, so they take turns rather than run side by side: three
/// emulated machines on a two-core host would each run at a third of the
/// speed and show an animation's frames too briefly to be caught.
static ONE_DEMO_AT_A_TIME: Mutex<()> = Mutex::new(());

/// Waits for the other tests here to finish with their QEMU (a test that
/// failed while holding the turn still hands it on).
fn my_turn() -> MutexGuard<'static, ()> {
    ONE_DEMO_AT_A_TIME.lock().unwrap_or_else(PoisonError::into_inner)
}

/// Pause between screendumps while waiting for a key to take effect.
const POLL: Duration = Duration::from_millis(20);

/// One key and what the screen then shows.
struct Step {
    /// QEMU's qcode of the key; none for the screen the demo starts with.
    key: Option<&'static str>,
    /// The show entry on the screen.
    entry: &'static str,
    /// The digit whose method (`MethodId::ALL[digit - 1]`) draws every
    /// entry; none for each entry's own.
    digit: Option<usize>,
    /// Whether the timer runs from this step on, so that the next entry
    /// may be on the screen by the time the harness looks.
    timer_runs: bool,
}

impl Step {
    fn describe(&self) -> String {
        self.key.map_or_else(|| "before any key".to_string(), |key| format!("after the key `{key}`"))
    }
}

/// The first page, then Space, a digit, Enter with the digit's method
/// kept, 0, the digit again, then Escape, which also drops the digit's
/// method (and the stay). Every step's picture differs from the one
/// before, so an ignored key shows. Digit 5 (`lamothe`) because
/// `abrash_int` (2) and `abrash_aet` (3) draw these pages exactly as their
/// own `abrash_float` does.
const STEPS: &[Step] = &[
    Step { key: None, entry: "abrash38-1", digit: None, timer_runs: false },
    Step { key: Some("spc"), entry: "abrash38-2", digit: None, timer_runs: false },
    Step { key: Some("5"), entry: "abrash38-2", digit: Some(5), timer_runs: false },
    Step { key: Some("ret"), entry: "abrash38-3", digit: Some(5), timer_runs: false },
    Step { key: Some("0"), entry: "abrash38-3", digit: None, timer_runs: false },
    Step { key: Some("5"), entry: "abrash38-3", digit: Some(5), timer_runs: false },
    Step { key: Some("esc"), entry: "abrash38-1", digit: None, timer_runs: true },
];

/// What the screen shows at `step`: frame 0 of its entry drawn and
/// labelled by the host (with 0 cycles: the bottom label is not compared),
/// in the show's palette, as QEMU displays it; and a name for it.
fn expected_screen(step: &Step) -> Result<(String, Image)> {
    let entry = show_entry(step.entry)?;
    let method = match step.digit {
        Some(digit) => *MethodId::ALL.get(digit - 1).with_context(|| format!("no method for the digit {digit}"))?,
        None => entry.method_at(0),
    };
    let name = format!("{}.{method}", entry.name);
    Ok((name, as_on_screen(&render_show(entry, 0, method, 0))))
}

/// What the screen may show at `step`: its picture, and where the timer
/// runs, the next entry's with the same method if that is a still page.
fn acceptable_screens(step: &Step, picture: &Image) -> Result<Vec<Image>> {
    let mut screens = vec![picture.clone()];
    if step.timer_runs {
        let index = ENTRIES_IN_ORDER.iter().position(|entry| entry.name == step.entry).context("no such entry")?;
        let next = &ENTRIES_IN_ORDER[(index + 1) % ENTRIES_IN_ORDER.len()];
        if !next.is_animated() {
            screens.push(expected_screen(&Step { entry: next.name, ..*step })?.1);
        }
    }
    Ok(screens)
}

/// Takes screendumps until one shows one of `expected` above the bottom
/// label, for at most [`HANG`], and returns which; otherwise fails with the
/// last dump written next to the first expected picture and their diff.
fn screen_shows_one_of(qemu: &mut Qemu, name: &str, expected: &[Image]) -> Result<usize> {
    let give_up = Instant::now() + HANG;
    loop {
        let screen = qemu.screendump()?;
        if let Some(shown) = expected.iter().position(|picture| images_match_in_rows(picture, &screen, COMPARED_ROWS)) {
            return Ok(shown);
        }
        if Instant::now() > give_up {
            compare_image_rows(name, &expected[0], &screen, COMPARED_ROWS)?;
            bail!("{name}: the screen matched only between dumps");
        }
        std::thread::sleep(POLL);
    }
}

/// [`screen_shows_one_of`] for one picture.
fn screen_shows(qemu: &mut Qemu, name: &str, expected: &Image) -> Result<()> {
    screen_shows_one_of(qemu, name, std::slice::from_ref(expected)).map(drop)
}

/// Checks one screendump, taken now, against `expected` above the bottom
/// label: for a picture that must still be there.
fn screen_still_shows(qemu: &mut Qemu, name: &str, expected: &Image) -> Result<()> {
    compare_image_rows(name, expected, &qemu.screendump()?, COMPARED_ROWS)
}

#[test]
fn space_enter_digits_and_escape_move_the_running_demo() -> Result<()> {
    let expected: Vec<(String, Image)> = STEPS.iter().map(expected_screen).collect::<Result<_>>()?;
    let acceptable: Vec<Vec<Image>> = STEPS
        .iter()
        .zip(&expected)
        .map(|(step, (_, picture))| acceptable_screens(step, picture))
        .collect::<Result<_>>()?;
    for (i, step) in STEPS.iter().enumerate().skip(1) {
        let ((before, was), name) = (&expected[i - 1], &expected[i].0);
        let key = step.key.unwrap_or("no key");
        ensure!(
            !acceptable[i].iter().any(|is| images_match_in_rows(was, is, COMPARED_ROWS)),
            "{name} looks like {before}: an ignored `{key}` would pass"
        );
    }
    let first = show_entry(STEPS[0].entry)?;
    ensure!(first.name == ENTRIES_IN_ORDER[0].name, "Escape starts the show over, at {}", ENTRIES_IN_ORDER[0].name);
    let _turn = my_turn();
    let mut qemu = Qemu::boot(QemuOptions::default())?;
    let answer = qemu.console.ok(&Command::Demo { entry: Some(first.name), method: None })?;
    let resumed = DemoReply { from: first.name, stay: true, method: None };
    ensure!(DemoReply::parse(&answer)? == resumed, "DEMO answered OK \"{answer}\"");
    for (i, (step, (name, _))) in STEPS.iter().zip(&expected).enumerate() {
        let name = format!("demo_keys.{i}.{name}");
        let pressed = Instant::now();
        if let Some(key) = step.key {
            qemu.send_key(key)?;
        }
        let shown = screen_shows_one_of(&mut qemu, &name, &acceptable[i])
            .with_context(|| format!("{}: the demo does not show {name}", step.describe()))?;
        let which = if shown == 0 { "" } else { " (the timer's next page: the host looked late)" };
        eprintln!("harness: {name} {}, shown within {} ms{which}", step.describe(), pressed.elapsed().as_millis());
    }
    Ok(())
}

/// How many different frames of an animation the harness must see to
/// judge that it plays forward.
const FRAMES_TO_SEE: usize = 4;

/// How many times the timer test goes back to `lamothe-rotate` (Escape,
/// then Space up to it) when a pass of it went by with fewer than
/// [`FRAMES_TO_SEE`] of its frames caught (a host too busy to take the
/// dumps while it played).
const VISITS: usize = 4;

/// With no key at all the timer turns the pages: the second page follows
/// the first by itself. Then, skipping to `lamothe-rotate` with Escape
/// and Space, the animation plays by itself: screendumps taken apart show
/// frames of it exactly as the host renders them (the top label names the
/// frame), each later than the one before. The timer moves on after one
/// pass of the animation, so a pass that went by with too few frames seen
/// is visited again, up to [`VISITS`] times.
#[test]
fn with_no_key_the_timer_turns_the_pages_and_animations_play_by_themselves() -> Result<()> {
    let (first, second) = (expected_screen(&STEPS[0])?, expected_screen(&Step { key: None, ..STEPS[1] })?);
    let rotate = show_entry("lamothe-rotate")?;
    let method = rotate.method_at(0);
    let frames: Vec<Image> = (0..rotate.frames).map(|f| as_on_screen(&render_show(rotate, f, method, 0))).collect();
    let skips = ENTRIES_IN_ORDER.iter().position(|entry| entry.name == rotate.name).context("no lamothe-rotate")?;
    let one_pass = Duration::from_millis(u64::from(rotate.demo_frames()) * 1000 / u64::from(FRAMES_PER_SECOND));

    let _turn = my_turn();
    let mut qemu = Qemu::boot(QemuOptions::default())?;
    // No key is pressed: only the timer can bring the second page.
    screen_shows(&mut qemu, "timer.0.abrash38-1", &first.1)?;
    screen_shows(&mut qemu, "timer.1.abrash38-2", &second.1)?;

    for visit in 1..=VISITS {
        qemu.send_key("esc")?;
        for _ in 0..skips {
            std::thread::sleep(Duration::from_millis(100));
            qemu.send_key("spc")?;
        }
        let shown = frames_seen(&mut qemu, &frames, Duration::from_secs(20), one_pass)?;
        let seen: Vec<usize> = shown.iter().map(|&(frame, _)| frame).collect();
        eprintln!("harness: lamothe-rotate, visit {visit} of {VISITS}: frames seen in turn: {seen:?}");
        if shown.len() >= FRAMES_TO_SEE {
            return moves_forward("lamothe-rotate", &shown, frames.len());
        }
    }
    bail!("lamothe-rotate: fewer than {FRAMES_TO_SEE} of its frames were seen in each of {VISITS} passes")
}

/// Takes screendumps until [`FRAMES_TO_SEE`] different frames of an animation
/// (`frames`, its host renders on QEMU's screen) have been seen: for at
/// most `arrives_within` until the first of them shows (a loaded machine
/// may take seconds to act on the keys that lead to it), then for at most
/// `then_for` from that first one. Each frame seen, with when its dump was
/// asked for.
fn frames_seen(
    qemu: &mut Qemu,
    frames: &[Image],
    arrives_within: Duration,
    then_for: Duration,
) -> Result<Vec<(usize, Instant)>> {
    let mut shown: Vec<(usize, Instant)> = Vec::new();
    let started = Instant::now();
    while shown.len() < FRAMES_TO_SEE {
        let watching = match shown.first() {
            None => started.elapsed() < arrives_within,
            Some(&(_, first)) => first.elapsed() < then_for,
        };
        if !watching {
            break;
        }
        let taken = Instant::now();
        let screen = qemu.screendump()?;
        if let Some(frame) = frames.iter().position(|frame| images_match_in_rows(frame, &screen, COMPARED_ROWS)) {
            if shown.last().map(|&(last, _)| last) != Some(frame) {
                shown.push((frame, taken));
            }
        }
        std::thread::sleep(Duration::from_millis(150));
    }
    Ok(shown)
}

/// Checks that at least [`FRAMES_TO_SEE`] frames were `shown` and that each is ahead of
/// the one before, modulo the loop of `loop_len` frames (it may wrap
/// between two dumps), by less than half the loop. Only dumps taken less
/// than half a loop's playing time apart are held to that: on a loaded
/// machine one dump and its matching can take seconds, and a frame seen
/// later than that may honestly be more than half a loop ahead.
fn moves_forward(name: &str, shown: &[(usize, Instant)], loop_len: usize) -> Result<()> {
    let seen: Vec<usize> = shown.iter().map(|&(frame, _)| frame).collect();
    ensure!(shown.len() >= FRAMES_TO_SEE, "{name} showed only the frames {seen:?}");
    let half_loop = Duration::from_millis(loop_len as u64 * 1000 / u64::from(FRAMES_PER_SECOND) / 2);
    let close: Vec<usize> = shown
        .windows(2)
        .filter(|w| w[1].1 - w[0].1 < half_loop)
        .map(|w| (w[1].0 + loop_len - w[0].0) % loop_len)
        .collect();
    ensure!(!close.is_empty(), "{name}: no two of the frames {seen:?} were seen within {half_loop:?} of each other");
    ensure!(close.iter().all(|&s| s > 0 && s < loop_len / 2), "{name}: frames {seen:?} do not move forward");
    Ok(())
}

/// `DEMO ENTRY METHOD` (what `cargo xtask run --scene --method` sends in a
/// window) plays the demo again from the host's command: a still page
/// drawn with the method named, staying past its 3 s, and an animation
/// that plays forward with it; the byte that ends the demo is the first of
/// the next command, which is answered.
#[test]
fn demo_resumes_the_show_on_the_named_entry_and_method_and_stays_there() -> Result<()> {
    let page = show_entry("abrash38-3")?;
    let still = as_on_screen(&render_show(page, 0, MethodId::Wgt, 0));
    let rotate = show_entry("lamothe-rotate")?;
    let frames: Vec<Image> =
        (0..rotate.frames).map(|f| as_on_screen(&render_show(rotate, f, MethodId::Exact, 0))).collect();

    let _turn = my_turn();
    let mut qemu = Qemu::boot(QemuOptions::default())?;
    let answer = qemu.console.ok(&Command::Demo { entry: Some(page.name), method: Some(MethodId::Wgt) })?;
    let expected = DemoReply { from: page.name, stay: true, method: Some(MethodId::Wgt) };
    ensure!(DemoReply::parse(&answer)? == expected, "DEMO answered OK \"{answer}\"");
    screen_shows(&mut qemu, "demo.abrash38-3.wgt", &still)?;
    // Past twice the page's 3 s, it is still there.
    std::thread::sleep(2 * page_lasts());
    screen_still_shows(&mut qemu, "demo.abrash38-3.wgt.stays", &still)?;

    let answer = qemu.console.ok(&Command::Demo { entry: Some(rotate.name), method: Some(MethodId::Exact) })?;
    let expected = DemoReply { from: rotate.name, stay: true, method: Some(MethodId::Exact) };
    ensure!(DemoReply::parse(&answer)? == expected, "DEMO answered OK \"{answer}\"");
    let shown = frames_seen(&mut qemu, &frames, Duration::from_secs(30), Duration::from_secs(30))?;
    moves_forward("lamothe-rotate with exact", &shown, frames.len())?;
    let losses = qemu.console.ping()?;
    ensure!(losses.none(), "PING after DEMO says the serial line lost bytes: {losses}");
    match qemu.console.request(&Command::Demo { entry: Some("no-such-entry"), method: None })? {
        Reply::Err(text) if ErrorReply::parse(&text)? == ErrorReply::UnknownShowEntry("no-such-entry") => Ok(()),
        other => bail!("DEMO of an unknown entry answered {other:?}, expected an ERR naming it"),
    }
}
