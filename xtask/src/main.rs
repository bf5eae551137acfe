//! `cargo xtask`: the developer's hands (see `opt.rs` for the commands).
//! Building, booting and talking to the kernel live in the `harness`
//! library, shared with the tests.

mod check;
mod convert;
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
mod source;
mod test;

use anyhow::Result;
use boot_image::secure_boot::{key, Enrollment};
use boot_image::{build_image_with, debian_packages, image_path, own_signing_key, users_signing_key};
use clap::Parser;

use crate::opt::{Action, Cli, EnrollOpt};

fn main() -> Result<()> {
    // The Secure Boot key's passphrase leaves the environment before any
    // thread or child starts: only the openssl that needs it gets it, on
    // a pipe (xtask/tests/passphrase.rs).
    let passphrase_in_environment = key::take_passphrase();
    match Cli::parse().action {
        Action::Run(opt) => run::run(&opt),
        Action::Image(opt) => {
            let passphrase = match (&opt.passphrase_file, passphrase_in_environment) {
                (Some(_), Some(_)) => {
                    anyhow::bail!("--passphrase-file and {} both give the passphrase: give one", key::PASSPHRASE_ENV)
                }
                (Some(file), None) => Some(key::passphrase_from_file(file)?),
                (None, given) => given,
            };
            let enrollment = match (opt.enroll, &opt.key, &opt.cert) {
                (EnrollOpt::Key, Some(key), Some(cert)) => Enrollment::Key(own_signing_key(key, cert, passphrase)?),
                (EnrollOpt::Key, _, _) => Enrollment::Key(users_signing_key(passphrase)?),
                (EnrollOpt::Hash, None, None) if opt.passphrase_file.is_none() => Enrollment::Hash,
                (EnrollOpt::Hash, _, _) => {
                    anyhow::bail!("--key, --cert and --passphrase-file sign the loader: add --enroll key")
                }
            };
            let image = build_image_with(&enrollment, &debian_packages()?, &image_path())?;
            // The path is the last line, for scripts: `dd if="$(cargo xtask image | tail -1)" ...`.
            println!("{}", image.display());
            Ok(())
        }
        Action::Dump(opt) => dump::dump(&opt),
        Action::Render(opt) => render::render(&opt),
        Action::Convert(opt) => convert::convert(&opt),
        Action::Record(opt) => record::record(&opt),
        Action::Test(opt) => test::test(&opt),
        Action::Lab(opt) => lab::lab(&opt),
        Action::Lint => lint::lint(),
        Action::Kbench(opt) => kbench::kbench(&opt),
        Action::Check(opt) => check::check(&opt),
        Action::Explore(opt) => {
            let scene = opt.drawing.optional_source()?.map(|source| scenes::file::write(&source.scene()));
            explorer_site::explore(opt.out.as_deref(), opt.results.as_deref(), scene.as_deref())
        }
        Action::Fuzz(opt) => fuzz::fuzz(&opt),
        Action::Soak(opt) => soak::soak(&opt),
    }
}
