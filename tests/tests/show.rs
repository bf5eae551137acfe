//! The show (`scenes::show`), drawn by the kernel with `SHOW` in QEMU:
//! every entry against the host render, labels and palette included; the
//! race's turns; every method on an animation; no allocation once an
//! animation runs with a method that allocates nothing itself; bad input.
//! Each test boots its own QEMU; every `SHOW` is followed by a 64 KB
//! `DUMP`, the bulk of the time.

use anyhow::{bail, ensure, Result};
use harness::checks::show_matches_host_render;
use harness::{Qemu, QemuOptions, Reply};
use protocol::{CommandError, ErrorReply, ShowReply};
use raster::{Heap, MethodId};
use scenes::show::{self, Entry, ENTRIES_IN_ORDER};

/// The frames checked of `entry`: its first, a third of the way, its last
/// (one frame for a still).
fn sampled_frames(entry: &Entry) -> Vec<u32> {
    let mut frames = vec![0, entry.frames / 3, entry.frames - 1];
    frames.dedup();
    frames
}

/// What is wrong with a reply to a `SHOW` with the entry's own method:
/// refused polygons or stray spans, or, once the entry's first frame has
/// been shown (`again`), any allocation by a method whose `MethodInfo::heap`
/// says it takes nothing for convex polygons (the show's own polygons all
/// are). The faithful ports that keep per-polygon tables in `Vec`s
/// (`Heap::EveryPolygon`) allocate on every frame, and say so. A page drawn
/// by every method in turn (`world`) is real art: a method that takes one
/// contour refuses its outlines with a hole, and none is convex, so only
/// `exact` refusing one and a stray span are problems there.
fn own_method_problems(reply: &ShowReply, again: bool) -> Vec<String> {
    let ShowReply { entry, frame, method, allocs, polygons, refused, strays, .. } = reply;
    let real_art = show::entry(entry).is_some_and(|entry| entry.is_animated() && entry.page().is_some());
    let mut problems = Vec::new();
    if (*refused != 0 && (!real_art || *method == MethodId::Exact)) || *strays != 0 {
        problems.push(format!("{entry} frame {frame} with its own {method}: refused={refused} strays={strays}"));
    }
    let allocating = method.method().info().heap == Heap::EveryPolygon;
    if again && !allocating && !real_art && *allocs != 0 {
        problems.push(format!(
            "{entry} frame {frame} with {method}, shown again: {allocs} allocations for {polygons} polygons"
        ));
    }
    problems
}

/// Fails listing every failure, so one does not hide the others.
fn none_failed(failures: Vec<String>) -> Result<()> {
    ensure!(failures.is_empty(), "{} failures:\n{}", failures.len(), failures.join("\n"));
    Ok(())
}

#[test]
fn every_entry_shows_what_the_host_renders_at_its_first_middle_and_last_frame() -> Result<()> {
    let mut qemu = Qemu::boot(QemuOptions::default())?;
    let mut failures = Vec::new();
    for entry in ENTRIES_IN_ORDER {
        for (shown_before, frame) in sampled_frames(entry).into_iter().enumerate() {
            match show_matches_host_render(&mut qemu.console, entry.name, frame, None) {
                // A still may allocate every time it is shown (it builds its
                // page); an animation only on its first frame.
                Ok((reply, _)) => failures.extend(own_method_problems(&reply, entry.is_animated() && shown_before > 0)),
                Err(error) => failures.push(format!("{error:#}")),
            }
        }
    }
    none_failed(failures)
}

#[test]
fn the_race_shows_each_method_from_the_first_frame_of_its_turn() -> Result<()> {
    let race = show::entry("race").expect("the show has a race");
    let turns: Vec<u32> =
        (0..race.frames).filter(|&frame| frame == 0 || race.method_at(frame) != race.method_at(frame - 1)).collect();
    ensure!(turns.len() >= MethodId::ALL.len(), "the race gives turns to {} methods", turns.len());
    let mut qemu = Qemu::boot(QemuOptions::default())?;
    let mut failures = Vec::new();
    for (shown_before, frame) in turns.into_iter().enumerate() {
        // The check also holds the reply's method to `method_at(frame)`.
        match show_matches_host_render(&mut qemu.console, race.name, frame, None) {
            Ok((reply, _)) => failures.extend(own_method_problems(&reply, shown_before > 0)),
            Err(error) => failures.push(format!("{error:#}")),
        }
    }
    none_failed(failures)
}

#[test]
fn an_animation_shows_what_the_host_renders_with_every_method_named() -> Result<()> {
    let entry = show::entry("lamothe-rotate").expect("the show has lamothe-rotate");
    let frame = entry.frames / 3;
    let mut qemu = Qemu::boot(QemuOptions::default())?;
    let failures = MethodId::ALL
        .into_iter()
        .filter_map(|method| show_matches_host_render(&mut qemu.console, entry.name, frame, Some(method)).err())
        .map(|error| format!("{error:#}"))
        .collect();
    none_failed(failures)
}

/// `exact` allocates nothing once an animation of the show's own (convex)
/// polygons runs. The control, in the same boot: the same frames shown
/// with each method that allocates for every polygon (`Heap::EveryPolygon`)
/// must report at least one allocation per polygon it drew, so a count
/// that never moves fails.
#[test]
fn every_animation_drawn_with_exact_allocates_nothing_after_its_first_frame() -> Result<()> {
    let allocating: Vec<MethodId> =
        MethodId::ALL.into_iter().filter(|method| method.method().info().heap == Heap::EveryPolygon).collect();
    ensure!(!allocating.is_empty(), "no method allocates for every polygon, so nothing shows the count moving");
    let mut qemu = Qemu::boot(QemuOptions::default())?;
    let mut failures = Vec::new();
    let animations = || ENTRIES_IN_ORDER.iter().filter(|entry| entry.is_animated() && entry.page().is_none());
    let frames = |entry: &Entry| [0, 1, entry.frames / 2, entry.frames - 1];
    for entry in animations() {
        for frame in frames(entry) {
            let reply = qemu.console.show(entry.name, frame, Some(MethodId::Exact))?;
            if frame > 0 && reply.allocs != 0 {
                failures.push(format!("{} frame {frame} with exact: {} allocations", entry.name, reply.allocs));
            }
        }
    }
    let mut controls = 0;
    for entry in animations() {
        for (frame, &method) in frames(entry).into_iter().flat_map(|frame| allocating.iter().map(move |m| (frame, m))) {
            let ShowReply { allocs, polygons, refused, .. } = qemu.console.show(entry.name, frame, Some(method))?;
            let drawn = polygons - refused;
            if allocs < drawn as u64 || drawn == 0 {
                failures.push(format!(
                    "control: {} frame {frame} with {method}, which allocates for every polygon: \
                     {allocs} allocations for {polygons} polygons ({refused} refused)",
                    entry.name
                ));
            }
            controls += 1;
        }
    }
    eprintln!("harness: {controls} control frames with {allocating:?} reported their allocations");
    none_failed(failures)
}

#[test]
fn kernel_lists_the_show_and_refuses_bad_show_commands_and_keeps_serving() -> Result<()> {
    let mut qemu = Qemu::boot(QemuOptions::default())?;
    let listing = qemu.console.list()?;
    let expected: Vec<(String, u32)> = ENTRIES_IN_ORDER.iter().map(|e| (e.name.to_string(), e.frames)).collect();
    ensure!(listing.shows == expected, "kernel lists the show {:?}, host has {expected:?}", listing.shows);
    for (line, expected) in [
        ("SHOW nope 0", ErrorReply::UnknownShowEntry("nope")),
        ("SHOW race 0 nomethod", ErrorReply::Command(CommandError::UnknownMethod("nomethod"))),
        ("SHOW race x", ErrorReply::Command(CommandError::BadArgument("x"))),
    ] {
        qemu.console.send_bytes(format!("{line}\n").as_bytes())?;
        match qemu.console.reply()? {
            Reply::Err(text) if ErrorReply::parse(&text)? == expected => {}
            other => bail!("`{line}` answered {other:?}, expected ERR {expected:?}"),
        }
    }
    let losses = qemu.console.ping()?;
    ensure!(losses.none(), "PING after bad SHOWs says the serial line lost bytes: {losses}");
    Ok(())
}
