//! The shaded entries: what the seeds announce beyond flat colour, drawn
//! through [`interp`](super::interp) by whichever method the viewer picks.
//!
//! - `wgt-gouraud`: the WGT tutorial's triangle (160,30), (50,150),
//!   (270,180), Gouraud shaded in the gold ramp, a light going round its
//!   corners.
//! - `wgt-texture`: a square of bricks turning once and swaying, mapped
//!   affinely (as WGT's and Pendleton's `poly2t`) as two triangles that
//!   share a diagonal.
//! - `pendleton-zbuffer`: Pendleton's Z buffer, two rectangles spinning
//!   about perpendicular axes through one point, so they always cut each
//!   other, and a triangle sliding through them in depth.
//!   The projection is orthographic, so depth is affine on the screen and
//!   is interpolated as it is, "just like Z".
//!
//! Every frame is a pure function of its number, in integers only: turns
//! come from [`trig`](super::trig)'s integer sine and cosine, a whole
//! number of turns over an entry's frames, so its last frame leads back to
//! its first.

use super::interp::{Painter, Vertex};
use super::ramp::Ramp;
use super::scratch::Scratch;
use super::trig::{angle_at, div_round, offset, rotate, sin_cos, unscale, TURN};
use crate::scene::DrawReport;
use raster::{Framebuffer, Method, Point, SpanSink, SUBPIXEL_BITS};

/// How much a shaded frame models ("model no more than a scene needs",
/// measured by the lab).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Modelling {
    /// What the entry needs: flat shading one attribute, texture two, the
    /// Z-buffered scene two and its depth buffer.
    Needed,
    /// Four interpolated attributes and a depth buffer, whatever it needs.
    Forced,
}

pub(super) const GOURAUD_FRAMES: u32 = 120;
pub(super) const TEXTURE_FRAMES: u32 = 120;
pub(super) const DEPTH_FRAMES: u32 = 120;

/// Fractional bits of an interpolated ramp level.
const LEVEL_BITS: u32 = 8;
/// One ramp level, in interpolated units.
const LEVEL_ONE: i32 = 1 << LEVEL_BITS;

/// The screen's centre, in subpixels.
const CENTRE: Point = Point::from_pixels(160, 100);

/// Goes from 0 up to `peak` and back to 0, linearly, as `t` runs over one
/// `period`.
fn triangle_wave(t: u32, period: u32, peak: i32) -> i32 {
    let phase = t % period;
    let rise = phase.min(period - phase);
    (i64::from(peak) * i64::from(2 * rise) / i64::from(period)) as i32
}

/// The WGT tutorial's triangle, in pixels.
const WGT_TRIANGLE: [(i32, i32); 3] = [(160, 30), (50, 150), (270, 180)];
/// The gold ramp's levels at a corner the light is far from and at.
const GOURAUD_DARK: i32 = 2;
const GOURAUD_BRIGHT: i32 = 31;

/// Frame `frame` of the Gouraud triangle: a light goes round the corners
/// once per loop (top, bottom left, bottom right); a corner is brightest
/// when the light is on it, darkest from when the light reaches either
/// other corner.
fn gouraud_triangle(frame: u32) -> [Vertex<1>; 3] {
    let third = GOURAUD_FRAMES / 3;
    [0, 1, 2].map(|i| {
        let (x, y) = WGT_TRIANGLE[i];
        // Frames from the light to this corner, either way round.
        let phase = (frame + GOURAUD_FRAMES - i as u32 * third) % GOURAUD_FRAMES;
        let away = phase.min(GOURAUD_FRAMES - phase).min(third);
        let lit = (GOURAUD_BRIGHT - GOURAUD_DARK) * LEVEL_ONE * (third - away) as i32 / third as i32;
        Vertex::new(Point::from_pixels(x, y), [GOURAUD_DARK * LEVEL_ONE + lit])
    })
}

/// Draws frame `frame` of `wgt-gouraud`.
pub(super) fn gouraud(frame: u32, method: &dyn Method, scratch: &mut Scratch, target: &mut Framebuffer) -> DrawReport {
    let mut painter = Painter::new(method, scratch, target);
    painter.triangle(&gouraud_triangle(frame), &mut |_, _, &[level]: &[i32; 1]| {
        Some(Ramp::Gold.color(level >> LEVEL_BITS))
    });
    painter.report()
}

/// Texels a side of the brick texture (a power of two, so it tiles by
/// masking).
const TEXTURE_SIZE: i32 = 32;
/// Fractional bits of a texture coordinate.
const TEXEL_BITS: u32 = 8;
/// Times the texture repeats along each side of the square.
const TILES: i32 = 2;
/// Half the square's side, in pixels, and how far it sways from the
/// centre.
const SQUARE_HALF: i32 = 55;
const SWAY: i32 = 60;

/// The brick texture at texel `(u, v)` (taken modulo its size): courses
/// 8 texels high, bricks 16 long, every other course shifted by half a
/// brick, each brick its own shade of red lit from the top, mortar gold.
fn texel(u: i32, v: i32) -> u8 {
    let (u, v) = (u & (TEXTURE_SIZE - 1), v & (TEXTURE_SIZE - 1));
    let course = v / 8;
    let along = (u + course % 2 * 8) & (TEXTURE_SIZE - 1);
    let (brick, x, y) = (along / 16, along % 16, v % 8);
    if x == 15 || y == 7 {
        return Ramp::Gold.color(9 - y / 4);
    }
    let shade = (course * 5 + brick * 3) % 4;
    let edge = if x == 0 || y == 0 { 4 } else { 0 };
    Ramp::Red.color(17 + shade * 2 + edge - y)
}

/// Frame `frame` of the textured square: corners in drawing order with
/// their texture coordinates `[u, v]`, turned and moved.
fn texture_quad(frame: u32) -> [Vertex<2>; 4] {
    let angle = angle_at(frame, TEXTURE_FRAMES, 1);
    let sway = triangle_wave(frame + TEXTURE_FRAMES / 4, TEXTURE_FRAMES, 2 * SWAY) - SWAY;
    let centre = offset(CENTRE, Point::from_pixels(sway, 0));
    let half = SQUARE_HALF << SUBPIXEL_BITS;
    let far = (TILES * TEXTURE_SIZE) << TEXEL_BITS;
    [(-1, -1), (1, -1), (1, 1), (-1, 1)].map(|(sx, sy)| {
        let uv = [(sx + 1) / 2 * far, (sy + 1) / 2 * far];
        Vertex::new(offset(centre, rotate(Point::new(sx * half, sy * half), angle)), uv)
    })
}

/// Draws frame `frame` of `wgt-texture`.
pub(super) fn texture(frame: u32, method: &dyn Method, scratch: &mut Scratch, target: &mut Framebuffer) -> DrawReport {
    let mut painter = Painter::new(method, scratch, target);
    painter.quad(&texture_quad(frame), &mut |_, _, &[u, v]: &[i32; 2]| Some(texel(u >> TEXEL_BITS, v >> TEXEL_BITS)));
    painter.report()
}

/// The corners of a polygon of the Z-buffered scene, each with `[z,
/// level]`: depth in subpixels (larger is farther) and level in 1/256.
#[derive(Clone, Copy, Debug)]
enum Shape {
    Triangle([Vertex<2>; 3]),
    Quad([Vertex<2>; 4]),
}

/// A polygon of the Z-buffered scene, shaded in its own ramp.
#[derive(Clone, Copy, Debug)]
struct Solid {
    shape: Shape,
    ramp: Ramp,
}

/// The scene's depth range: every z lies within `±DEPTH_RANGE` subpixels.
const DEPTH_RANGE: i32 = 128 << SUBPIXEL_BITS;

/// The level of a point at depth `z` on a face that looks at the viewer
/// by `facing` (0 to [`FACING_LEVELS`]): brighter when nearer and when
/// facing squarely, from level 4 to 31.
fn depth_level(z: i32, facing: i32) -> i32 {
    let near = div_round(i64::from(DEPTH_RANGE - z) * i64::from(17 * LEVEL_ONE), i64::from(2 * DEPTH_RANGE));
    4 * LEVEL_ONE + facing * LEVEL_ONE + near as i32
}

/// Levels a face gains by looking at the viewer squarely.
const FACING_LEVELS: i32 = 10;
/// How far the sloping triangle slides forward and back, in subpixels.
const SLIDE: i32 = 60 << SUBPIXEL_BITS;

/// A rectangle `2 * width` by `2 * height` pixels around the screen's
/// centre, turned by `angle` (in [`TURN`]ths) about the vertical axis
/// (`about_x` false) or the horizontal one, projected straight onto the
/// screen.
fn spinning_rectangle(width: i32, height: i32, angle: u32, about_x: bool, ramp: Ramp) -> Solid {
    // How squarely the face looks at the viewer: |cos| of the turn.
    let facing = unscale(i64::from(sin_cos(angle).1.abs()) * i64::from(FACING_LEVELS));
    let corners = [(-1, -1), (1, -1), (1, 1), (-1, 1)].map(|(sx, sy)| {
        let (x, y) = (sx * (width << SUBPIXEL_BITS), sy * (height << SUBPIXEL_BITS));
        // The turning axis of the face stays put; the other one turns into
        // depth: (along, 0) becomes (along cos, along sin) = (screen, z).
        let (screen, z) = if about_x {
            let turned = rotate(Point::new(y, 0), angle);
            (Point::new(x, turned.x), turned.y)
        } else {
            let turned = rotate(Point::new(x, 0), angle);
            (Point::new(turned.x, y), turned.y)
        };
        Vertex::new(offset(CENTRE, screen), [z, depth_level(z, facing)])
    });
    Solid { shape: Shape::Quad(corners), ramp }
}

/// Frame `frame` of the Z-buffered scene: a wide red rectangle turning
/// once about the vertical axis, a tall blue one turning once the other
/// way about the horizontal axis, an eighth of a turn apart, and a green
/// triangle sloping back that slides forward and back through them.
fn solids(frame: u32) -> [Solid; 3] {
    let wide = spinning_rectangle(100, 55, angle_at(frame, DEPTH_FRAMES, 1), false, Ramp::Red);
    let back = angle_at(frame, DEPTH_FRAMES, -1) + TURN / 8;
    let tall = spinning_rectangle(42, 85, back, true, Ramp::Blue);
    let slide = triangle_wave(frame + DEPTH_FRAMES / 8, DEPTH_FRAMES, 2 * SLIDE) - SLIDE;
    let corners = [(-40, 80, -50), (150, 20, 60), (-120, -20, 20)].map(|(x, y, z)| {
        let z = (z << SUBPIXEL_BITS) + slide;
        let at = offset(CENTRE, Point::from_pixels(x, y));
        Vertex::new(at, [z, depth_level(z, FACING_LEVELS * 3 / 4)])
    });
    let sloping = Solid { shape: Shape::Triangle(corners), ramp: Ramp::Green };
    [wide, tall, sloping]
}

/// The Z test at pixel `(x, y)` of `depth`, a row-major buffer `width`
/// values a row: whether `z` is nearer than what is there, which it then
/// replaces. Pixels beyond the buffer's end never pass.
fn nearer(depth: &mut [i32], width: i32, x: i32, y: i32, z: i32) -> bool {
    let Some(nearest) = usize::try_from(y * width + x).ok().and_then(|i| depth.get_mut(i)) else {
        return false;
    };
    let passes = z < *nearest;
    if passes {
        *nearest = z;
    }
    passes
}

/// Draws `solids` with the Z test against `depth`, a row-major buffer
/// `width` values a row (pixels beyond its end are left alone).
fn draw_solids(solids: &[Solid], painter: &mut Painter, depth: &mut [i32], width: i32) {
    for solid in solids {
        let mut shade = |x: i32, y: i32, &[z, level]: &[i32; 2]| {
            nearer(depth, width, x, y, z).then(|| solid.ramp.color(level >> LEVEL_BITS))
        };
        match &solid.shape {
            Shape::Triangle(corners) => painter.triangle(corners, &mut shade),
            Shape::Quad(corners) => painter.quad(corners, &mut shade),
        }
    }
}

/// Attributes a frame carries when more is modelled than it needs.
const OVERMODELLED: usize = 4;

/// `v` with its attributes followed by zeros, up to [`OVERMODELLED`].
fn padded<const N: usize>(v: Vertex<N>) -> Vertex<OVERMODELLED> {
    let mut attrs = [0; OVERMODELLED];
    attrs[..N].copy_from_slice(&v.attrs);
    Vertex::new(v.at, attrs)
}

/// Draws frame `frame` of a shaded entry as `modelling` asks; `depth` holds
/// one value per pixel of `target` and is reset first where it is used.
/// [`Modelling::Forced`] costs more for the same picture: four interpolated
/// attributes where the entry uses one or two, and a depth buffer, reset
/// and tested at every pixel, where it has none (the Gouraud and texture
/// entries take depth 0 everywhere, so every pixel passes).
pub(super) fn draw(
    entry: Shaded,
    modelling: Modelling,
    frame: u32,
    method: &dyn Method,
    scratch: &mut Scratch,
    depth: &mut [i32],
    target: &mut Framebuffer,
) -> DrawReport {
    match (entry, modelling) {
        (Shaded::Gouraud, Modelling::Needed) => return gouraud(frame, method, scratch, target),
        (Shaded::Texture, Modelling::Needed) => return texture(frame, method, scratch, target),
        _ => {}
    }
    depth.fill(i32::MAX);
    let width = target.size().width;
    let mut painter = Painter::new(method, scratch, target);
    match entry {
        Shaded::Gouraud => {
            let corners = gouraud_triangle(frame).map(padded);
            painter.triangle(&corners, &mut |x, y, &[level, z, _, _]: &[i32; OVERMODELLED]| {
                nearer(depth, width, x, y, z).then(|| Ramp::Gold.color(level >> LEVEL_BITS))
            });
        }
        Shaded::Texture => {
            let corners = texture_quad(frame).map(padded);
            painter.quad(&corners, &mut |x, y, &[u, v, z, _]: &[i32; OVERMODELLED]| {
                nearer(depth, width, x, y, z).then(|| texel(u >> TEXEL_BITS, v >> TEXEL_BITS))
            });
        }
        Shaded::Depth if modelling == Modelling::Needed => {
            draw_solids(&solids(frame), &mut painter, depth, width);
        }
        Shaded::Depth => {
            for solid in solids(frame) {
                let mut shade = |x: i32, y: i32, &[z, level, _, _]: &[i32; OVERMODELLED]| {
                    nearer(depth, width, x, y, z).then(|| solid.ramp.color(level >> LEVEL_BITS))
                };
                match &solid.shape {
                    Shape::Triangle(corners) => painter.triangle(&corners.map(padded), &mut shade),
                    Shape::Quad(corners) => painter.quad(&corners.map(padded), &mut shade),
                }
            }
        }
    }
    painter.report()
}

/// The shaded entries.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Shaded {
    Gouraud,
    Texture,
    Depth,
}

#[cfg(test)]
mod tests {
    use alloc::vec;
    use alloc::vec::Vec;

    use super::*;
    use raster::methods::Exact;
    use raster::{CoverageSink, Polygon, SCREEN};

    #[test]
    fn the_light_goes_round_the_triangle() {
        let (mut scratch, mut target) = (Scratch::new(), Framebuffer::new(SCREEN));
        // Just inside each corner of the WGT triangle.
        let near = [(160, 34), (57, 148), (262, 177)];
        for (corner, &(x, y)) in near.iter().enumerate() {
            let lit_frame = corner as u32 * GOURAUD_FRAMES / 3;
            gouraud(lit_frame, &Exact, &mut scratch, &mut target);
            let lit = target.get(x, y).unwrap();
            assert!(lit >= Ramp::Gold.color(GOURAUD_BRIGHT - 3), "corner {corner} when lit: {lit}");
            gouraud(lit_frame + GOURAUD_FRAMES / 2, &Exact, &mut scratch, &mut target);
            let dark = target.get(x, y).unwrap();
            assert!(dark <= Ramp::Gold.color(GOURAUD_DARK + 1), "corner {corner} when dark: {dark}");
        }
    }

    /// What `solids` draw alone, each on its own screen, and together.
    fn solo_and_together(solids: &[Solid]) -> (Vec<Framebuffer>, Framebuffer) {
        let draw = |solids: &[Solid]| {
            let (mut scratch, mut target) = (Scratch::new(), Framebuffer::new(SCREEN));
            let mut depth = vec![0; (SCREEN.width * SCREEN.height) as usize];
            depth.fill(i32::MAX);
            let mut painter = Painter::new(&Exact, &mut scratch, &mut target);
            draw_solids(solids, &mut painter, &mut depth, SCREEN.width);
            target
        };
        (solids.iter().map(|solid| draw(core::slice::from_ref(solid))).collect(), draw(solids))
    }

    /// Over the pixels both solid `a` and solid `b` cover, how many show
    /// `a` and how many `b`.
    fn shares(solo: &[Framebuffer], together: &Framebuffer, a: usize, b: usize) -> (usize, usize) {
        let both = |i: usize| solo[a].pixels()[i] != 0 && solo[b].pixels()[i] != 0;
        let shown = |i: usize, s: usize| Ramp::of(together.pixels()[i]) == Ramp::of(solo[s].pixels()[i]);
        let overlap: Vec<usize> = (0..together.pixels().len()).filter(|&i| both(i)).collect();
        (overlap.iter().filter(|&&i| shown(i, a)).count(), overlap.iter().filter(|&&i| shown(i, b)).count())
    }

    #[test]
    fn the_rectangles_cut_each_other_and_the_triangle_slides_through() {
        // Frames where the triangle cuts the red and the blue rectangle.
        let mut cuts = [0; 2];
        for frame in (0..DEPTH_FRAMES).step_by(3) {
            let solids = solids(frame);
            let (solo, together) = solo_and_together(&solids);
            // The rectangles meet on a line through the centre of both:
            // wherever they overlap, each is in front on its side of it.
            let (wide, tall) = shares(&solo, &together, 0, 1);
            if wide + tall > 200 {
                assert!(wide > 20 && tall > 20, "frame {frame}: red {wide} and blue {tall} pixels where they overlap");
            }
            for (rectangle, cut) in cuts.iter_mut().enumerate() {
                let (shown, sloping) = shares(&solo, &together, rectangle, 2);
                *cut += usize::from(shown > 20 && sloping > 20);
            }
        }
        assert!(cuts.iter().all(|&c| c >= 10), "frames where the triangle cuts red, blue: {cuts:?}");
    }

    #[test]
    fn exact_keeps_every_polygon_on_screen_and_splits_quads_cleanly() {
        let fill = |corners: &[Point], sink: &mut CoverageSink| {
            Exact.fill(&Polygon::new(corners.to_vec(), 1), sink).unwrap();
        };
        let check = |sink: &CoverageSink, what: &str| {
            let report = sink.report(sink);
            assert_eq!((report.out_of_bounds, report.overdrawn), (0, 0), "{what}: stray spans, pixels drawn twice");
        };
        let quad = |corners: [Point; 4], what: &str| {
            let mut sink = CoverageSink::new(SCREEN);
            fill(&[corners[0], corners[1], corners[2]], &mut sink);
            fill(&[corners[0], corners[2], corners[3]], &mut sink);
            check(&sink, what);
        };
        for frame in 0..GOURAUD_FRAMES {
            let mut sink = CoverageSink::new(SCREEN);
            fill(&gouraud_triangle(frame).map(|v| v.at), &mut sink);
            check(&sink, "gouraud");
        }
        for frame in 0..TEXTURE_FRAMES {
            quad(texture_quad(frame).map(|v| v.at), "texture");
        }
        for frame in 0..DEPTH_FRAMES {
            for solid in solids(frame) {
                match solid.shape {
                    Shape::Triangle(corners) => {
                        let mut sink = CoverageSink::new(SCREEN);
                        fill(&corners.map(|v| v.at), &mut sink);
                        check(&sink, "depth triangle");
                    }
                    Shape::Quad(corners) => quad(corners.map(|v| v.at), "depth rectangle"),
                }
            }
        }
    }
}
