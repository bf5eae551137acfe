//! `cargo xtask explore`: the explorer page, written and served.

use anyhow::Result;
use harness::explorer::{write_page, PageServer};
use harness::workspace;

use crate::opt::ExploreOpt;

pub fn explore(opt: &ExploreOpt) -> Result<()> {
    let dir = opt.out.clone().unwrap_or_else(|| workspace::target_dir().join("explorer"));
    write_page(&dir, opt.results.as_deref())?;
    if opt.out.is_some() {
        println!("{}", dir.display());
        return Ok(());
    }
    let server = PageServer::start(&dir)?;
    eprintln!("serving {} on 127.0.0.1 until stopped (Ctrl-C)", dir.display());
    println!("{}", server.url());
    server.serve_forever();
    Ok(())
}
