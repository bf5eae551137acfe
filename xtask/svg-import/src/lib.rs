//! `svg_import`: an SVG drawing as a polylab scene. usvg reads the SVG
//! (transforms, groups, `use` and `defs`, styles, shapes as paths); each
//! visible fill and stroke becomes one polygon, in document order over
//! `clear 0`: its subpaths the contours, its fill rule kept (a stroke's
//! outline, from kurbo's stroker, non-zero). Curves are flattened within
//! a tolerance in screen pixels and vertices snapped to the 1/256 grid;
//! the SVG's view box (or one asked for) is fitted to 320x200, its aspect
//! kept, centred. Colours go to a palette of the scene's own at 6 bits a
//! channel, or to the VGA default palette's nearest entries.
//!
//! What cannot be drawn exactly is drawn flat with a note (gradients and
//! patterns in a mean colour, opacity ignored, clip paths, masks and
//! filters left out); what cannot be drawn at all is an error naming the
//! element (text, images), and so is bad input: malformed XML, bad or
//! huge numbers, an empty drawing. `docs/scenes.md` tells it for users.

mod colours;
mod fit;
mod import;
mod notes;
mod options;
mod outline;
mod paint;
mod scan;

pub use import::{import, import_file, Imported};
pub use options::{Options, PaletteChoice, ViewBox};
