//! The lab's command line, run by `cargo xtask lab` in release (timings of
//! an unoptimised build mean little): `lab [--quick] [--out DIR]`.

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
    /// Where results.json, report.md and the charts go.
    #[arg(long, default_value = "target/lab")]
    out: PathBuf,
}

fn main() -> anyhow::Result<()> {
    let cli = Cli::parse();
    lab::run(&lab::LabOptions { quick: cli.quick, out_dir: cli.out })
}
