//! The end-to-end checks that the integration tests and the xtask share.

use anyhow::{Context, Result};
use raster::Method;

use crate::compare::compare_images;
use crate::console::{Console, Dump};
use crate::picture::Image;
use crate::render::{builtin_scene, render};

/// QEMU shows each mode-13h pixel as a 2x2 block of its 640x400 screen.
pub const SCREEN_SCALE: u32 = 2;

/// Has the kernel draw built-in scene `scene` with `method` on a black
/// screen, and checks its dump against the host render byte for byte.
/// Returns the dump for further checks.
pub fn dump_matches_host_render(console: &mut Console, scene: &str, method: &dyn Method) -> Result<Dump> {
    let method_name = method.info().name;
    let expected = render(&builtin_scene(scene)?, method);
    console
        .draw(scene, Some(method_name))
        .with_context(|| format!("kernel failed to draw {scene} with {method_name}"))?;
    let dump = console.dump()?;
    compare_images(&format!("{scene}.{method_name}.dump"), &expected, &dump.image())?;
    Ok(dump)
}

/// Checks QEMU's screendump against the kernel's dump seen through its
/// read-back DAC (`c6_to_8`), every pixel a 2x2 block: zero differing
/// pixels means the registers really put QEMU's VGA model in mode 13h.
pub fn screen_matches_dump(name: &str, dump: &Dump, screen: &Image) -> Result<()> {
    compare_images(&format!("{name}.screen"), &dump.image().scaled(SCREEN_SCALE), screen)
}
