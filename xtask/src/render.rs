//! `cargo xtask render`: a scene drawn on the host.

use anyhow::Result;
use harness::render::{render as render_scene, SceneSource};

use crate::opt::RenderOpt;

pub fn render(opt: &RenderOpt) -> Result<()> {
    let scene = SceneSource::find(&opt.scene)?.scene();
    let method = opt.method.unwrap_or(scene.method);
    render_scene(&scene, method).write_png(&opt.out)?;
    println!("{}", opt.out.display());
    Ok(())
}
