//! `cargo xtask kbench`: boots the kernel and has it time every method on
//! every demo scene with `BENCH`. The numbers are rdtsc cycles counted by
//! QEMU's TCG emulation: they are written apart from the host lab's
//! results and never compared with its nanoseconds.

use std::fmt::Write as _;
use std::fs;
use std::path::absolute;

use anyhow::{ensure, Context, Result};
use harness::{Qemu, QemuOptions};
use protocol::BENCH_UNIT_LINE;
use raster::MethodId;
use scenes::builtin;
use serde_json::json;

use crate::opt::KbenchOpt;

/// The caption both outputs carry.
const CAPTION: &str = "Median rdtsc cycles for the kernel to draw each whole scene once onto the \
mode-13h screen, measured inside QEMU under TCG emulation: these are emulated cycles, not comparable \
with the host lab's nanoseconds (target/lab/report.md).";

/// Cycles per method (rows, `methods::ALL` order) and scene (columns).
struct Table {
    scenes: Vec<&'static str>,
    methods: Vec<&'static str>,
    cycles: Vec<Vec<u64>>,
}

pub fn kbench(opt: &KbenchOpt) -> Result<()> {
    let out = absolute(&opt.out).with_context(|| format!("bad output directory {}", opt.out.display()))?;
    let table = measure(opt.repeats)?;
    let markdown = markdown(&table, opt.repeats);
    print!("{markdown}");
    fs::create_dir_all(&out).with_context(|| format!("cannot create {}", out.display()))?;
    let md_path = out.join("kernel_bench.md");
    let json_path = out.join("kernel_bench.json");
    fs::write(&md_path, &markdown).with_context(|| format!("cannot write {}", md_path.display()))?;
    let json = serde_json::to_string_pretty(&to_json(&table, opt.repeats))?;
    fs::write(&json_path, json + "\n").with_context(|| format!("cannot write {}", json_path.display()))?;
    println!("{}", md_path.display());
    println!("{}", json_path.display());
    Ok(())
}

fn measure(repeats: u8) -> Result<Table> {
    let methods: Vec<&str> = MethodId::ALL.map(MethodId::name).to_vec();
    let scenes: Vec<&str> = builtin::ALL.map(|page| page.name).to_vec();
    let mut cycles = vec![Vec::new(); methods.len()];
    let mut qemu = Qemu::boot(QemuOptions::default())?;
    for &scene in &scenes {
        eprintln!("xtask: BENCH {scene} {repeats}");
        let rows = qemu.console.bench(scene, repeats)?;
        let listed: Vec<MethodId> = rows.iter().map(|&(method, _)| method).collect();
        ensure!(listed == MethodId::ALL, "BENCH {scene} listed methods {listed:?}, expected {:?}", MethodId::ALL);
        for (column, (_, count)) in cycles.iter_mut().zip(rows) {
            column.push(count);
        }
    }
    qemu.quit()?;
    Ok(Table { scenes, methods, cycles })
}

fn markdown(table: &Table, repeats: u8) -> String {
    let mut text = String::new();
    // Writing to a `String` cannot fail.
    let _ = writeln!(text, "# Kernel BENCH: rdtsc cycles under QEMU TCG emulation\n");
    let _ = writeln!(text, "{CAPTION} Median of {repeats} draws per cell.\n");
    let _ = writeln!(text, "| method | {} |", table.scenes.join(" | "));
    let _ = writeln!(text, "|---|{}", "---:|".repeat(table.scenes.len()));
    for (method, row) in table.methods.iter().zip(&table.cycles) {
        let cells: Vec<String> = row.iter().map(|count| count.to_string()).collect();
        let _ = writeln!(text, "| `{method}` | {} |", cells.join(" | "));
    }
    text
}

fn to_json(table: &Table, repeats: u8) -> serde_json::Value {
    let rows: Vec<_> = table
        .methods
        .iter()
        .zip(&table.cycles)
        .flat_map(|(method, row)| {
            let cells = table.scenes.iter().zip(row);
            cells.map(move |(scene, cycles)| json!({"scene": scene, "method": method, "cycles": cycles}))
        })
        .collect();
    json!({
        "unit": "rdtsc cycles per whole-scene draw, QEMU TCG emulated",
        "kernel_unit_line": BENCH_UNIT_LINE,
        "note": CAPTION,
        "repeats": repeats,
        "results": rows,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_markdown_table_says_what_its_numbers_are() {
        let table = Table { scenes: vec!["a", "b"], methods: vec!["m1", "m2"], cycles: vec![vec![1, 2], vec![3, 4]] };
        let text = markdown(&table, 3);
        assert!(text.contains("QEMU TCG"), "{text}");
        assert!(text.contains("not comparable"), "{text}");
        assert!(text.contains("| method | a | b |\n|---|---:|---:|\n| `m1` | 1 | 2 |\n| `m2` | 3 | 4 |\n"), "{text}");
        let json = to_json(&table, 3);
        assert_eq!(json["results"][1], json!({"scene": "b", "method": "m1", "cycles": 2}));
    }
}
