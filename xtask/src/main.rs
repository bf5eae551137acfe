//! `cargo xtask`: the developer's hands (see `opt.rs` for the commands).
//! Building, booting and talking to the kernel live in the `harness`
//! library, shared with the tests.

mod dump;
mod fuzz;
mod kbench;
mod lab;
mod lint;
mod opt;
mod record;
mod render;
mod run;
mod soak;
mod test;

use anyhow::Result;
use boot_image::{build_image, build_image_signed_by, own_signing_key};
use clap::Parser;

use crate::opt::{Action, Cli};

fn main() -> Result<()> {
    match Cli::parse().action {
        Action::Run(opt) => run::run(&opt),
        Action::Image(opt) => {
            let image = match (&opt.key, &opt.cert) {
                (Some(key), Some(cert)) => build_image_signed_by(&own_signing_key(key, cert)?)?,
                _ => build_image()?,
            };
            // The path is the last line, for scripts: `dd if="$(cargo xtask image | tail -1)" ...`.
            println!("{}", image.display());
            Ok(())
        }
        Action::Dump(opt) => dump::dump(&opt),
        Action::Render(opt) => render::render(&opt),
        Action::Record(opt) => record::record(&opt),
        Action::Test(opt) => test::test(&opt),
        Action::Lab(opt) => lab::lab(&opt),
        Action::Lint => lint::lint(),
        Action::Kbench(opt) => kbench::kbench(&opt),
        Action::Explore(opt) => explorer_site::explore(opt.out.as_deref(), opt.results.as_deref()),
        Action::Fuzz(opt) => fuzz::fuzz(&opt),
        Action::Soak(opt) => soak::soak(&opt),
    }
}
