//! Scenes: plain data, a list of operations drawn in order.

use alloc::string::String;
use alloc::vec::Vec;

use raster::stores;
use raster::{MethodId, Polygon, Refusal, SpanSink};

use crate::palette::{Palette, VGA_DEFAULT};

/// One drawing step.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Op {
    /// Every pixel to one colour.
    Clear(u8),
    /// One polygon, filled by whichever method draws the scene.
    Fill(Polygon),
}

/// One entry of the DAC a scene sets: its index and its 6-bit red, green
/// and blue levels (0-63, as the VGA's DAC takes them).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PaletteEntry {
    pub index: u8,
    pub rgb: [u8; 3],
}

/// The method a scene with no source of its own (a scene file, an SVG
/// converted, an uploaded scene) is drawn with when none is named: the one
/// home of that default, on both sides of the wire.
pub const FILE_METHOD: MethodId = MethodId::Exact;

/// A named list of operations. Nothing is cleared implicitly: like the
/// book's programs, each operation draws over what the previous ones left.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Scene {
    pub name: String,
    pub ops: Vec<Op>,
    /// The method the scene is drawn with when none is named: its source's
    /// (Listing 38.3 uses Listing 38.1, Listing 40.4 the edge-table filler),
    /// [`FILE_METHOD`] for scene files.
    pub method: MethodId,
    /// The DAC entries the scene sets over the VGA default palette, in
    /// order (a later one for the same index wins); empty for a scene in
    /// the default palette, which every built-in page is.
    pub palette: Vec<PaletteEntry>,
}

/// What drawing a scene did.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct DrawReport {
    pub polygons: usize,
    pub refused: usize,
    /// The first refusal, if any, for error messages.
    pub first_refusal: Option<Refusal>,
}

impl DrawReport {
    /// Counts one polygon and what its fill returned.
    pub fn record(&mut self, fill: Result<(), Refusal>) {
        self.polygons += 1;
        if let Err(refusal) = fill {
            self.refused += 1;
            self.first_refusal.get_or_insert(refusal);
        }
    }
}

impl Scene {
    /// A scene in the VGA default palette.
    pub fn new(name: String, ops: Vec<Op>, method: MethodId) -> Self {
        Self { name, ops, method, palette: Vec::new() }
    }

    /// The method to draw the scene with: the one `named`, else its own.
    pub fn method_or(&self, named: Option<MethodId>) -> MethodId {
        named.unwrap_or(self.method)
    }

    /// The polygons the scene fills, in order.
    pub fn polygons(&self) -> impl Iterator<Item = &Polygon> {
        self.ops.iter().filter_map(|op| match op {
            Op::Fill(polygon) => Some(polygon),
            Op::Clear(_) => None,
        })
    }

    /// The 256 entries the scene is shown in: the VGA default palette with
    /// the scene's own entries set over it.
    pub fn dac(&self) -> Palette {
        let mut dac = VGA_DEFAULT;
        for entry in &self.palette {
            dac[usize::from(entry.index)] = entry.rgb;
        }
        dac
    }

    /// Draws every operation with `method`. A refused polygon is counted and
    /// skipped; the rest of the scene is still drawn. The sink's type is
    /// known here, so `method` fills with its store inlined
    /// ([`MethodId::fill`]).
    pub fn draw<S: SpanSink>(&self, method: MethodId, sink: &mut S) -> DrawReport {
        let mut report = DrawReport::default();
        for op in &self.ops {
            match op {
                Op::Clear(color) => stores::clear(sink, *color),
                Op::Fill(polygon) => report.record(method.fill(polygon, sink)),
            }
        }
        report
    }
}
