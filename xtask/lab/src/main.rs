//! The lab's command line, run by `cargo xtask lab` in release (timings of
//! an unoptimised build mean little): `lab [--quick] [--runs N] [--out DIR]
//! [--scene FILE [--scene-from TEXT]]`.

use std::path::PathBuf;

use clap::Parser;

/// Counts allocations, for the allocations per polygon of exact's paths.
#[global_allocator]
static ALLOCATOR: lab::heap::Counting = lab::heap::Counting;

/// Measures every fill method for speed and accuracy on one seeded corpus,
/// or on the polygons of a scene file.
#[derive(Parser, Debug)]
#[command(name = "lab")]
struct Cli {
    /// A small corpus and short timing, for CI; with --scene, the short
    /// timing alone.
    #[arg(long)]
    quick: bool,
    /// Runs of the whole timing, one after the other; with 2 or more the
    /// report says how far they disagree.
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u16).range(1..))]
    runs: u16,
    /// Where results.json, report.md and the charts go [default:
    /// target/lab, or target/lab-scene with --scene].
    #[arg(long)]
    out: Option<PathBuf>,
    /// Measure the polygons of this scene file instead of the corpus, in
    /// families by class.
    #[arg(long, value_name = "FILE")]
    scene: Option<PathBuf>,
    /// What the report says the scene came from [default: FILE].
    #[arg(long, value_name = "TEXT", requires = "scene")]
    scene_from: Option<String>,
}

fn main() -> anyhow::Result<()> {
    let cli = Cli::parse();
    let shapes = match cli.scene {
        Some(path) => lab::Shapes::Scene(lab::UserScene::read(&path, cli.scene_from)?),
        None => lab::Shapes::Corpus,
    };
    let out_dir = cli.out.unwrap_or_else(|| PathBuf::from(lab::default_out_dir(&shapes)));
    lab::run(&lab::LabOptions { quick: cli.quick, runs: usize::from(cli.runs), out_dir, shapes })
}
