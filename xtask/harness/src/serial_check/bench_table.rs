//! The kernel's `BENCH` over every demo scene as one table: rdtsc ticks
//! per method and scene, the polygons each method declined, the Black
//! Book's float / integer ratio and `exact` against the fewest ticks of the
//! methods that draw a scene whole. What a tick is depends on where the
//! kernel ran ([`TickUnit`]): an emulated instruction under QEMU's
//! `-icount`, a TSC tick on a PC.

use std::fmt::Write as _;

use anyhow::{ensure, Context, Result};
use protocol::{TscRate, BENCH_UNIT_LINE};
use raster::{MethodId, Refusal};
use scenes::Scene;
use serde_json::{json, Value};

use crate::client::Console;

/// A scene `BENCH` times: a built-in page, by its name, or a scene of the
/// user's, uploaded first ([`Console::upload`]) and timed by the name it
/// was uploaded under.
#[derive(Clone, Copy, Debug)]
pub enum Benched<'a> {
    Page(&'static str),
    Uploaded(&'a Scene),
}

/// The pages of the Black Book's Listing 38.3.
pub const LISTING_38_3: [&str; 3] = ["abrash38-1", "abrash38-2", "abrash38-3"];
/// The float and the integer filler of chapters 38 and 39.
const FLOAT: &str = "abrash_float";
const INTEGER: &str = "abrash_int";
/// The Black Book's Table 39.1, Listing 38.3 drawn on a 386 without an
/// FPU: seconds with the float filler and with the integer one.
const BOOK_FLOAT_SECONDS: f64 = 6.64;
const BOOK_INTEGER_SECONDS: f64 = 0.60;

const EXACT: &str = "exact";

/// What one tick of the table is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TickUnit {
    /// QEMU with `-icount shift=0`: one tick per emulated instruction.
    EmulatedInstructions,
    /// A real machine's time-stamp counter, at the rate the kernel
    /// measured (`CLOCK`).
    Tsc(TscRate),
}

impl TickUnit {
    /// The table's title.
    fn title(self) -> &'static str {
        match self {
            TickUnit::EmulatedInstructions => {
                "Kernel BENCH: rdtsc ticks under QEMU -icount, one per emulated instruction"
            }
            TickUnit::Tsc(_) => "Kernel BENCH: TSC ticks on this machine",
        }
    }

    /// What the numbers are and are not.
    fn caption(self) -> String {
        match self {
            TickUnit::EmulatedInstructions => "Median rdtsc ticks for the kernel to draw each whole scene once onto \
                the mode-13h screen, measured in QEMU with -icount shift=0, where rdtsc advances one tick per \
                emulated instruction: instructions, not cycles, the same in every run of the same image whatever \
                the host's load. Every instruction weighs the same, so they cannot see what makes one cost more \
                than another on a real CPU: latencies, memory and bus traffic (video memory included), cache \
                misses. Not comparable with the host lab's nanoseconds (target/lab/report.md)."
                .to_string(),
            TickUnit::Tsc(rate) => format!(
                "Median time-stamp counter ticks for the kernel to draw each whole scene once onto the screen, \
                 measured by the kernel with rdtsc on the machine it runs on: on a PC the CPU's real cost, video \
                 memory and caches included (under an emulator, the emulator's clock). The TSC runs at {:.3} MHz ({}); microseconds are ticks over that rate. On CPUs \
                 with an invariant TSC a tick is a fixed slice of time, not a core clock cycle.",
                rate.hz as f64 / 1e6,
                match rate.source {
                    protocol::ClockSource::Pit => "measured by the kernel against the PIT at boot",
                    protocol::ClockSource::PmTimer => "measured by the kernel against the ACPI PM timer at boot",
                    protocol::ClockSource::Hpet => "measured by the kernel against the HPET at boot",
                    protocol::ClockSource::Cpuid => "as the CPU states it in CPUID",
                    protocol::ClockSource::Assumed => "ASSUMED: nothing measured it, so the microseconds are not real",
                }
            ),
        }
    }

    /// What "fewest" counts.
    fn counted(self) -> &'static str {
        match self {
            TickUnit::EmulatedInstructions => "instructions",
            TickUnit::Tsc(_) => "ticks",
        }
    }
}

/// Ticks per method (rows, `MethodId::ALL` order) and scene (columns), and
/// the polygons each declined with the first one's reason.
#[derive(Clone, Debug, PartialEq)]
pub struct BenchTable {
    pub unit: TickUnit,
    pub repeats: u8,
    /// The scenes' names: a page's, or the name a scene was uploaded under.
    pub scenes: Vec<String>,
    pub methods: Vec<&'static str>,
    pub ticks: Vec<Vec<u64>>,
    pub refused: Vec<Vec<(usize, Option<Refusal>)>>,
}

impl BenchTable {
    /// Has the kernel behind `console` run `BENCH SCENE REPEATS` for each of
    /// `scenes` (an uploaded one uploaded just before), each a step of its
    /// own (retried if the console retries), calling `progress` with each
    /// scene before it is asked.
    pub fn measure(
        console: &mut Console,
        unit: TickUnit,
        scenes: &[Benched],
        repeats: u8,
        mut progress: impl FnMut(&str, &Console),
    ) -> Result<Self> {
        let methods: Vec<&str> = MethodId::ALL.map(MethodId::name).to_vec();
        let mut table = BenchTable {
            unit,
            repeats,
            scenes: Vec::with_capacity(scenes.len()),
            methods: methods.clone(),
            ticks: vec![Vec::new(); methods.len()],
            refused: vec![Vec::new(); methods.len()],
        };
        for benched in scenes {
            let scene = match benched {
                Benched::Page(name) => name.to_string(),
                Benched::Uploaded(scene) => {
                    progress(&format!("UPLOAD {}", scene.name), console);
                    console.upload(scene)?.name
                }
            };
            progress(&format!("BENCH {scene} {repeats}"), console);
            let rows = console.retrying(|console| console.bench(&scene, repeats))?;
            let listed: Vec<MethodId> = rows.iter().map(|row| row.method).collect();
            ensure!(listed == MethodId::ALL, "BENCH {scene} listed methods {listed:?}, expected {:?}", MethodId::ALL);
            for ((ticks, refused), row) in table.ticks.iter_mut().zip(&mut table.refused).zip(rows) {
                ticks.push(row.cycles);
                refused.push((row.refused, row.refusal));
            }
            table.scenes.push(scene);
        }
        Ok(table)
    }

    /// The ticks of `method` summed over `scenes`; `None` if one is missing.
    fn total(&self, method: &str, scenes: &[&str]) -> Option<u64> {
        let row = &self.ticks[self.methods.iter().position(|m| *m == method)?];
        scenes.iter().map(|scene| Some(row[self.scenes.iter().position(|s| s == scene)?])).sum()
    }

    /// The float filler's ticks over the integer filler's on the Listing
    /// 38.3 pages together, the measure of the book's Table 39.1.
    pub fn float_integer_ratio(&self) -> Option<f64> {
        let (float, integer) = (self.total(FLOAT, &LISTING_38_3)?, self.total(INTEGER, &LISTING_38_3)?);
        (integer > 0).then(|| float as f64 / integer as f64)
    }

    /// On scene `column`: the method that draws it whole (declining no
    /// polygon) with the fewest ticks, those ticks, and `exact`'s over them.
    fn exact_against_fewest(&self, column: usize) -> Option<(&'static str, u64, f64)> {
        let exact = self.ticks[self.methods.iter().position(|m| *m == EXACT)?][column];
        let (method, fewest) = (0..self.methods.len())
            .filter(|&m| self.refused[m][column].0 == 0)
            .map(|m| (self.methods[m], self.ticks[m][column]))
            .min_by_key(|&(_, ticks)| ticks)?;
        (fewest > 0).then(|| (method, fewest, exact as f64 / fewest as f64))
    }

    /// Microseconds for `ticks`, if a tick is a known slice of time.
    pub fn micros(&self, ticks: u64) -> Option<f64> {
        match self.unit {
            TickUnit::Tsc(rate) if rate.hz > 0 => Some(ticks as f64 * 1e6 / rate.hz as f64),
            _ => None,
        }
    }

    /// The whole table as Markdown, its title a heading of `level`.
    pub fn markdown(&self, level: usize) -> String {
        let mut text = String::new();
        // Writing to a `String` cannot fail.
        let _ = writeln!(text, "{} {}\n", "#".repeat(level), self.unit.title());
        let _ = writeln!(text, "{} Median of {} draws per cell.\n", self.unit.caption(), self.repeats);
        self.grid(&mut text, |ticks| ticks.to_string());
        if self.micros(0).is_some() {
            let _ = writeln!(text, "\nThe same in microseconds:\n");
            self.grid(&mut text, |ticks| format!("{:.1}", self.micros(ticks).unwrap_or_default()));
        }
        self.refusals(&mut text);
        self.against_fewest(&mut text);
        if let Some(ratio) = self.float_integer_ratio() {
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

    /// A method-by-scene table of `cell(ticks)`.
    fn grid(&self, text: &mut String, cell: impl Fn(u64) -> String) {
        let _ = writeln!(text, "| method | {} |", self.scenes.join(" | "));
        let _ = writeln!(text, "|---|{}", "---:|".repeat(self.scenes.len()));
        for (method, row) in self.methods.iter().zip(&self.ticks) {
            let cells: Vec<String> = row.iter().map(|&ticks| cell(ticks)).collect();
            let _ = writeln!(text, "| `{method}` | {} |", cells.join(" | "));
        }
    }

    /// Which methods declined which polygons, scene by scene.
    fn refusals(&self, text: &mut String) {
        let _ =
            writeln!(text, "\nDeclined polygons (each draws nothing for them; the others it draws, right or wrong):\n");
        let mut any = false;
        for (column, scene) in self.scenes.iter().enumerate() {
            let declined: Vec<String> = self
                .methods
                .iter()
                .zip(&self.refused)
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

    /// `exact` against the fewest ticks of a method drawing each scene
    /// whole (a ratio, held to no mark: the fewest is often a filler that
    /// draws the scene wrong, docs/lab.md#in-the-kernel).
    fn against_fewest(&self, text: &mut String) {
        let counted = self.unit.counted();
        let _ = writeln!(
            text,
            "\n`{EXACT}` against the fewest {counted} of any method that draws the scene without declining a \
             polygon:\n\n| scene | fewest | `{EXACT}` / fewest |\n|---|---|---:|"
        );
        for (column, scene) in self.scenes.iter().enumerate() {
            if let Some((method, fewest, ratio)) = self.exact_against_fewest(column) {
                let _ = writeln!(text, "| {scene} | `{method}` {fewest} | {ratio:.2} |");
            }
        }
    }

    /// Per scene and method: the ticks (and microseconds, on a real
    /// machine), the polygons declined and the first one's reason.
    pub fn cells_json(&self) -> Vec<Value> {
        self.methods
            .iter()
            .zip(self.ticks.iter().zip(&self.refused))
            .flat_map(|(method, (ticks, refused))| {
                let cells = self.scenes.iter().zip(ticks.iter().zip(refused));
                cells.map(move |(scene, (&ticks, (count, refusal)))| {
                    let mut cell = json!({"scene": scene, "method": method, "ticks": ticks, "refused": count,
                                          "refusal": refusal.map(Refusal::name)});
                    if let Some(micros) = self.micros(ticks) {
                        cell["microseconds"] = json!(micros);
                    }
                    cell
                })
            })
            .collect()
    }

    /// `exact` against the fewest, per scene.
    pub fn against_fewest_json(&self) -> Vec<Value> {
        (0..self.scenes.len())
            .filter_map(|column| {
                let (method, fewest, ratio) = self.exact_against_fewest(column)?;
                Some(json!({"scene": self.scenes[column], "fewest": method, "fewest_ticks": fewest,
                            "exact_over_fewest": ratio}))
            })
            .collect()
    }

    /// The whole table as JSON.
    pub fn json(&self) -> Value {
        let unit = match self.unit {
            TickUnit::EmulatedInstructions => {
                "rdtsc ticks per whole-scene draw under QEMU -icount shift=0: emulated instructions".to_string()
            }
            TickUnit::Tsc(rate) => {
                format!("TSC ticks per whole-scene draw on the machine itself, {} per second", rate.hz)
            }
        };
        json!({
            "unit": unit,
            "tsc_hz": match self.unit { TickUnit::Tsc(rate) => Some(rate.hz), TickUnit::EmulatedInstructions => None },
            "kernel_unit_line": BENCH_UNIT_LINE,
            "note": self.unit.caption(),
            "repeats": self.repeats,
            "float_integer_ratio_listing_38_3": self.float_integer_ratio(),
            "exact_against_fewest_whole": self.against_fewest_json(),
            "results": self.cells_json(),
        })
    }

    /// The table [`BenchTable::json`] wrote under QEMU (kernel_bench.json),
    /// read back: its cells give the scenes and methods in their order, the
    /// ticks and the polygons declined. A PC's table is not read back (the
    /// JSON keeps its TSC rate, not how the kernel came by it).
    pub fn from_json(json: &Value) -> Result<Self> {
        ensure!(json["tsc_hz"].is_null(), "a table of a PC's TSC ticks is not read back");
        let repeats = json["repeats"].as_u64().and_then(|r| u8::try_from(r).ok()).context("no repeats")?;
        let cells = json["results"].as_array().context("no results")?;
        let (mut scenes, mut methods) = (Vec::<String>::new(), Vec::<&'static str>::new());
        let (mut ticks, mut refused) = (Vec::<Vec<u64>>::new(), Vec::<Vec<(usize, Option<Refusal>)>>::new());
        for cell in cells {
            let scene = cell["scene"].as_str().context("a cell without a scene")?;
            let method = cell["method"].as_str().context("a cell without a method")?;
            let method = method.parse::<MethodId>().with_context(|| format!("`{method}` is no method"))?.name();
            if methods.last() != Some(&method) {
                methods.push(method);
                ticks.push(Vec::new());
                refused.push(Vec::new());
            }
            if methods.len() == 1 {
                scenes.push(scene.to_string());
            }
            let column = ticks.last().map_or(0, Vec::len);
            ensure!(scenes.get(column).is_some_and(|s| s == scene), "`{method}`'s cells are not in the scenes' order");
            let refusal = match cell["refusal"].as_str() {
                Some(name) => Some(Refusal::from_name(name).with_context(|| format!("`{name}` is no refusal"))?),
                None => None,
            };
            let declined = cell["refused"].as_u64().context("a cell without its declined count")? as usize;
            ticks.last_mut().expect("a row was pushed").push(cell["ticks"].as_u64().context("a cell without ticks")?);
            refused.last_mut().expect("a row was pushed").push((declined, refusal));
        }
        ensure!(ticks.iter().all(|row| row.len() == scenes.len()), "a method lacks a scene");
        Ok(Self { unit: TickUnit::EmulatedInstructions, repeats, scenes, methods, ticks, refused })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use protocol::{ClockReadings, ClockSource};

    fn table(unit: TickUnit) -> BenchTable {
        BenchTable {
            unit,
            repeats: 3,
            scenes: vec!["a".to_string(), "b".to_string()],
            methods: vec!["m1", "m2"],
            ticks: vec![vec![1, 2], vec![3, 4_000_000]],
            refused: vec![vec![(0, None); 2]; 2],
        }
    }

    #[test]
    fn the_markdown_table_says_what_its_numbers_are() {
        let text = table(TickUnit::EmulatedInstructions).markdown(1);
        assert!(text.starts_with("# Kernel BENCH: rdtsc ticks under QEMU -icount"), "{text}");
        assert!(text.contains("emulated instruction"), "{text}");
        assert!(text.contains("Not comparable"), "{text}");
        assert!(!text.contains("microseconds"), "{text}");
        assert!(!text.contains("Listing 38.3 pages"), "no ratio without the pages: {text}");
        assert!(
            text.contains("| method | a | b |\n|---|---:|---:|\n| `m1` | 1 | 2 |\n| `m2` | 3 | 4000000 |\n"),
            "{text}"
        );
        let json = table(TickUnit::EmulatedInstructions).json();
        assert_eq!(
            json["results"][1],
            json!({"scene": "b", "method": "m1", "ticks": 2, "refused": 0, "refusal": null})
        );
        assert_eq!(json["tsc_hz"], Value::Null);
    }

    #[test]
    fn on_a_real_machine_the_ticks_are_tsc_ticks_also_given_in_microseconds() {
        let unit =
            TickUnit::Tsc(TscRate { hz: 2_000_000_000, source: ClockSource::Pit, readings: ClockReadings::default() });
        let text = table(unit).markdown(2);
        assert!(text.starts_with("## Kernel BENCH: TSC ticks on this machine"), "{text}");
        assert!(text.contains("The TSC runs at 2000.000 MHz (measured by the kernel against the PIT at boot)"));
        assert!(text.contains("The same in microseconds:\n\n| method | a | b |"), "{text}");
        assert!(text.contains("| `m2` | 0.0 | 2000.0 |"), "{text}");
        assert!(text.contains("fewest ticks"), "{text}");
        let json = table(unit).json();
        assert_eq!(json["tsc_hz"], json!(2_000_000_000u64));
        assert_eq!(json["results"][3]["microseconds"], json!(2000.0));
        let assumed =
            TickUnit::Tsc(TscRate { hz: 1, source: ClockSource::Assumed, readings: ClockReadings::default() });
        assert!(table(assumed).markdown(1).contains("ASSUMED"));
    }

    #[test]
    fn the_float_integer_ratio_sums_the_three_listing_38_3_pages() {
        let mut scenes = LISTING_38_3.map(String::from).to_vec();
        scenes.push("other".to_string());
        let table = BenchTable {
            unit: TickUnit::EmulatedInstructions,
            repeats: 3,
            scenes,
            methods: vec![FLOAT, "exact", INTEGER],
            ticks: vec![vec![10, 20, 30, 1000], vec![1, 1, 1, 1], vec![2, 4, 6, 1]],
            refused: vec![vec![(0, None); 4]; 3],
        };
        assert_eq!(table.float_integer_ratio(), Some(5.0));
        let text = table.markdown(1);
        assert!(
            text.contains(
                "`abrash_float` / `abrash_int` on the Listing 38.3 pages (abrash38-1, abrash38-2, abrash38-3) \
                 together: 5.00 (the Black Book's Table 39.1, a 386 without an FPU: 6.64 s / 0.60 s = 11.07)."
            ),
            "{text}"
        );
        assert_eq!(table.json()["float_integer_ratio_listing_38_3"], json!(5.0));
    }

    /// The fewest ticks are taken over the methods that declined nothing: one
    /// that declines half a scene is quick for nothing.
    #[test]
    fn exact_is_set_against_the_fewest_of_the_methods_drawing_the_scene_whole() {
        let table = BenchTable {
            unit: TickUnit::EmulatedInstructions,
            repeats: 1,
            scenes: vec!["a".to_string(), "b".to_string()],
            methods: vec!["quick", EXACT, "whole"],
            ticks: vec![vec![10, 10], vec![120, 130], vec![100, 100]],
            refused: vec![
                vec![(0, None), (2, Some(Refusal::MultipleContours))],
                vec![(0, None); 2],
                vec![(0, None); 2],
            ],
        };
        assert_eq!(table.exact_against_fewest(0), Some(("quick", 10, 12.0)));
        assert_eq!(table.exact_against_fewest(1), Some(("whole", 100, 1.3)));
        let text = table.markdown(1);
        assert!(text.contains("- b: `quick` 2 (several contours, method takes one)"), "{text}");
        assert!(text.contains("| b | `whole` 100 | 1.30 |\n"), "{text}");
        let json = table.json();
        assert_eq!(json["exact_against_fewest_whole"][1]["fewest"], json!("whole"));
        assert_eq!(json["results"][1]["refusal"], json!("multiple-contours"));
    }

    #[test]
    fn a_table_read_back_from_its_json_is_the_table() {
        let table = BenchTable {
            unit: TickUnit::EmulatedInstructions,
            repeats: 3,
            scenes: vec!["a".to_string(), "b".to_string()],
            methods: vec!["wgt", "exact"],
            ticks: vec![vec![1, 2], vec![3, 4]],
            refused: vec![vec![(0, None), (2, Some(Refusal::MultipleContours))], vec![(0, None); 2]],
        };
        assert_eq!(BenchTable::from_json(&table.json()).expect("it reads back"), table);
        let mut json = table.json();
        json["results"][1]["scene"] = json!("c");
        assert!(BenchTable::from_json(&json).is_err(), "a cell out of the scenes' order is refused");
        let rate = TscRate { hz: 1, source: ClockSource::Pit, readings: ClockReadings::default() };
        assert!(BenchTable::from_json(&BenchTable { unit: TickUnit::Tsc(rate), ..table }.json()).is_err());
    }

    /// docs/lab-results.md shows the kernel's counts as kbench wrote them
    /// in docs/kernel_bench.json: the table that file makes, word for word.
    #[test]
    fn docs_lab_results_md_holds_the_kernel_table_kernel_bench_json_makes() {
        let docs = crate::workspace::root().join("docs");
        let json = std::fs::read_to_string(docs.join("kernel_bench.json")).expect("docs/kernel_bench.json is there");
        let table = BenchTable::from_json(&serde_json::from_str(&json).expect("it is JSON")).expect("it reads back");
        let page = std::fs::read_to_string(docs.join("lab-results.md")).expect("docs/lab-results.md is there");
        let made = table.markdown(3);
        assert!(
            page.contains(&made),
            "docs/lab-results.md's kernel table differs from docs/kernel_bench.json's:\n{made}"
        );
    }
}
