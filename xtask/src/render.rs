//! `cargo xtask render`: a scene drawn on the host.

use anyhow::Result;
use harness::render::{render as render_scene, scene_named_or_file};

use crate::opt::RenderOpt;

pub fn render(opt: &RenderOpt) -> Result<()> {
    let scene = scene_named_or_file(&opt.scene)?;
    let method = opt.method.unwrap_or(scene.method);
    render_scene(&scene, method.method()).write_png(&opt.out)?;
    println!("{}", opt.out.display());
    Ok(())
}
