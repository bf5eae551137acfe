//! `cargo xtask kbench`: boots the kernel under instruction counting and
//! has it time every method on every demo scene with `BENCH`. The numbers
//! are rdtsc ticks of QEMU's virtual clock, one per emulated instruction:
//! the same in every run, written apart from the host lab's results and
//! never compared with its nanoseconds. It says which methods declined
//! which polygons, and how `exact` stands against the fewest instructions
//! of the methods that draw each scene whole (without declining a
//! polygon, rightly or not).

use std::fmt::Write as _;
use std::fs;
use std::path::absolute;

use anyhow::{ensure, Context, Result};
use harness::{Clock, Qemu, QemuOptions};
use protocol::BENCH_UNIT_LINE;
use raster::{MethodId, Refusal};
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

/// `exact` may take this many times the instructions of the method that
/// draws a scene whole with the fewest (issue 19).
const EXACT_GOAL: f64 = 1.2;
const EXACT: &str = "exact";

/// Ticks per method (rows, `methods::ALL` order) and scene (columns), and
/// the polygons each declined with the first one's reason.
struct Table {
    scenes: Vec<&'static str>,
    methods: Vec<&'static str>,
    cycles: Vec<Vec<u64>>,
    refused: Vec<Vec<(usize, Option<Refusal>)>>,
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

    /// On scene `column`: the method that draws it whole (declining no
    /// polygon) with the fewest ticks, those ticks, and `exact`'s over them.
    fn exact_against_fewest(&self, column: usize) -> Option<(&'static str, u64, f64)> {
        let exact = self.cycles[self.methods.iter().position(|m| *m == EXACT)?][column];
        let (method, fewest) = (0..self.methods.len())
            .filter(|&m| self.refused[m][column].0 == 0)
            .map(|m| (self.methods[m], self.cycles[m][column]))
            .min_by_key(|&(_, cycles)| cycles)?;
        (fewest > 0).then(|| (method, fewest, exact as f64 / fewest as f64))
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
    let (mut cycles, mut refused) = (vec![Vec::new(); methods.len()], vec![Vec::new(); methods.len()]);
    let mut qemu = Qemu::boot(QemuOptions { clock: Clock::InstructionCount, ..QemuOptions::default() })?;
    for &scene in &scenes {
        eprintln!("xtask: BENCH {scene} {repeats}");
        let rows = qemu.console.bench(scene, repeats)?;
        let listed: Vec<MethodId> = rows.iter().map(|row| row.method).collect();
        ensure!(listed == MethodId::ALL, "BENCH {scene} listed methods {listed:?}, expected {:?}", MethodId::ALL);
        for ((cycles, refused), row) in cycles.iter_mut().zip(&mut refused).zip(rows) {
            cycles.push(row.cycles);
            refused.push((row.refused, row.refusal));
        }
    }
    qemu.quit()?;
    Ok(Table { scenes, methods, cycles, refused })
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
    refusals(&mut text, table);
    against_fewest(&mut text, table);
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

/// Which methods declined which polygons, scene by scene.
fn refusals(text: &mut String, table: &Table) {
    let _ = writeln!(text, "\nDeclined polygons (each draws nothing for them; the others it draws, right or wrong):\n");
    let mut any = false;
    for (column, scene) in table.scenes.iter().enumerate() {
        let declined: Vec<String> = table
            .methods
            .iter()
            .zip(&table.refused)
            .filter_map(|(method, row)| match row[column] {
                (0, _) => None,
                (count, refusal) => {
                    Some(format!("`{method}` {count} ({})", refusal.map_or("no reason given", Refusal::describe)))
                }
            })
            .collect();
        if !declined.is_empty() {
            any = true;
            let _ = writeln!(text, "- {scene}: {}", declined.join(", "));
        }
    }
    if !any {
        let _ = writeln!(text, "- none: every method drew every polygon of every scene");
    }
}

/// `exact` against the fewest instructions of a method drawing each scene
/// whole, and whether it keeps within [`EXACT_GOAL`] of them.
fn against_fewest(text: &mut String, table: &Table) {
    let _ = writeln!(
        text,
        "\n`{EXACT}` against the fewest instructions of any method that draws the scene without declining a \
         polygon (goal: at most {EXACT_GOAL}x):\n\n| scene | fewest | `{EXACT}` / fewest | within {EXACT_GOAL}x |\n|---|---|---:|---|"
    );
    for (column, scene) in table.scenes.iter().enumerate() {
        if let Some((method, fewest, ratio)) = table.exact_against_fewest(column) {
            let met = if ratio <= EXACT_GOAL { "yes" } else { "no" };
            let _ = writeln!(text, "| {scene} | `{method}` {fewest} | {ratio:.2} | {met} |");
        }
    }
}

fn to_json(table: &Table, repeats: u8) -> serde_json::Value {
    let rows: Vec<_> = table
        .methods
        .iter()
        .zip(table.cycles.iter().zip(&table.refused))
        .flat_map(|(method, (cycles, refused))| {
            let cells = table.scenes.iter().zip(cycles.iter().zip(refused));
            cells.map(move |(scene, (cycles, (count, refusal)))| {
                json!({"scene": scene, "method": method, "cycles": cycles, "refused": count,
                       "refusal": refusal.map(Refusal::name)})
            })
        })
        .collect();
    let against_fewest: Vec<_> = (0..table.scenes.len())
        .filter_map(|column| {
            let (method, fewest, ratio) = table.exact_against_fewest(column)?;
            Some(json!({"scene": table.scenes[column], "fewest": method, "fewest_cycles": fewest,
                        "exact_over_fewest": ratio, "within_goal": ratio <= EXACT_GOAL}))
        })
        .collect();
    json!({
        "unit": "rdtsc ticks per whole-scene draw under QEMU -icount shift=0: emulated instructions",
        "kernel_unit_line": BENCH_UNIT_LINE,
        "note": CAPTION,
        "repeats": repeats,
        "float_integer_ratio_listing_38_3": table.float_integer_ratio(),
        "exact_against_fewest_whole": against_fewest,
        "exact_goal": EXACT_GOAL,
        "results": rows,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_markdown_table_says_what_its_numbers_are() {
        let table = Table {
            scenes: vec!["a", "b"],
            methods: vec!["m1", "m2"],
            cycles: vec![vec![1, 2], vec![3, 4]],
            refused: vec![vec![(0, None); 2]; 2],
        };
        let text = markdown(&table, 3);
        assert!(text.contains("-icount"), "{text}");
        assert!(text.contains("emulated instruction"), "{text}");
        assert!(text.contains("Not comparable"), "{text}");
        assert!(!text.contains("Listing 38.3 pages"), "no ratio without the pages: {text}");
        assert!(text.contains("| method | a | b |\n|---|---:|---:|\n| `m1` | 1 | 2 |\n| `m2` | 3 | 4 |\n"), "{text}");
        let json = to_json(&table, 3);
        assert_eq!(
            json["results"][1],
            json!({"scene": "b", "method": "m1", "cycles": 2, "refused": 0, "refusal": null})
        );
    }

    #[test]
    fn the_float_integer_ratio_sums_the_three_listing_38_3_pages() {
        let mut scenes = LISTING_38_3.to_vec();
        scenes.push("other");
        let table = Table {
            scenes,
            methods: vec![FLOAT, "exact", INTEGER],
            cycles: vec![vec![10, 20, 30, 1000], vec![1, 1, 1, 1], vec![2, 4, 6, 1]],
            refused: vec![vec![(0, None); 4]; 3],
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

    /// The fewest instructions are taken over the methods that declined
    /// nothing: one that declines half a scene is quick for nothing.
    #[test]
    fn exact_is_held_to_the_fewest_of_the_methods_drawing_the_scene_whole() {
        let table = Table {
            scenes: vec!["a", "b"],
            methods: vec!["quick", EXACT, "whole"],
            cycles: vec![vec![10, 10], vec![120, 130], vec![100, 100]],
            refused: vec![
                vec![(0, None), (2, Some(Refusal::MultipleContours))],
                vec![(0, None); 2],
                vec![(0, None); 2],
            ],
        };
        assert_eq!(table.exact_against_fewest(0), Some(("quick", 10, 12.0)));
        assert_eq!(table.exact_against_fewest(1), Some(("whole", 100, 1.3)));
        let text = markdown(&table, 1);
        assert!(text.contains("- b: `quick` 2 (several contours, method takes one)"), "{text}");
        assert!(text.contains("| b | `whole` 100 | 1.30 | no |"), "{text}");
        let json = to_json(&table, 1);
        assert_eq!(json["exact_against_fewest_whole"][1]["fewest"], json!("whole"));
        assert_eq!(json["results"][1]["refusal"], json!("multiple-contours"));
    }
}
