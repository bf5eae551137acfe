//! `cargo xtask kbench`: has the kernel time every method on every demo
//! scene (or on the user's scene files, each uploaded whole) with `BENCH`
//! and writes the table (`harness::serial_check::bench_table`) as
//! kernel_bench.md and kernel_bench.json.
//!
//! Under QEMU (the default) the kernel boots under instruction counting:
//! the numbers are rdtsc ticks of QEMU's virtual clock, one per emulated
//! instruction, the same in every run, written apart from the host lab's
//! results and never compared with its nanoseconds. With `--serial DEVICE`
//! the kernel is the one on the PC at the other end of that line: the
//! numbers are that PC's TSC ticks, also given in microseconds from the
//! TSC rate the kernel measured (`CLOCK`), every `BENCH` retried if the
//! line damages it.

use std::fs;
use std::path::{absolute, Path};
use std::time::Duration;

use anyhow::{Context, Result};
use harness::cable::open_console;
use harness::serial_check::bench_table::{BenchTable, Benched, TickUnit};
use harness::{Console, Qemu, QemuOptions, TimeBase};
use scenes::builtin;

use crate::opt::KbenchOpt;

/// How long `--serial` waits for the kernel to answer at all.
const WAIT_FOR_KERNEL: Duration = Duration::from_secs(120);

pub fn kbench(opt: &KbenchOpt) -> Result<()> {
    let out = absolute(&opt.out).with_context(|| format!("bad output directory {}", opt.out.display()))?;
    let files = opt.files.read()?;
    let scenes = match files.is_empty() {
        true => builtin::ALL.map(|page| Benched::Page(page.name)).to_vec(),
        false => files.iter().map(|file| Benched::Uploaded(&file.scene)).collect(),
    };
    let table = match &opt.serial {
        Some(device) => measure_on_serial(device, opt.retries, opt.repeats, &scenes)?,
        None => measure_under_qemu(opt.repeats, &scenes)?,
    };
    let markdown = table.markdown(1);
    print!("{markdown}");
    fs::create_dir_all(&out).with_context(|| format!("cannot create {}", out.display()))?;
    let md_path = out.join("kernel_bench.md");
    let json_path = out.join("kernel_bench.json");
    fs::write(&md_path, &markdown).with_context(|| format!("cannot write {}", md_path.display()))?;
    let json = serde_json::to_string_pretty(&table.json())?;
    fs::write(&json_path, json + "\n").with_context(|| format!("cannot write {}", json_path.display()))?;
    println!("{}", md_path.display());
    println!("{}", json_path.display());
    Ok(())
}

fn say(what: &str, _: &Console) {
    eprintln!("xtask: {what}");
}

fn measure_under_qemu(repeats: u8, scenes: &[Benched]) -> Result<BenchTable> {
    let mut qemu = Qemu::boot(QemuOptions { clock: TimeBase::InstructionCount, ..QemuOptions::default() })?;
    let table = BenchTable::measure(&mut qemu.console, TickUnit::EmulatedInstructions, scenes, repeats, say)?;
    qemu.quit()?;
    Ok(table)
}

fn measure_on_serial(device: &Path, retries: u32, repeats: u8, scenes: &[Benched]) -> Result<BenchTable> {
    let mut console = open_console(device, retries)?;
    let (ready, _) = console.wait_for_kernel(WAIT_FOR_KERNEL, &device.display().to_string())?;
    eprintln!("xtask: the kernel on {}: {ready}", device.display());
    let rate = console.retrying(Console::tsc_rate)?;
    let table = BenchTable::measure(&mut console, TickUnit::Tsc(rate), scenes, repeats, say)?;
    let retried = console.line_stats().map_or(0, |stats| stats.retries);
    eprintln!("xtask: {retried} BENCH steps retried after the line damaged them");
    Ok(table)
}

#[cfg(test)]
mod tests {
    use super::kbench;
    use crate::opt::{parse_command, Action};
    use crate::source::svg_fixture;

    #[test]
    fn scene_files_and_svgs_are_read_and_refused_before_any_boot() {
        let svg = svg_fixture("holes.svg");
        let args = ["--svg", svg.to_str().unwrap(), "--svg", svg.to_str().unwrap(), "--tolerance", "0.5"];
        let Ok(Action::Kbench(opt)) = parse_command("kbench", &args) else { panic!() };
        let files = opt.files.read().unwrap();
        assert_eq!(files.len(), 2);
        assert_eq!(files[0].scene.name, "holes");
        let Ok(Action::Kbench(opt)) = parse_command("kbench", &["--palette", "vga"]) else { panic!() };
        let error = format!("{:#}", kbench(&opt).unwrap_err());
        assert_eq!(error, "--tolerance, --view-box and --palette go with --svg");
        let bad = svg_fixture("bad/text.svg");
        let Ok(Action::Kbench(opt)) = parse_command("kbench", &["--svg", bad.to_str().unwrap()]) else { panic!() };
        let error = format!("{:#}", kbench(&opt).unwrap_err());
        assert!(error.contains("bad/text.svg"), "{error}");
    }

    #[test]
    fn serial_takes_a_device_and_retries_a_count() {
        let Ok(Action::Kbench(opt)) = parse_command("kbench", &["--serial", "/dev/ttyUSB0", "--retries", "2"]) else {
            panic!()
        };
        assert_eq!((opt.serial.unwrap().to_str(), opt.retries), (Some("/dev/ttyUSB0"), 2));
        let Ok(Action::Kbench(opt)) = parse_command("kbench", &[]) else { panic!() };
        assert!(opt.serial.is_none());
    }
}
