//! The lab's command line, run by `cargo xtask lab` in release (timings of
//! an unoptimised build mean little): `lab [--quick] [--launches N]
//! [--order-seed S] [--build NAME] [--out DIR] [--scene FILE [--scene-from
//! TEXT]]`. Each launch is this binary again, with `--launch K --plan FILE
//! --record FILE`; `lab --compare NAME=DIR ... --out DIR` sets the runs of
//! several builds side by side.

use std::path::PathBuf;

use clap::Parser;

/// Counts allocations, for the allocations per polygon of exact's paths.
#[global_allocator]
static ALLOCATOR: lab::Counting = lab::Counting;

/// Measures every fill method for speed and accuracy on one seeded corpus,
/// or on the polygons of a scene file.
#[derive(Parser, Debug)]
#[command(name = "lab")]
struct Cli {
    /// A small corpus and short timing, for CI; with --scene, the short
    /// timing alone.
    #[arg(long)]
    quick: bool,
    /// Launches of the whole timing, each a fresh process, one after the
    /// other; every ratio's interval is across them [default: 3, or 2 with
    /// --quick].
    #[arg(long, value_parser = clap::value_parser!(u16).range(1..))]
    launches: Option<u16>,
    /// The seed of the orders passes are timed in; launch K (from 0) draws
    /// from SEED + K.
    #[arg(long, value_name = "SEED", default_value_t = lab::ORDER_SEED)]
    order_seed: u64,
    /// What the binary was built as, for the report (`cargo xtask lab
    /// --build` names it: native, x86-64-v3).
    #[arg(long, value_name = "NAME", default_value = "as built")]
    build: String,
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
    /// Instead of measuring: set the runs of several builds side by side,
    /// each NAME=DIR (its results.json in DIR), in --out's report.md.
    #[arg(long, value_name = "NAME=DIR", value_parser = lab::BuildRun::parse, conflicts_with = "launch")]
    compare: Vec<lab::BuildRun>,
    /// Run as launch K (from 0) of a run: time as --plan says, write what
    /// was timed to --record.
    #[arg(long, value_name = "K", hide = true, requires_all = ["plan", "record"])]
    launch: Option<usize>,
    #[arg(long, value_name = "FILE", hide = true)]
    plan: Option<PathBuf>,
    #[arg(long, value_name = "FILE", hide = true)]
    record: Option<PathBuf>,
}

fn main() -> anyhow::Result<()> {
    let cli = Cli::parse();
    let shapes = match cli.scene {
        Some(path) => lab::Shapes::Scene(lab::UserScene::read(&path, cli.scene_from)?),
        None => lab::Shapes::Corpus,
    };
    let out_dir = cli.out.unwrap_or_else(|| PathBuf::from(lab::default_out_dir(&shapes)));
    if !cli.compare.is_empty() {
        return lab::compare(&cli.compare, &out_dir);
    }
    let options = lab::LabOptions {
        quick: cli.quick,
        launches: cli.launches.map_or(lab::default_launches(cli.quick), usize::from),
        order_seed: cli.order_seed,
        build: cli.build,
        out_dir,
        shapes,
    };
    match (cli.launch, cli.plan, cli.record) {
        (Some(launch), Some(plan), Some(record)) => lab::run_launch(&options, launch, &plan, &record),
        _ => lab::run(&options),
    }
}
