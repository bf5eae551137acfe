//! The show: what the kernel's demo puts on the screen, frame by frame,
//! and what the host renders to check it byte for byte.
//!
//! An [`Entry`] is one scene of the show: a still page of a seed (the
//! [`builtin`](crate::builtin) table's) or an animation. Frame `f` of an entry is a pure
//! function of `(entry, f, method)`, drawn into a [`Stage`] whose memory is
//! allocated once, so the kernel draws frame after frame without touching
//! the heap. Labels (scene, method, measured cycles) are drawn afterwards
//! by [`Stage::label`], with the cycles the kernel measured: the host gets
//! them from the kernel's reply and renders the same pixels.
//!
//! The types the animations share live in modules of their own, beside
//! them: the entries (`entries`), the pace (`pace`), the palette's ramps
//! (`ramp`) and the reusable polygon (`scratch`).

mod entries;
mod interp;
mod label;
mod lamothe;
mod pace;
mod race;
mod ramp;
mod scratch;
mod shaded;
mod trig;

use alloc::vec;
use alloc::vec::Vec;

use crate::builtin::BuiltinPage;
use crate::scene::{DrawReport, Scene};
use entries::Kind;
use raster::stores;
use raster::{Framebuffer, MethodId, SpanSink, SCREEN};
use scratch::Scratch;

pub use entries::{entry, Entry, ENTRIES_IN_ORDER};
pub use pace::{FRAMES_PER_SECOND, STILL_FRAMES};
pub use ramp::{Ramp, PALETTE, RAMP_BASE, RAMP_LEVELS};
pub use shaded::Modelling;

/// All the memory a frame needs, allocated once.
pub struct Stage {
    target: Framebuffer,
    /// One depth value per pixel, for the Z-buffered entry.
    depth: Vec<i32>,
    scratch: Scratch,
    /// The still scene built last, kept so a still page is built once.
    still: Option<Scene>,
    /// The page drawn by every method in turn, built once and kept apart
    /// from the stills', so that playing it leaves the still kept as it was.
    art: Option<Scene>,
}

impl Default for Stage {
    fn default() -> Self {
        Self::new()
    }
}

impl Stage {
    pub fn new() -> Self {
        let pixels = (SCREEN.width * SCREEN.height) as usize;
        Self {
            target: Framebuffer::new(SCREEN),
            depth: vec![0; pixels],
            scratch: Scratch::new(),
            still: None,
            art: None,
        }
    }

    /// Draws frame `frame` (modulo `entry.frames`) of `entry` with `method`
    /// onto a black screen. Allocates only when a still page other than the
    /// last one is built.
    pub fn draw(&mut self, entry: &Entry, frame: u32, method: MethodId) -> DrawReport {
        let frame = entry.wrap(frame);
        let animated = method.method();
        stores::clear(&mut self.target, 0);
        match entry.kind {
            Kind::Still(page) => draw_page(&mut self.still, &page, method, &mut self.target),
            Kind::EveryMethod(page) => draw_page(&mut self.art, &page, method, &mut self.target),
            Kind::LamotheRotate => lamothe::draw(frame, animated, &mut self.scratch, &mut self.target),
            Kind::WgtGouraud => shaded::gouraud(frame, animated, &mut self.scratch, &mut self.target),
            Kind::WgtTexture => shaded::texture(frame, animated, &mut self.scratch, &mut self.target),
            Kind::PendletonDepth => {
                let (scratch, depth, target) = (&mut self.scratch, &mut self.depth, &mut self.target);
                shaded::draw(shaded::Shaded::Depth, Modelling::Needed, frame, animated, scratch, depth, target)
            }
            Kind::Race => race::draw(frame, animated, &mut self.scratch, &mut self.target),
        }
    }

    /// Draws still `entry` with `method` onto `target`, cleared to black
    /// first, as [`Stage::draw`] draws it onto the stage: for a target
    /// other than the stage, such as the screen itself. An animated entry
    /// draws nothing but the black.
    pub fn draw_still<S: SpanSink>(&mut self, entry: &Entry, method: MethodId, target: &mut S) -> DrawReport {
        stores::clear(target, 0);
        match entry.kind {
            Kind::Still(page) => draw_page(&mut self.still, &page, method, target),
            _ => DrawReport::default(),
        }
    }

    /// Draws frame `frame` of a shaded entry with `method`, modelling what
    /// `modelling` asks; `None` for an entry that is not shaded. With
    /// [`Modelling::Needed`] it is [`Stage::draw`]; with
    /// [`Modelling::Forced`] the same picture costs four interpolated
    /// attributes and a depth buffer.
    pub fn draw_modelled(
        &mut self,
        entry: &Entry,
        frame: u32,
        method: MethodId,
        modelling: Modelling,
    ) -> Option<DrawReport> {
        let shaded = match entry.kind {
            Kind::WgtGouraud => shaded::Shaded::Gouraud,
            Kind::WgtTexture => shaded::Shaded::Texture,
            Kind::PendletonDepth => shaded::Shaded::Depth,
            Kind::Still(_) | Kind::LamotheRotate | Kind::Race | Kind::EveryMethod(_) => return None,
        };
        stores::clear(&mut self.target, 0);
        let (scratch, depth, target) = (&mut self.scratch, &mut self.depth, &mut self.target);
        Some(shaded::draw(shaded, modelling, entry.wrap(frame), method.method(), scratch, depth, target))
    }

    /// Draws the labels over the frame (see [`draw_labels`]).
    pub fn label(&mut self, entry: &Entry, frame: u32, method: MethodId, cycles: u64) {
        draw_labels(&mut self.target, entry, frame, method, cycles);
    }

    /// The frame: 320x200 bytes, row after row.
    pub fn pixels(&self) -> &[u8] {
        self.target.pixels()
    }

    /// Spans drawn outside the screen since the stage was made (a method
    /// bug; they were clipped, not written).
    pub fn stray_spans(&self) -> usize {
        self.target.stray_spans()
    }
}

/// Draws built-in `page` with `method` onto `target`, building the page
/// into `built` unless it is the one built last.
fn draw_page<S: SpanSink>(
    built: &mut Option<Scene>,
    page: &BuiltinPage,
    method: MethodId,
    target: &mut S,
) -> DrawReport {
    let scene = match built {
        Some(scene) if scene.name == page.name => scene,
        built => built.insert(page.scene()),
    };
    scene.draw(method, target)
}

/// Draws a caption over `target` in the letters of the labels: `top` at
/// the top, `bottom_left` and `bottom_right` at the bottom.
pub fn draw_caption(target: &mut dyn SpanSink, top: &str, bottom_left: &str, bottom_right: &str) {
    label::draw_caption(target, top, bottom_left, bottom_right);
}

/// Draws the labels of frame `frame` (modulo `entry.frames`) of `entry`
/// over `target`: the entry and frame number at the top, the method and
/// the cycles its draw took at the bottom.
pub fn draw_labels(target: &mut dyn SpanSink, entry: &Entry, frame: u32, method: MethodId, cycles: u64) {
    label::draw_labels(target, entry, entry.wrap(frame), method.name(), cycles);
}

#[cfg(test)]
mod tests {
    use alloc::vec::Vec;

    use super::*;

    /// The entries whose picture moves from frame to frame: the animated
    /// ones but the pages drawn by every method in turn, whose picture
    /// changes only with the method.
    fn animations() -> impl Iterator<Item = &'static Entry> {
        ENTRIES_IN_ORDER.iter().filter(|entry| entry.is_animated() && !matches!(entry.kind, Kind::EveryMethod(_)))
    }

    #[test]
    fn the_world_is_drawn_by_the_method_whose_turn_it_is_and_exact_draws_it_whole() {
        let world = entry("world").unwrap();
        let mut stage = Stage::new();
        let mut pictures = Vec::new();
        for frame in (0..world.frames).step_by(world.frames as usize / MethodId::ALL.len()) {
            let method = world.method_at(frame);
            let strays = stage.stray_spans();
            let (pixels, report) = frame_of(&mut stage, world, frame, method);
            assert_eq!(report.polygons, 129, "world with {method}");
            assert_eq!(stage.stray_spans(), strays, "world with {method} drew outside the screen");
            if method == MethodId::Exact {
                assert_eq!(report.refused, 0, "exact refused {report:?}");
            }
            pictures.push((method, pixels));
        }
        let methods: Vec<MethodId> = pictures.iter().map(|(method, _)| *method).collect();
        assert_eq!(methods, MethodId::ALL);
        let exact = &pictures.last().expect("exact has the last turn").1;
        let differing = pictures.iter().filter(|(_, pixels)| pixels != exact).count();
        assert!(differing >= 5, "only {differing} methods draw the world otherwise than exact");
    }

    /// Frame `frame` of `entry` with `method` on `stage`, and its report.
    fn frame_of(stage: &mut Stage, entry: &Entry, frame: u32, method: MethodId) -> (Vec<u8>, DrawReport) {
        let report = stage.draw(entry, frame, method);
        (stage.pixels().to_vec(), report)
    }

    #[test]
    fn every_frame_is_a_pure_function_of_its_number_and_the_loop_closes() {
        for entry in animations() {
            let frames: Vec<u32> = (0..entry.frames).step_by(11).collect();
            let mut stage = Stage::new();
            let first: Vec<Vec<u8>> =
                frames.iter().map(|&f| frame_of(&mut stage, entry, f, MethodId::Exact).0).collect();
            // A stage that drew other frames, in another order, draws the
            // same pixels: nothing carries over from one frame to the next.
            let mut other = Stage::new();
            for (&f, pixels) in frames.iter().zip(&first).rev() {
                assert_eq!(&frame_of(&mut other, entry, f, MethodId::Exact).0, pixels, "{} frame {f}", entry.name);
            }
            assert_eq!(
                frame_of(&mut stage, entry, entry.frames, MethodId::Exact).0,
                first[0],
                "{} does not loop",
                entry.name
            );
            assert_ne!(
                frame_of(&mut stage, entry, 1, MethodId::Exact).0,
                first[0],
                "{}: frame 1 is frame 0",
                entry.name
            );
        }
    }

    #[test]
    fn every_method_draws_every_animation_whole_and_inside_the_screen() {
        let mut stage = Stage::new();
        for entry in animations() {
            for method in MethodId::ALL {
                let name = method.name();
                let (_, first) = frame_of(&mut stage, entry, 0, method);
                for frame in (0..entry.frames).step_by(13) {
                    let strays = stage.stray_spans();
                    let (pixels, report) = frame_of(&mut stage, entry, frame, method);
                    let at = || alloc::format!("{} frame {frame} with {name}: {report:?}", entry.name);
                    assert!(report.polygons > 0 && report.polygons == first.polygons, "{}", at());
                    assert_eq!(report.refused, 0, "{}", at());
                    assert_eq!(stage.stray_spans(), strays, "{}", at());
                    assert!(pixels.iter().any(|&p| p != 0), "{}: nothing drawn", at());
                }
            }
        }
    }

    /// The shaded entries (`shaded.rs`).
    fn shaded_entries() -> [&'static Entry; 3] {
        ["wgt-gouraud", "wgt-texture", "pendleton-zbuffer"].map(|name| entry(name).unwrap())
    }

    /// Frame `frame` of `entry` drawn by `exact` on a stage that has drawn
    /// before (the stage must not carry anything from one frame over),
    /// which must draw it whole.
    fn whole_frame(stage: &mut Stage, entry: &Entry, frame: u32) -> Vec<u8> {
        let (pixels, report) = frame_of(stage, entry, frame, MethodId::Exact);
        assert_eq!(report.refused, 0, "{} frame {frame}: {report:?}", entry.name);
        pixels
    }

    /// Modelling more than needed costs time, not pixels: four attributes
    /// and a depth buffer draw each shaded frame as it is drawn without.
    #[test]
    fn overmodelled_shaded_frames_are_the_frames_they_overmodel() {
        let mut stage = Stage::new();
        for entry in shaded_entries() {
            for frame in [0, 37, entry.frames - 1] {
                let needed = whole_frame(&mut stage, entry, frame);
                let report = stage.draw_modelled(entry, frame, MethodId::Exact, Modelling::Forced).unwrap();
                assert_eq!(report.refused, 0, "{} frame {frame}", entry.name);
                assert!(stage.pixels() == needed.as_slice(), "{} frame {frame} differs", entry.name);
            }
        }
        let still = entry("abrash38-1").unwrap();
        assert_eq!(stage.draw_modelled(still, 0, MethodId::Exact, Modelling::Forced), None);
    }

    #[test]
    fn shaded_frames_differ_from_each_other() {
        let mut stage = Stage::new();
        for entry in shaded_entries() {
            let quarters: Vec<Vec<u8>> = (0..4).map(|q| whole_frame(&mut stage, entry, q * entry.frames / 4)).collect();
            for a in 0..4 {
                for b in a + 1..4 {
                    assert!(quarters[a] != quarters[b], "{}: quarters {a} and {b} are the same", entry.name);
                }
            }
            let next = whole_frame(&mut stage, entry, 1);
            assert!(next != quarters[0], "{}: frame 1 is frame 0", entry.name);
        }
    }

    #[test]
    fn shaded_pixels_are_black_or_ramp_colours() {
        let expected: [&[Ramp]; 3] = [&[Ramp::Gold], &[Ramp::Red, Ramp::Gold], &[Ramp::Red, Ramp::Green, Ramp::Blue]];
        let mut stage = Stage::new();
        for (entry, ramps) in shaded_entries().into_iter().zip(expected) {
            // For each ramp, the frames that show more than a speck of it.
            let mut shown = [0; 4];
            let frames: Vec<u32> = (0..entry.frames).step_by(5).collect();
            for &frame in &frames {
                let pixels = whole_frame(&mut stage, entry, frame);
                let used: Vec<Option<Ramp>> = pixels.iter().map(|&p| Ramp::of(p)).collect();
                let allowed = |(&p, r): (&u8, &Option<Ramp>)| p == 0 || r.is_some_and(|r| ramps.contains(&r));
                assert!(pixels.iter().zip(&used).all(allowed), "{} frame {frame}: a stray colour", entry.name);
                for &ramp in ramps {
                    shown[ramp as usize] += usize::from(used.iter().filter(|&&r| r == Some(ramp)).count() > 500);
                }
            }
            // A rectangle turned edge-on is a line for a few frames.
            for &ramp in ramps {
                let seen = shown[ramp as usize];
                assert!(seen >= frames.len() * 9 / 10, "{}: {ramp:?} in {seen} of {} frames", entry.name, frames.len());
            }
        }
    }

    #[test]
    fn a_still_drawn_onto_another_target_is_the_stage_s_frame_and_an_animation_is_black() {
        let mut stage = Stage::new();
        for entry in ENTRIES_IN_ORDER.iter().filter(|e| !e.is_animated()) {
            let method = entry.method_at(0);
            let mut elsewhere = Framebuffer::new(SCREEN);
            // Not black: the still clears its target first.
            stores::clear(&mut elsewhere, 9);
            let report = stage.draw_still(entry, method, &mut elsewhere);
            draw_labels(&mut elsewhere, entry, 0, method, 1234);
            let staged = stage.draw(entry, 0, method);
            stage.label(entry, 0, method, 1234);
            assert_eq!(elsewhere.pixels(), stage.pixels(), "{}", entry.name);
            assert_eq!(report, staged, "{}", entry.name);
            assert!(report.polygons > 0, "{}", entry.name);
        }
        let rotate = entry("lamothe-rotate").unwrap();
        let mut elsewhere = Framebuffer::new(SCREEN);
        stores::clear(&mut elsewhere, 9);
        assert_eq!(stage.draw_still(rotate, MethodId::Exact, &mut elsewhere).polygons, 0);
        assert!(elsewhere.pixels().iter().all(|&p| p == 0));
    }
}
