//! `cargo xtask kbench`: boots the kernel under instruction counting and
//! has it time every method on every demo scene with `BENCH`. The numbers
//! are rdtsc ticks of QEMU's virtual clock, one per emulated instruction:
//! the same in every run, written apart from the host lab's results and
//! never compared with its nanoseconds.

use std::fmt::Write as _;
use std::fs;
use std::path::absolute;

use anyhow::{ensure, Context, Result};
use harness::{Clock, Qemu, QemuOptions};
use protocol::BENCH_UNIT_LINE;
use raster::MethodId;
use scenes::builtin;
use serde_json::json;

use crate::opt::KbenchOpt;

/// The caption both outputs carry.
const CAPTION: &str = "Median rdtsc ticks for the kernel to draw each whole scene once onto the mode-13h \
screen, measured in QEMU with -icount shift=0, where rdtsc advances one tick per emulated instruction: \
instructions, not cycles, the same in every run of the same image whatever the host's load. Every instruction weighs the same, so they \
cannot see what makes one cost more than another on a real CPU: latencies, memory and bus traffic (video \
memory included), cache misses. Not comparable with the host lab's nanoseconds (target/lab/report.md).";

/// The pages of the Black Book's Listing 38.3.
const LISTING_38_3: [&str; 3] = ["abrash38-1", "abrash38-2", "abrash38-3"];
/// The float and the integer filler of chapters 38 and 39.
const FLOAT: &str = "abrash_float";
const INTEGER: &str = "abrash_int";
/// The Black Book's Table 39.1, Listing 38.3 drawn on a 386 without an
/// FPU: seconds with the float filler and with the integer one.
const BOOK_FLOAT_SECONDS: f64 = 6.64;
const BOOK_INTEGER_SECONDS: f64 = 0.60;

/// Ticks per method (rows, `methods::ALL` order) and scene (columns).
struct Table {
    scenes: Vec<&'static str>,
    methods: Vec<&'static str>,
    cycles: Vec<Vec<u64>>,
}

impl Table {
    /// The ticks of `method` summed over `scenes`; `None` if one is missing.
    fn total(&self, method: &str, scenes: &[&str]) -> Option<u64> {
        let row = &self.cycles[self.methods.iter().position(|m| *m == method)?];
        scenes.iter().map(|scene| Some(row[self.scenes.iter().position(|s| s == scene)?])).sum()
    }

    /// The float filler's ticks over the integer filler's on the Listing
    /// 38.3 pages together, the measure of the book's Table 39.1.
    fn float_integer_ratio(&self) -> Option<f64> {
        let (float, integer) = (self.total(FLOAT, &LISTING_38_3)?, self.total(INTEGER, &LISTING_38_3)?);
        (integer > 0).then(|| float as f64 / integer as f64)
    }
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
    let mut qemu = Qemu::boot(QemuOptions { clock: Clock::InstructionCount, ..QemuOptions::default() })?;
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
    let _ = writeln!(text, "# Kernel BENCH: rdtsc ticks under QEMU -icount, one per emulated instruction\n");
    let _ = writeln!(text, "{CAPTION} Median of {repeats} draws per cell.\n");
    let _ = writeln!(text, "| method | {} |", table.scenes.join(" | "));
    let _ = writeln!(text, "|---|{}", "---:|".repeat(table.scenes.len()));
    for (method, row) in table.methods.iter().zip(&table.cycles) {
        let cells: Vec<String> = row.iter().map(|count| count.to_string()).collect();
        let _ = writeln!(text, "| `{method}` | {} |", cells.join(" | "));
    }
    if let Some(ratio) = table.float_integer_ratio() {
        let _ = writeln!(
            text,
            "\n`{FLOAT}` / `{INTEGER}` on the Listing 38.3 pages ({}) together: {ratio:.2} \
             (the Black Book's Table 39.1, a 386 without an FPU: {BOOK_FLOAT_SECONDS:.2} s / \
             {BOOK_INTEGER_SECONDS:.2} s = {:.2}).",
            LISTING_38_3.join(", "),
            BOOK_FLOAT_SECONDS / BOOK_INTEGER_SECONDS
        );
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
        "unit": "rdtsc ticks per whole-scene draw under QEMU -icount shift=0: emulated instructions",
        "kernel_unit_line": BENCH_UNIT_LINE,
        "note": CAPTION,
        "repeats": repeats,
        "float_integer_ratio_listing_38_3": table.float_integer_ratio(),
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
        assert!(text.contains("-icount"), "{text}");
        assert!(text.contains("emulated instruction"), "{text}");
        assert!(text.contains("Not comparable"), "{text}");
        assert!(!text.contains("Listing 38.3 pages"), "no ratio without the pages: {text}");
        assert!(text.contains("| method | a | b |\n|---|---:|---:|\n| `m1` | 1 | 2 |\n| `m2` | 3 | 4 |\n"), "{text}");
        let json = to_json(&table, 3);
        assert_eq!(json["results"][1], json!({"scene": "b", "method": "m1", "cycles": 2}));
    }

    #[test]
    fn the_float_integer_ratio_sums_the_three_listing_38_3_pages() {
        let mut scenes = LISTING_38_3.to_vec();
        scenes.push("other");
        let table = Table {
            scenes,
            methods: vec![FLOAT, "exact", INTEGER],
            cycles: vec![vec![10, 20, 30, 1000], vec![1, 1, 1, 1], vec![2, 4, 6, 1]],
        };
        assert_eq!(table.float_integer_ratio(), Some(5.0));
        let text = markdown(&table, 3);
        assert!(
            text.contains(
                "`abrash_float` / `abrash_int` on the Listing 38.3 pages (abrash38-1, abrash38-2, abrash38-3) \
                 together: 5.00 (the Black Book's Table 39.1, a 386 without an FPU: 6.64 s / 0.60 s = 11.07)."
            ),
            "{text}"
        );
        assert_eq!(to_json(&table, 3)["float_integer_ratio_listing_38_3"], json!(5.0));
    }
}
