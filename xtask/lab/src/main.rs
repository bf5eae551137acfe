//! The lab's command line, run by `cargo xtask lab` in release (timings of
//! an unoptimised build mean little): `lab [--quick] [--runs N] [--out DIR]`.

use std::path::PathBuf;

use clap::Parser;

/// Counts allocations, for the allocations per polygon of exact's paths.
#[global_allocator]
static ALLOCATOR: lab::heap::Counting = lab::heap::Counting;

/// Measures every fill method for speed and accuracy on one seeded corpus.
#[derive(Parser, Debug)]
#[command(name = "lab")]
struct Cli {
    /// A small corpus and short timing, for CI.
    #[arg(long)]
    quick: bool,
    /// Runs of the whole timing, one after the other; with 2 or more the
    /// report says how far they disagree.
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u16).range(1..))]
    runs: u16,
    /// Where results.json, report.md and the charts go.
    #[arg(long, default_value = "target/lab")]
    out: PathBuf,
}

fn main() -> anyhow::Result<()> {
    let cli = Cli::parse();
    lab::run(&lab::LabOptions { quick: cli.quick, runs: usize::from(cli.runs), out_dir: cli.out })
}
