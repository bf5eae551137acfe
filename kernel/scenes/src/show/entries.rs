//! The show's entries, in demo order, and what each draws.

use super::pace::STILL_FRAMES;
use super::{lamothe, race, shaded};
use crate::builtin::{self, BuiltinPage};
use raster::MethodId;

/// What an entry draws.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Kind {
    /// A built-in scene, the same on every frame.
    Still(BuiltinPage),
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
    /// A built-in page drawn by every method in turn, on the race's
    /// schedule: real art, where the methods' failures show.
    EveryMethod(BuiltinPage),
}

/// One scene of the show.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Entry {
    pub name: &'static str,
    /// Distinct frames; frame numbers wrap around modulo this. 1 for stills.
    pub frames: u32,
    /// The method of the scene's source.
    pub method: MethodId,
    pub(super) kind: Kind,
}

impl Entry {
    /// A still page: the built-in scene, with its name and its method.
    const fn still(builtin: BuiltinPage) -> Self {
        Self { name: builtin.name, frames: 1, method: builtin.method, kind: Kind::Still(builtin) }
    }

    const fn animation(name: &'static str, frames: u32, method: MethodId, kind: Kind) -> Self {
        Self { name, frames, method, kind }
    }

    /// The built-in page the entry draws, for a still and for a page drawn
    /// by every method in turn; `None` for an animation of the show's own
    /// polygons (all convex).
    pub fn page(&self) -> Option<BuiltinPage> {
        match self.kind {
            Kind::Still(page) | Kind::EveryMethod(page) => Some(page),
            _ => None,
        }
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
    /// source's method, or for the race and the pages drawn by every method
    /// the method whose turn it is.
    pub fn method_at(&self, frame: u32) -> MethodId {
        match self.kind {
            Kind::Race | Kind::EveryMethod(_) => race::method_at(self.wrap(frame)),
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
    Entry::animation("world", race::FRAMES, MethodId::Exact, Kind::EveryMethod(builtin::WORLD)),
];

/// The entry called `name`.
pub fn entry(name: &str) -> Option<&'static Entry> {
    ENTRIES_IN_ORDER.iter().find(|e| e.name == name)
}

#[cfg(test)]
mod tests {
    use alloc::vec::Vec;

    use super::*;

    #[test]
    fn the_race_and_the_world_give_every_method_a_turn_and_stills_keep_their_source_s() {
        for name in ["race", "world"] {
            let entry = entry(name).unwrap();
            let turns: Vec<MethodId> = (0..entry.frames).map(|f| entry.method_at(f)).collect();
            for method in MethodId::ALL {
                assert!(turns.contains(&method), "{method} never has a turn in {name}");
            }
        }
        for still in ENTRIES_IN_ORDER.iter().filter(|e| !e.is_animated()) {
            let builtin = builtin::named(still.name).expect("a still is a built-in scene");
            assert_eq!(still.method_at(7), builtin.method, "{}", still.name);
        }
    }
}
