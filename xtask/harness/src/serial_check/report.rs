//! The check's findings as `report.md`, for a person, and `report.json`,
//! for a program.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use protocol::LineLosses;
use serde_json::{json, Value};

use super::CheckReport;
use crate::client::{transfer_time, TroubleKind, BAUD};

/// Writes `report.md` and `report.json` into `dir` (made if missing) and
/// returns their paths.
pub fn write_reports(report: &CheckReport, dir: &Path) -> Result<(PathBuf, PathBuf)> {
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let (md_path, json_path) = (dir.join("report.md"), dir.join("report.json"));
    std::fs::write(&md_path, markdown(report)).with_context(|| format!("cannot write {}", md_path.display()))?;
    let json = serde_json::to_string_pretty(&to_json(report))? + "\n";
    std::fs::write(&json_path, json).with_context(|| format!("cannot write {}", json_path.display()))?;
    Ok((md_path, json_path))
}

/// One line saying how the pictures came out.
fn verdict(report: &CheckReport) -> String {
    match report.differing().count() {
        0 => format!(
            "All {} pictures equal the host render, pixel for pixel and palette entry for entry.",
            report.pictures.len()
        ),
        differing => format!("{differing} of {} pictures differ from the host render.", report.pictures.len()),
    }
}

/// How long the bytes that crossed the line take at [`BAUD`] 8N1: the
/// kernel's replies, far the larger direction (the commands go the other
/// way at the same time).
fn line_seconds(report: &CheckReport) -> f64 {
    transfer_time(report.bytes_received.max(report.stats.bytes_sent), BAUD).as_secs_f64()
}

fn markdown(report: &CheckReport) -> String {
    let mut text = String::new();
    // Writing to a `String` cannot fail.
    let _ = writeln!(text, "# polylab check on {}\n", report.device);
    let _ = writeln!(text, "{}\n", verdict(report));
    let _ = writeln!(
        text,
        "The check took {:.1} s: {} command lines sent ({} bytes), {} bytes received. At {BAUD} baud 8N1 those \
         bytes take {:.1} s on the wire.\n",
        report.elapsed.as_secs_f64(),
        report.stats.commands,
        report.stats.bytes_sent,
        report.bytes_received,
        line_seconds(report)
    );
    let _ = writeln!(text, "## The machine\n");
    let how = if report.ready_at_boot { "sent at boot" } else { "asked for with `READY`" };
    let _ = writeln!(text, "`READY` ({how}):\n\n```text\n{}\n```\n", report.ready);
    let _ = writeln!(text, "Time-stamp counter: `{}`.\n", report.tsc);
    let _ = writeln!(text, "## Pictures\n");
    let _ = writeln!(text, "Each `DUMP` (the frame read back and the DAC) against the host's render of the same scene with the same method.\n");
    let _ = writeln!(text, "| scene | method | differing pixels | differing palette entries |\n|---|---|---:|---:|");
    for picture in &report.pictures {
        let scene = match picture.frame {
            Some(frame) => format!("`{}` frame {frame}", picture.scene),
            None => format!("`{}`", picture.scene),
        };
        let _ = writeln!(
            text,
            "| {scene} | `{}` | {} | {} |",
            picture.method, picture.differing_pixels, picture.differing_palette_entries
        );
    }
    for diff in report.differing().filter_map(|picture| picture.diff.as_ref()) {
        let _ = writeln!(text, "\n- {diff}");
    }
    let (ok, vga) = &report.vgacheck;
    let _ = writeln!(text, "\n## VGACHECK\n\n{} `{vga}`\n", if *ok { "OK:" } else { "ERR:" });
    text.push_str(&report.bench.markdown(2));
    let _ = writeln!(text, "\n## The line\n");
    let errors = match report.line.errors {
        Some(e) => format!(", and {} framing errors, {} parity errors, {} breaks", e.framing, e.parity, e.breaks),
        None => String::new(),
    };
    let _ = writeln!(
        text,
        "What the kernel counted lost on the way in (the last `PING`): {} overruns, {} bytes dropped{errors}.\n",
        report.line.overruns, report.line.dropped
    );
    let _ = writeln!(
        text,
        "What the host met on the way (each step retried whole, at most {} times):\n",
        report.retries_allowed
    );
    let _ = writeln!(text, "| what | count |\n|---|---:|");
    let _ = writeln!(text, "| steps retried | {} |", report.stats.retries);
    for kind in TroubleKind::ALL {
        let _ = writeln!(text, "| {} | {} |", kind.describe(), report.stats.count(kind));
    }
    let _ = writeln!(text, "| late replies to earlier lines, skipped | {} |", report.stats.stale_replies);
    if !report.stats.log.is_empty() {
        let _ = writeln!(text, "\nAs they happened:\n");
        for entry in &report.stats.log {
            let _ = writeln!(text, "- {entry}");
        }
    }
    text
}

fn to_json(report: &CheckReport) -> Value {
    let pictures: Vec<Value> = report
        .pictures
        .iter()
        .map(|picture| {
            json!({"scene": picture.scene, "frame": picture.frame, "method": picture.method.name(),
                   "differing_pixels": picture.differing_pixels,
                   "differing_palette_entries": picture.differing_palette_entries})
        })
        .collect();
    let troubles: serde_json::Map<String, Value> =
        TroubleKind::ALL.iter().map(|&kind| (kind.name().to_string(), json!(report.stats.count(kind)))).collect();
    json!({
        "device": report.device,
        "ready": report.ready,
        "ready_at_boot": report.ready_at_boot,
        "pictures": pictures,
        "pictures_differing": report.differing().count(),
        "vgacheck": {"ok": report.vgacheck.0, "text": report.vgacheck.1},
        "bench": report.bench.cells_json(),
        "bench_repeats": report.bench.repeats,
        "bench_exact_against_fewest": report.bench.against_fewest_json(),
        "float_integer_ratio_listing_38_3": report.bench.float_integer_ratio(),
        "tsc_hz": report.tsc.hz,
        "tsc_source": report.tsc.source.name(),
        "retries": report.stats.retries,
        "retries_allowed": report.retries_allowed,
        "troubles": troubles,
        "stale_replies": report.stats.stale_replies,
        "line": line_json(&report.line),
        "commands_sent": report.stats.commands,
        "bytes_sent": report.stats.bytes_sent,
        "bytes_received": report.bytes_received,
        "seconds": report.elapsed.as_secs_f64(),
        "seconds_at_115200_baud": line_seconds(report),
    })
}

/// The kernel's losses as `report.json`'s `line`: `overruns` and
/// `dropped`, and the UART's error counts where the kernel reports them.
fn line_json(line: &LineLosses) -> Value {
    let mut json = json!({"overruns": line.overruns, "dropped": line.dropped});
    if let Some(errors) = line.errors {
        json["framing"] = errors.framing.into();
        json["parity"] = errors.parity.into();
        json["breaks"] = errors.breaks.into();
    }
    json
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::client::LineStats;
    use crate::serial_check::bench_table::{BenchTable, TickUnit};
    use crate::serial_check::Picture;
    use protocol::{ClockReadings, ClockSource, LineErrors, TscRate};
    use raster::MethodId;
    use std::time::Duration;

    fn report() -> CheckReport {
        let tsc = TscRate { hz: 1_000_000, source: ClockSource::Pit, readings: ClockReadings::default() };
        let picture = |scene: &str, frame, differing_pixels| Picture {
            scene: scene.to_string(),
            frame,
            method: MethodId::Exact,
            differing_pixels,
            differing_palette_entries: 0,
            diff: (differing_pixels > 0).then(|| "wrote a.png".to_string()),
        };
        let mut stats = LineStats { commands: 12, bytes_sent: 300, retries: 2, ..LineStats::default() };
        stats.troubles[TroubleKind::Stalled as usize] = 2;
        stats.log = vec!["`DUMP`: a reply stopped half way (a byte of it lost)".to_string(); 2];
        CheckReport {
            device: "/dev/ttyUSB0".to_string(),
            ready: "firmware=bios display=1234:1111 video=vga13h vga_mismatches=0 overruns=0 dropped=0".to_string(),
            ready_at_boot: false,
            pictures: vec![picture("abrash38-1", None, 0), picture("race", Some(0), 7)],
            vgacheck: (true, "vga: 0 mismatches".to_string()),
            bench: BenchTable {
                unit: TickUnit::Tsc(tsc),
                repeats: 3,
                scenes: vec!["abrash38-1".to_string()],
                methods: vec!["exact"],
                ticks: vec![vec![500]],
                refused: vec![vec![(0, None)]],
            },
            tsc,
            line: LineLosses { overruns: 1, dropped: 0, errors: Some(LineErrors { framing: 2, parity: 0, breaks: 1 }) },
            stats,
            retries_allowed: 5,
            bytes_received: 115_200,
            elapsed: Duration::from_secs(12),
        }
    }

    #[test]
    fn the_json_report_has_the_fields_a_program_reads() {
        let json = to_json(&report());
        assert_eq!(json["ready"], json!(report().ready));
        assert_eq!(
            json["pictures"][1],
            json!({"scene": "race", "frame": 0, "method": "exact", "differing_pixels": 7, "differing_palette_entries": 0})
        );
        assert_eq!(json["pictures_differing"], json!(1));
        assert_eq!(json["bench"][0]["ticks"], json!(500));
        assert_eq!(json["bench"][0]["microseconds"], json!(500.0));
        assert_eq!(json["tsc_hz"], json!(1_000_000));
        assert_eq!(json["retries"], json!(2));
        assert_eq!(json["troubles"]["stalled_reply"], json!(2));
        assert_eq!(json["line"], json!({"overruns": 1, "dropped": 0, "framing": 2, "parity": 0, "breaks": 1}));
        // 115,200 bytes of 10 bits at 115200 baud.
        assert_eq!(json["seconds_at_115200_baud"], json!(10.0));
    }

    #[test]
    fn the_markdown_report_tells_a_person_what_differs_and_what_was_retried() {
        let text = markdown(&report());
        assert!(text.starts_with("# polylab check on /dev/ttyUSB0\n\n1 of 2 pictures differ from the host render."));
        assert!(text.contains("| `race` frame 0 | `exact` | 7 | 0 |"), "{text}");
        assert!(text.contains("\n- wrote a.png\n"), "{text}");
        assert!(text.contains("## Kernel BENCH: TSC ticks on this machine"), "{text}");
        assert!(text.contains("| steps retried | 2 |"), "{text}");
        assert!(text.contains("| a reply stopped half way (a byte of it lost) | 2 |"), "{text}");
        assert!(
            text.contains("1 overruns, 0 bytes dropped, and 2 framing errors, 0 parity errors, 1 breaks"),
            "{text}"
        );
        assert!(text.contains("take 10.0 s on the wire"), "{text}");
    }
}
