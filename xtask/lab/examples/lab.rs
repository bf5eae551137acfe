//! Runs the lab without the xtask: `cargo run --release -p lab --example lab -- [--quick] [OUT_DIR]`.

fn main() -> anyhow::Result<()> {
    let mut options = lab::LabOptions::default();
    for arg in std::env::args().skip(1) {
        match arg.as_str() {
            "--quick" => options.quick = true,
            dir => options.out_dir = dir.into(),
        }
    }
    lab::run(&options)
}
