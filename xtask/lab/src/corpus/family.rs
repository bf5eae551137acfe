//! What a family is: its group, the axis it sweeps, its polygons and
//! tilings; and each family's own seeded generator.

use std::ops::Range;

use rand::SeedableRng;
use rand_pcg::Pcg64Mcg;
use raster::Polygon;

/// How a family is read in the report and the charts.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Group {
    /// The demo scenes of `raster::scenes`.
    Scene,
    /// Random polygons of one kind: everyday work.
    Random,
    /// Meshes that tile the screen exactly once under the exact rule.
    Tiling,
    /// Sweeps and hostile input: where methods break.
    Stress,
    /// Shapes no one here drew: a real font's glyphs, a real icon set.
    Real,
    /// The polygons of a scene the user gave (`lab --scene`), in place of
    /// the corpus.
    UserScene,
}

impl Group {
    /// The demo scenes, random polygons, tilings, real shapes and the
    /// user's: the work a program does every day, where speed and accuracy
    /// are weighed together.
    pub const fn is_everyday(self) -> bool {
        matches!(self, Group::Scene | Group::Random | Group::Tiling | Group::Real | Group::UserScene)
    }
}

/// What a sweep varies.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Axis {
    /// Rotation in degrees.
    Angle,
    /// Polygon area in square pixels.
    Area,
    /// Vertex count.
    Vertices,
    /// log2 of the largest coordinate magnitude, in subpixels.
    Magnitude,
}

impl Axis {
    /// Whether each value of the axis gets its own timing (the scaling
    /// chart's time against area and vertex count).
    pub const fn timed_per_value(self) -> bool {
        matches!(self, Axis::Area | Axis::Vertices)
    }

    pub const fn label(self) -> &'static str {
        match self {
            Axis::Angle => "rotation (degrees)",
            Axis::Area => "area (px²)",
            Axis::Vertices => "vertices",
            Axis::Magnitude => "log2 coordinate magnitude (subpixels)",
        }
    }
}

/// The swept value of every polygon of a family, in polygon order.
#[derive(Clone, Debug, PartialEq)]
pub struct Sweep {
    pub axis: Axis,
    pub values: Vec<f64>,
}

impl Sweep {
    /// Consecutive runs of polygons sharing one value: `(value, range)`.
    pub fn runs(&self) -> Vec<(f64, Range<usize>)> {
        let mut runs: Vec<(f64, Range<usize>)> = Vec::new();
        for (i, &value) in self.values.iter().enumerate() {
            match runs.last_mut() {
                Some((v, range)) if *v == value => range.end = i + 1,
                _ => runs.push((value, i..i + 1)),
            }
        }
        runs
    }
}

/// One family of polygons.
#[derive(Clone, Debug, PartialEq)]
pub struct Family {
    pub name: &'static str,
    pub group: Group,
    pub description: &'static str,
    pub polygons: Vec<Polygon>,
    /// Runs of polygons that together tile a region exactly once under the
    /// exact rule; overdraw and gaps are counted per tiling. Empty when the
    /// family does not tile.
    pub tilings: Vec<Range<usize>>,
    pub sweep: Option<Sweep>,
}

/// The corpus seed. Changing it changes every family.
pub const SEED: u64 = 0x1AB_5EED;

/// The generator for the family called `name`.
pub(super) fn rng_for(name: &str) -> Pcg64Mcg {
    // FNV-1a: a stable hash, unlike `std`'s, so seeds never move.
    let hash = name.bytes().fold(0xcbf2_9ce4_8422_2325u64, |h, b| (h ^ u64::from(b)).wrapping_mul(0x100_0000_01b3));
    Pcg64Mcg::seed_from_u64(SEED ^ hash)
}

pub(super) fn random_family(
    name: &'static str,
    group: Group,
    description: &'static str,
    count: usize,
    make: fn(&mut Pcg64Mcg) -> Polygon,
) -> Family {
    let mut rng = rng_for(name);
    Family {
        name,
        group,
        description,
        polygons: (0..count).map(|_| make(&mut rng)).collect(),
        tilings: vec![],
        sweep: None,
    }
}
