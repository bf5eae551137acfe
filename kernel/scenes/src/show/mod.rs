//! The show: what the kernel's demo puts on the screen, frame by frame,
//! and what the host renders to check it byte for byte.
//!
//! An [`Entry`] is one scene of the show: a still page of a seed (the
//! [`builtin`] table's) or an animation. Frame `f` of an entry is a pure
//! function of `(entry, f, method)`, drawn into a [`Stage`] whose memory is
//! allocated once, so the kernel draws frame after frame without touching
//! the heap. Labels (scene, method, measured cycles) are drawn afterwards
//! by [`Stage::label`], with the cycles the kernel measured: the host gets
//! them from the kernel's reply and renders the same pixels.

mod interp;
mod label;
mod lamothe;
mod race;
mod shaded;
mod trig;

use alloc::vec;
use alloc::vec::Vec;

use crate::builtin::{self, Builtin};
use crate::palette::{ENTRIES, VGA_DEFAULT};
use crate::scene::{DrawReport, Scene};
use raster::geometry::{Point, Polygon};
use raster::sink::{self, Framebuffer, SpanSink, SCREEN};
use raster::{Method, MethodId};

/// Frames per second the show is paced at: every second retrace of mode
/// 13h's 70 Hz refresh.
pub const FRAMES_PER_SECOND: u32 = 35;
/// How long a still page stays up in the demo, in frames (3 seconds).
pub const STILL_FRAMES: u32 = 3 * FRAMES_PER_SECOND;

/// What an entry draws.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    /// A built-in scene, the same on every frame.
    Still(Builtin),
    /// LaMothe's rotation test: a convex n-gon and quads turning 360 degrees.
    LamotheRotate,
    /// The WGT triangle, Gouraud shaded through a palette ramp.
    WgtGouraud,
    /// A texture-mapped quad, texels from palette ramps.
    WgtTexture,
    /// Pendleton's Z-buffered 3D polygons that intersect.
    PendletonDepth,
    /// One scene drawn by every method in turn.
    Race,
}

/// One scene of the show.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Entry {
    pub name: &'static str,
    /// Distinct frames; frame numbers wrap around modulo this. 1 for stills.
    pub frames: u32,
    /// The method of the scene's source.
    pub method: MethodId,
    kind: Kind,
}

impl Entry {
    /// A still page: the built-in scene, with its name and its method.
    const fn still(builtin: Builtin) -> Self {
        Self { name: builtin.name, frames: 1, method: builtin.method, kind: Kind::Still(builtin) }
    }

    const fn animation(name: &'static str, frames: u32, method: MethodId, kind: Kind) -> Self {
        Self { name, frames, method, kind }
    }

    /// Whether frames differ from each other.
    pub fn is_animated(&self) -> bool {
        self.frames > 1
    }

    /// How many frames the demo shows this entry for before moving on.
    pub fn demo_frames(&self) -> u32 {
        if self.is_animated() {
            self.frames
        } else {
            STILL_FRAMES
        }
    }

    /// Frame `frame` as the entry draws it: frame numbers wrap around its
    /// [`Entry::frames`].
    pub fn wrap(&self, frame: u32) -> u32 {
        frame % self.frames.max(1)
    }

    /// The method that draws frame `frame` when the viewer picked none: the
    /// source's method, or for the race the method whose turn it is.
    pub fn method_at(&self, frame: u32) -> MethodId {
        match self.kind {
            Kind::Race => race::method_at(self.wrap(frame)),
            _ => self.method,
        }
    }
}

/// The show in demo order.
pub const ENTRIES_IN_ORDER: &[Entry] = &[
    Entry::still(builtin::ABRASH38_1),
    Entry::still(builtin::ABRASH38_2),
    Entry::still(builtin::ABRASH38_3),
    Entry::still(builtin::ABRASH40_1),
    Entry::still(builtin::ABRASH40_2),
    Entry::still(builtin::ABRASH40_3),
    Entry::still(builtin::ABRASH40_4),
    Entry::still(builtin::LAMOTHE_TRIANGLE),
    Entry::animation("lamothe-rotate", lamothe::FRAMES, MethodId::Lamothe, Kind::LamotheRotate),
    Entry::still(builtin::WGT_TRIANGLE),
    Entry::animation("wgt-gouraud", shaded::GOURAUD_FRAMES, MethodId::Wgt, Kind::WgtGouraud),
    Entry::animation("wgt-texture", shaded::TEXTURE_FRAMES, MethodId::Wgt, Kind::WgtTexture),
    Entry::animation("pendleton-zbuffer", shaded::DEPTH_FRAMES, MethodId::Pendleton, Kind::PendletonDepth),
    Entry::animation("race", race::FRAMES, MethodId::Exact, Kind::Race),
];

/// The entry called `name`.
pub fn entry(name: &str) -> Option<&'static Entry> {
    ENTRIES_IN_ORDER.iter().find(|e| e.name == name)
}

/// First palette index of the show's colour ramps.
pub const RAMP_BASE: u8 = 128;
/// Levels per ramp, darkest first.
pub const RAMP_LEVELS: u8 = 32;

/// The show's four colour ramps, at `RAMP_BASE + ramp * RAMP_LEVELS`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ramp {
    Red = 0,
    Green = 1,
    Blue = 2,
    Gold = 3,
}

impl Ramp {
    /// The palette index of `level` (clamped to `0..RAMP_LEVELS`).
    pub const fn color(self, level: i32) -> u8 {
        let level = if level < 0 {
            0
        } else if level >= RAMP_LEVELS as i32 {
            RAMP_LEVELS as i32 - 1
        } else {
            level
        };
        RAMP_BASE + self as u8 * RAMP_LEVELS + level as u8
    }

    /// Full-brightness colour, 6-bit red, green, blue.
    const fn top(self) -> [u8; 3] {
        match self {
            Ramp::Red => [63, 12, 8],
            Ramp::Green => [10, 63, 16],
            Ramp::Blue => [12, 28, 63],
            Ramp::Gold => [63, 52, 12],
        }
    }
}

/// The show's palette: the VGA default for entries 0-127 (every still page
/// uses only those) and four ramps of [`RAMP_LEVELS`] from black to full
/// colour in 128-255, for shading and textures.
pub const PALETTE: [[u8; 3]; ENTRIES] = {
    let mut palette = VGA_DEFAULT;
    let ramps = [Ramp::Red, Ramp::Green, Ramp::Blue, Ramp::Gold];
    let mut r = 0;
    while r < ramps.len() {
        let top = ramps[r].top();
        let mut level = 0;
        while level < RAMP_LEVELS as usize {
            let mut c = 0;
            while c < 3 {
                // Linear from black (level 0) to `top` (the last level).
                let value = top[c] as usize * level / (RAMP_LEVELS as usize - 1);
                palette[ramps[r].color(level as i32) as usize][c] = value as u8;
                c += 1;
            }
            level += 1;
        }
        r += 1;
    }
    palette
};

/// Reusable polygon storage: filled in place each frame, so that after the
/// first frame no vertex list is allocated again.
pub(crate) struct Scratch {
    polygon: Polygon,
}

/// Vertices a scratch polygon holds without growing.
const SCRATCH_VERTICES: usize = 64;

impl Scratch {
    fn new() -> Self {
        Self { polygon: Polygon { contours: vec![Vec::with_capacity(SCRATCH_VERTICES)], ..Polygon::default() } }
    }

    /// The scratch polygon set to one contour of `points` in `color`
    /// (even-odd rule).
    pub(crate) fn polygon(&mut self, points: impl IntoIterator<Item = Point>, color: u8) -> &Polygon {
        self.polygon.contours.truncate(1);
        let contour = &mut self.polygon.contours[0];
        contour.clear();
        contour.extend(points);
        self.polygon.color = color;
        self.polygon.rule = raster::geometry::FillRule::EvenOdd;
        &self.polygon
    }
}

/// All the memory a frame needs, allocated once.
pub struct Stage {
    target: Framebuffer,
    /// One depth value per pixel, for the Z-buffered entry.
    depth: Vec<i32>,
    scratch: Scratch,
    /// The still scene built last, kept so a still page is built once.
    still: Option<Scene>,
}

impl Default for Stage {
    fn default() -> Self {
        Self::new()
    }
}

impl Stage {
    pub fn new() -> Self {
        let pixels = (SCREEN.width * SCREEN.height) as usize;
        Self { target: Framebuffer::new(SCREEN), depth: vec![0; pixels], scratch: Scratch::new(), still: None }
    }

    /// Draws frame `frame` (modulo `entry.frames`) of `entry` with `method`
    /// onto a black screen. Allocates only when a still page other than the
    /// last one is built.
    pub fn draw(&mut self, entry: &Entry, frame: u32, method: &dyn Method) -> DrawReport {
        let frame = entry.wrap(frame);
        sink::clear(&mut self.target, 0);
        match entry.kind {
            Kind::Still(_) => draw_page(&mut self.still, entry, method, &mut self.target),
            Kind::LamotheRotate => lamothe::draw(frame, method, &mut self.scratch, &mut self.target),
            Kind::WgtGouraud => shaded::gouraud(frame, method, &mut self.scratch, &mut self.target),
            Kind::WgtTexture => shaded::texture(frame, method, &mut self.scratch, &mut self.target),
            Kind::PendletonDepth => {
                let (scratch, depth, target) = (&mut self.scratch, &mut self.depth, &mut self.target);
                shaded::draw(shaded::Shaded::Depth, Modelling::Needed, frame, method, scratch, depth, target)
            }
            Kind::Race => race::draw(frame, method, &mut self.scratch, &mut self.target),
        }
    }

    /// Draws still `entry` with `method` onto `target`, cleared to black
    /// first, as [`Stage::draw`] draws it onto the stage: for a target
    /// other than the stage, such as the screen itself. An animated entry
    /// draws nothing but the black.
    pub fn draw_still<S: SpanSink>(&mut self, entry: &Entry, method: &dyn Method, target: &mut S) -> DrawReport {
        sink::clear(target, 0);
        draw_page(&mut self.still, entry, method, target)
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
        method: &dyn Method,
        modelling: Modelling,
    ) -> Option<DrawReport> {
        let shaded = match entry.kind {
            Kind::WgtGouraud => shaded::Shaded::Gouraud,
            Kind::WgtTexture => shaded::Shaded::Texture,
            Kind::PendletonDepth => shaded::Shaded::Depth,
            Kind::Still(_) | Kind::LamotheRotate | Kind::Race => return None,
        };
        sink::clear(&mut self.target, 0);
        let (scratch, depth, target) = (&mut self.scratch, &mut self.depth, &mut self.target);
        Some(shaded::draw(shaded, modelling, entry.wrap(frame), method, scratch, depth, target))
    }

    /// Draws the labels over the frame (see [`draw_labels`]).
    pub fn label(&mut self, entry: &Entry, frame: u32, method: &dyn Method, cycles: u64) {
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

/// Draws the still page of `entry` with `method` onto `target`, building
/// the page into `built` unless it is the one built last; nothing for an
/// entry that is not a still.
fn draw_page<S: SpanSink>(built: &mut Option<Scene>, entry: &Entry, method: &dyn Method, target: &mut S) -> DrawReport {
    let Kind::Still(page) = entry.kind else { return DrawReport::default() };
    let scene = match built {
        Some(scene) if scene.name == page.name => scene,
        built => built.insert(page.scene()),
    };
    scene.draw(method, target)
}

/// Draws the labels of frame `frame` (modulo `entry.frames`) of `entry`
/// over `target`: the entry and frame number at the top, the method and
/// the cycles its draw took at the bottom.
pub fn draw_labels(target: &mut dyn SpanSink, entry: &Entry, frame: u32, method: &dyn Method, cycles: u64) {
    label::draw_labels(target, entry, entry.wrap(frame), method.info().name, cycles);
}

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

/// What one animation's `draw` puts on a fresh screen with fresh scratch.
#[cfg(test)]
fn drawn_alone(
    draw: fn(u32, &dyn Method, &mut Scratch, &mut Framebuffer) -> DrawReport,
    frame: u32,
    method: &dyn Method,
) -> (Framebuffer, DrawReport) {
    let mut target = Framebuffer::new(SCREEN);
    let report = draw(frame, method, &mut Scratch::new(), &mut target);
    (target, report)
}

#[cfg(test)]
mod tests {
    use alloc::vec::Vec;

    use super::*;
    use raster::methods::exact::Exact;

    fn animations() -> impl Iterator<Item = &'static Entry> {
        ENTRIES_IN_ORDER.iter().filter(|entry| entry.is_animated())
    }

    /// Frame `frame` of `entry` with `method` on `stage`, and its report.
    fn frame_of(stage: &mut Stage, entry: &Entry, frame: u32, method: &dyn Method) -> (Vec<u8>, DrawReport) {
        let report = stage.draw(entry, frame, method);
        (stage.pixels().to_vec(), report)
    }

    #[test]
    fn every_frame_is_a_pure_function_of_its_number_and_the_loop_closes() {
        for entry in animations() {
            let frames: Vec<u32> = (0..entry.frames).step_by(11).collect();
            let mut stage = Stage::new();
            let first: Vec<Vec<u8>> = frames.iter().map(|&f| frame_of(&mut stage, entry, f, &Exact).0).collect();
            // A stage that drew other frames, in another order, draws the
            // same pixels: nothing carries over from one frame to the next.
            let mut other = Stage::new();
            for (&f, pixels) in frames.iter().zip(&first).rev() {
                assert_eq!(&frame_of(&mut other, entry, f, &Exact).0, pixels, "{} frame {f}", entry.name);
            }
            assert_eq!(frame_of(&mut stage, entry, entry.frames, &Exact).0, first[0], "{} does not loop", entry.name);
            assert_ne!(frame_of(&mut stage, entry, 1, &Exact).0, first[0], "{}: frame 1 is frame 0", entry.name);
        }
    }

    #[test]
    fn every_method_draws_every_animation_whole_and_inside_the_screen() {
        let mut stage = Stage::new();
        for entry in animations() {
            for &method in raster::methods::ALL {
                let name = method.info().name;
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

    #[test]
    fn a_still_drawn_onto_another_target_is_the_stage_s_frame_and_an_animation_is_black() {
        let mut stage = Stage::new();
        for entry in ENTRIES_IN_ORDER.iter().filter(|e| !e.is_animated()) {
            let method = entry.method_at(0).method();
            let mut elsewhere = Framebuffer::new(SCREEN);
            // Not black: the still clears its target first.
            sink::clear(&mut elsewhere, 9);
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
        sink::clear(&mut elsewhere, 9);
        assert_eq!(stage.draw_still(rotate, &Exact, &mut elsewhere).polygons, 0);
        assert!(elsewhere.pixels().iter().all(|&p| p == 0));
    }

    #[test]
    fn the_race_gives_every_method_a_turn_and_stills_keep_their_source_s() {
        let race = entry("race").unwrap();
        let turns: Vec<MethodId> = (0..race.frames).map(|f| race.method_at(f)).collect();
        for method in MethodId::ALL {
            assert!(turns.contains(&method), "{method} never races");
        }
        for still in ENTRIES_IN_ORDER.iter().filter(|e| !e.is_animated()) {
            let builtin = builtin::named(still.name).expect("a still is a built-in scene");
            assert_eq!(still.method_at(7), builtin.method, "{}", still.name);
        }
    }

    #[test]
    fn the_palette_keeps_the_vga_default_below_the_ramps_and_ramps_climb() {
        assert_eq!(PALETTE[..usize::from(RAMP_BASE)], VGA_DEFAULT[..usize::from(RAMP_BASE)]);
        for ramp in [Ramp::Red, Ramp::Green, Ramp::Blue, Ramp::Gold] {
            assert_eq!(PALETTE[usize::from(ramp.color(0))], [0, 0, 0]);
            assert_eq!(PALETTE[usize::from(ramp.color(i32::MAX))], ramp.top());
            for level in 1..i32::from(RAMP_LEVELS) {
                let (below, here) =
                    (PALETTE[usize::from(ramp.color(level - 1))], PALETTE[usize::from(ramp.color(level))]);
                assert!((0..3).all(|c| below[c] <= here[c]), "{ramp:?} level {level}");
            }
        }
        assert_eq!(Ramp::Gold.color(-5), Ramp::Gold.color(0));
    }
}
