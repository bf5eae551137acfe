//! The end-to-end checks that the integration tests and the xtask share.

use std::time::{Duration, Instant};

use anyhow::{bail, ensure, Context, Result};
use protocol::{Presentation, ShowReply, Video};
use raster::MethodId;
use scenes::{builtin, show};

use crate::client::{Console, Dump};
use crate::picture::compare::{compare_images, compare_palettes};
use crate::picture::render::{render, render_show};
use crate::picture::Image;
use crate::qemu::Qemu;
use crate::sources::{builtin_scene, show_entry, SceneSource};

/// QEMU shows each mode-13h pixel as a 2x2 block of its 640x400 screen.
pub const SCREEN_SCALE: u32 = 2;

/// Has the kernel draw built-in scene `scene` with `method` on a black
/// screen, and checks its dump against the host render byte for byte, and
/// its DAC against the palette of the render. Returns the dump for further
/// checks.
pub fn dump_matches_host_render(console: &mut Console, scene: &str, method: MethodId) -> Result<Dump> {
    let page = builtin::named(scene).with_context(|| format!("{:#}", builtin_scene(scene).unwrap_err()))?;
    source_matches_host_render(console, &SceneSource::Builtin(page), method)
}

/// Has the kernel draw `source` with `method` on a black screen (a
/// built-in page with `DRAW`; a scene file uploaded whole, then drawn by
/// name) and checks its dump against the host render of the same scene
/// byte for byte, and its DAC against the scene's palette (the VGA
/// default, with a scene file's own entries over it). Returns the dump for
/// further checks.
pub fn source_matches_host_render(console: &mut Console, source: &SceneSource, method: MethodId) -> Result<Dump> {
    let name = source.name();
    let scene = source.scene();
    let expected = render(&scene, method);
    match source {
        SceneSource::Builtin(page) => console.draw(page.name, Some(method)).map(|_| ()),
        SceneSource::File(_) => console.draw_scene(&scene, method).map(|_| ()),
    }
    .with_context(|| format!("kernel failed to draw {name} with {method}"))?;
    let dump = console.dump()?;
    compare_images(&format!("{name}.{method}.dump"), &expected, &dump.image())?;
    compare_palettes(&format!("{name}.{method}.dump"), &scene.dac(), &dump.palette)?;
    Ok(dump)
}

/// Has the kernel show frame `frame` of show entry `entry` with `method`
/// (for `None`, the entry's own method for that frame), and checks that it
/// says it drew what was asked (entry, frame modulo the entry's frames,
/// method), that its dump's framebuffer is the host render (labelled with
/// the kernel's cycles) byte for byte, and that its DAC is the show's
/// palette. Returns the reply and the dump for further checks.
pub fn show_matches_host_render(
    console: &mut Console,
    entry: &str,
    frame: u32,
    method: Option<MethodId>,
) -> Result<(ShowReply<'static>, Dump)> {
    let entry = show_entry(entry)?;
    let drawn_with = method.unwrap_or(entry.method_at(frame));
    let name = format!("{}.{frame}.{drawn_with}.show", entry.name);
    let reply = console.show(entry.name, frame, method).with_context(|| format!("kernel failed to show {name}"))?;
    let asked = (entry.name, entry.wrap(frame), drawn_with);
    let said = (reply.entry, reply.frame, reply.method);
    ensure!(said == asked, "{name}: the kernel says it showed {said:?}, not {asked:?}");
    let dump = console.dump()?;
    let expected = render_show(entry, frame, drawn_with, reply.cycles);
    compare_images(&name, &expected, &dump.image())?;
    compare_palettes(&name, &show::PALETTE, &dump.palette)?;
    Ok((reply, dump))
}

/// Checks QEMU's screendump against the kernel's dump seen through its
/// palette (`c6_to_8`) on the video path `video` that READY named. Mode
/// 13h: every pixel a 2x2 block of a 640x400 screen; zero differing pixels
/// means the registers really put QEMU's VGA model in mode 13h. The
/// framebuffer path: the whole framebuffer, the frame at the scale and
/// offset READY stated and black around it. With no video path nothing
/// shows the frame, which is an error.
pub fn screen_matches_dump(name: &str, dump: &Dump, screen: &Image, video: &Video) -> Result<()> {
    let expected = match video {
        Video::Vga13h { .. } => as_on_screen(&dump.image()),
        Video::Framebuffer(presentation) => on_framebuffer(&dump.image(), presentation)?,
        Video::None => bail!("{name}: READY says nothing shows the frame (video=none), so no screen can match it"),
    };
    compare_images(&format!("{name}.screen"), &expected, screen)
}

/// A 320x200 picture as QEMU's screendump shows it in mode 13h: 640x400,
/// every pixel a [`SCREEN_SCALE`] x [`SCREEN_SCALE`] block of its colour.
/// Row `y` of the picture is rows `y * SCREEN_SCALE` onwards of the screen.
pub fn as_on_screen(picture: &Image) -> Image {
    picture.scaled(SCREEN_SCALE)
}

/// A picture as the framebuffer path presents it: a `width` x `height`
/// black framebuffer with the picture scaled by `scale` at (`left`, `top`);
/// an error if it does not fit.
pub fn on_framebuffer(picture: &Image, presentation: &Presentation) -> Result<Image> {
    let &Presentation { width, height, scale, left, top } = presentation;
    let scaled = picture.scaled(scale);
    ensure!(
        left + scaled.width() <= width && top + scaled.height() <= height,
        "a {}x{} picture at scale {scale} does not fit at ({left}, {top}) in a {width}x{height} framebuffer",
        picture.width(),
        picture.height()
    );
    let inside =
        |x: u32, y: u32| (left..left + scaled.width()).contains(&x) && (top..top + scaled.height()).contains(&y);
    let colors =
        (0..height)
            .flat_map(|y| (0..width).map(move |x| (x, y)))
            .map(|(x, y)| {
                if inside(x, y) {
                    scaled.color(((y - top) * scaled.width() + (x - left)) as usize)
                } else {
                    [0, 0, 0]
                }
            })
            .collect();
    Image::rgb(width, height, colors)
}

/// How many different screens QEMU shows over `watch`, its screen taken
/// every `every`: one while the show stands still, more while it plays (a
/// still page of the show stays 3 s, an animation's frame 1/35 s).
pub fn distinct_screens(qemu: &mut Qemu, watch: Duration, every: Duration) -> Result<usize> {
    let mut screens = Vec::new();
    let started = Instant::now();
    while started.elapsed() < watch {
        let screen = qemu.screendump()?;
        if !screens.contains(&screen) {
            screens.push(screen);
        }
        std::thread::sleep(every);
    }
    Ok(screens.len())
}
