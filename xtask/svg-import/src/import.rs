//! The import itself: the SVG checked, converted by usvg, walked in
//! document order into polygons, and their colours given indices.

use std::path::Path;

use anyhow::{anyhow, bail, Context, Result};
use kurbo::{Affine, BezPath};
use raster::{FillRule, Point, Polygon};
use scenes::{Op, Scene, FILE_METHOD};
use usvg::roxmltree::{Document, ParsingOptions};
use usvg::{Group, Node, Opacity, Paint, PaintOrder};

use crate::colours;
use crate::fit::{affine, to_screen};
use crate::notes::{element_name, Notes};
use crate::options::{Options, PaletteChoice};
use crate::outline::{bez_path, filled, stroked};
use crate::paint::{flat_colour, Rgb};
use crate::scan;

/// An SVG as a scene, and what could not be drawn as the SVG asks.
#[derive(Clone, Debug)]
pub struct Imported {
    /// `clear 0`, then one polygon per fill and per stroke in document
    /// order, drawn with `exact`, in the palette asked for.
    pub scene: Scene,
    /// One line per kind of thing drawn otherwise than the SVG asks (a
    /// gradient made flat, an opacity ignored, colours merged, ...),
    /// naming the elements.
    pub notes: Vec<String>,
}

/// The SVG `svg` as the scene `name`. An error, and no scene, for what
/// is not an SVG or not well-formed, for text, images and foreign
/// content, for path data, points, transforms or shape sizes that do not
/// parse or hold numbers past ±1e30, for a coordinate outside the
/// subpixels' `i32` range once fitted to the screen, and for a drawing
/// with nothing to fill.
pub fn import(name: &str, svg: &[u8], options: &Options) -> Result<Imported> {
    options.check()?;
    let text = text_of(svg)?;
    let document = Document::parse_with_options(text, ParsingOptions { allow_dtd: true, ..ParsingOptions::default() })
        .map_err(|error| anyhow!("malformed XML: {error}"))?;
    scan::check(&document)?;
    let tree = usvg::Tree::from_xmltree(&document, &usvg::Options::default())
        .map_err(|error| anyhow!("usvg cannot read it: {error}"))?;
    let mut drawing = Drawing {
        to_screen: to_screen(&document, &tree, options.view_box)?,
        tolerance: options.tolerance,
        shapes: 0,
        fills: Vec::new(),
        notes: Notes::default(),
    };
    drawing.group(tree.root(), 1.0)?;
    if drawing.fills.is_empty() {
        bail!("nothing to draw: no shape in it is filled or stroked with an area that shows");
    }
    let colours: Vec<Rgb> = drawing.fills.iter().map(|fill| fill.colour).collect();
    let indexed = match options.palette {
        PaletteChoice::Own => colours::own(&colours),
        PaletteChoice::VgaDefault => colours::vga_default(&colours),
    };
    let mut ops = vec![Op::Clear(0)];
    for (fill, &color) in drawing.fills.into_iter().zip(&indexed.indices) {
        ops.push(Op::Fill(Polygon { contours: fill.contours, color, rule: fill.rule }));
    }
    let mut scene = Scene::new(name.to_string(), ops, FILE_METHOD);
    scene.palette = indexed.palette;
    let mut notes = drawing.notes.lines();
    notes.extend(indexed.notes);
    Ok(Imported { scene, notes })
}

/// The SVG file at `path` as a scene named after the file's stem; errors
/// name the file.
pub fn import_file(path: &Path, options: &Options) -> Result<Imported> {
    let svg = std::fs::read(path).with_context(|| format!("failed to read {}", path.display()))?;
    let name = path.file_stem().map_or_else(|| "svg".to_string(), |stem| stem.to_string_lossy().into_owned());
    import(&name, &svg, options).with_context(|| format!("{}: not imported", path.display()))
}

/// The bytes as the XML's text: UTF-8, without a byte order mark.
fn text_of(svg: &[u8]) -> Result<&str> {
    if svg.starts_with(&[0x1f, 0x8b]) {
        bail!("a compressed SVG (gzip, .svgz): decompress it first");
    }
    let text = std::str::from_utf8(svg).map_err(|error| anyhow!("not UTF-8 text: {error}"))?;
    Ok(text.strip_prefix('\u{feff}').unwrap_or(text))
}

/// One polygon to be: its contours on the screen, its rule, its colour.
struct Fill {
    contours: Vec<Vec<Point>>,
    rule: FillRule,
    colour: Rgb,
}

/// One visible path on its way to polygons: its outline in its own
/// coordinates, the transform from them to the screen, its groups'
/// opacity and its name in notes and errors.
struct Shape<'a> {
    path: &'a usvg::Path,
    outline: BezPath,
    to_screen: Affine,
    opacity: f32,
    name: String,
}

/// The walk through usvg's tree.
struct Drawing {
    to_screen: Affine,
    tolerance: f64,
    /// Shapes met so far, visible ones, to name those with no id.
    shapes: usize,
    fills: Vec<Fill>,
    notes: Notes,
}

impl Drawing {
    /// Everything in `group`, in document order, at `opacity` (its
    /// ancestors'), noting what of the group itself is not drawn.
    fn group(&mut self, group: &Group, opacity: f32) -> Result<()> {
        let next_shape = self.shapes + 1;
        let name = || match group.id() {
            "" => format!("group (no id) at shape {next_shape}"),
            id => format!("group #{id}"),
        };
        if group.clip_path().is_some() {
            self.notes.add("clip paths ignored, drawn unclipped", name());
        }
        if group.mask().is_some() {
            self.notes.add("masks ignored, drawn unmasked", name());
        }
        if !group.filters().is_empty() {
            self.notes.add("filters ignored", name());
        }
        if group.blend_mode() != usvg::BlendMode::Normal {
            self.notes.add("blend modes ignored, drawn normally", name());
        }
        let opacity = opacity * group.opacity().get();
        for node in group.children() {
            match node {
                Node::Group(child) => self.group(child, opacity)?,
                Node::Path(path) => self.path(path, opacity)?,
                Node::Image(_) | Node::Text(_) => {
                    bail!(
                        "{}: images and text are not drawn",
                        element_name("image or text", node.id(), self.shapes + 1)
                    )
                }
            }
        }
        Ok(())
    }

    /// The path's fill and stroke, in its paint order, at `opacity` (its
    /// groups').
    fn path(&mut self, path: &usvg::Path, opacity: f32) -> Result<()> {
        if !path.is_visible() {
            return Ok(());
        }
        self.shapes += 1;
        let shape = Shape {
            path,
            outline: bez_path(path.data()),
            to_screen: self.to_screen * affine(path.abs_transform()),
            opacity,
            name: element_name("shape", path.id(), self.shapes),
        };
        let fill_first = path.paint_order() == PaintOrder::FillAndStroke;
        for filling in [fill_first, !fill_first] {
            if filling {
                self.fill(&shape)?;
            } else {
                self.stroke(&shape)?;
            }
        }
        Ok(())
    }

    fn fill(&mut self, shape: &Shape) -> Result<()> {
        let Some(fill) = shape.path.fill() else { return Ok(()) };
        let Some(colour) = self.colour(shape, "fill", fill.paint(), fill.opacity()) else { return Ok(()) };
        let rule = match fill.rule() {
            usvg::FillRule::NonZero => FillRule::NonZero,
            usvg::FillRule::EvenOdd => FillRule::EvenOdd,
        };
        let contours = filled(&shape.outline, shape.to_screen, self.tolerance, &shape.name)?;
        self.push(contours, rule, colour);
        Ok(())
    }

    fn stroke(&mut self, shape: &Shape) -> Result<()> {
        let Some(stroke) = shape.path.stroke() else { return Ok(()) };
        let Some(colour) = self.colour(shape, "stroke", stroke.paint(), stroke.opacity()) else { return Ok(()) };
        if stroke.linejoin() == usvg::LineJoin::MiterClip {
            self.notes.add("miter-clip joins drawn as miter joins", shape.name.clone());
        }
        let contours = stroked(&shape.outline, stroke, shape.to_screen, self.tolerance, &shape.name)?;
        self.push(contours, FillRule::NonZero, colour);
        Ok(())
    }

    /// The flat colour of the shape's `part` (fill or stroke), painted
    /// with `paint` at `opacity` times the shape's groups'.
    fn colour(&mut self, shape: &Shape, part: &str, paint: &Paint, opacity: Opacity) -> Option<Rgb> {
        let what = format!("the {part} of {}", shape.name);
        flat_colour(paint, opacity.get() * shape.opacity, &what, &mut self.notes)
    }

    /// A polygon of `contours`, unless it has none (nothing of it covers
    /// an area).
    fn push(&mut self, contours: Vec<Vec<Point>>, rule: FillRule, colour: Rgb) {
        if !contours.is_empty() {
            self.fills.push(Fill { contours, rule, colour });
        }
    }
}
