//! Where the drawing lands on the 320x200 screen: a rectangle of it (the
//! SVG's view box, or the one asked for) scaled to fit, its aspect kept,
//! and centred.

use anyhow::{ensure, Context, Result};
use kurbo::{Affine, Rect, Vec2};
use raster::SCREEN;
use usvg::roxmltree::Document;

use crate::options::ViewBox;

/// usvg's transform as kurbo's: both map (x, y) to (a x + c y + e,
/// b x + d y + f); tiny-skia names a-f `sx`, `ky`, `kx`, `sy`, `tx`, `ty`.
pub(crate) fn affine(transform: usvg::Transform) -> Affine {
    let usvg::Transform { sx, ky, kx, sy, tx, ty } = transform;
    Affine::new([sx, ky, kx, sy, tx, ty].map(f64::from))
}

/// The transform from usvg's coordinates (the SVG's viewport, in which
/// usvg gives every path's absolute transform) to the screen's pixels:
/// `view_box` (in the SVG's user units) if given, else the root's
/// `viewBox`, else the whole viewport, fitted to the screen.
pub(crate) fn to_screen(document: &Document, tree: &usvg::Tree, view_box: Option<ViewBox>) -> Result<Affine> {
    let in_user_units = view_box.or_else(|| own_view_box(document));
    let region = match in_user_units {
        Some(ViewBox { x, y, width, height }) => {
            root_transform(document)?.transform_rect_bbox(Rect::new(x, y, x + width, y + height))
        }
        None => Rect::new(0.0, 0.0, f64::from(tree.size().width()), f64::from(tree.size().height())),
    };
    ensure!(
        region.is_finite() && region.width() > 0.0 && region.height() > 0.0,
        "the view box lands on {region:?} in the SVG's viewport, which has no area to fit to the screen"
    );
    let (width, height) = (f64::from(SCREEN.width), f64::from(SCREEN.height));
    let scale = (width / region.width()).min(height / region.height());
    Ok(Affine::translate(Vec2::new(width / 2.0, height / 2.0))
        * Affine::scale(scale)
        * Affine::translate(-region.center().to_vec2()))
}

/// The root's `viewBox` as usvg reads it: four numbers, the width and
/// height above zero; `None` if it has none or usvg would ignore it.
fn own_view_box(document: &Document) -> Option<ViewBox> {
    let parsed: svgtypes::ViewBox = document.root_element().attribute("viewBox")?.parse().ok()?;
    (parsed.w > 0.0 && parsed.h > 0.0).then_some(ViewBox {
        x: parsed.x,
        y: parsed.y,
        width: parsed.w,
        height: parsed.h,
    })
}

/// The transform usvg puts between the root's user units and its
/// viewport (from `width`, `height`, `viewBox`, `preserveAspectRatio` and
/// a `transform` on the root), which usvg does not expose: read off a
/// path at the user units' origin in an SVG whose root has the same
/// attributes, so that it is usvg's own.
fn root_transform(document: &Document) -> Result<Affine> {
    let root = document.root_element();
    let mut probe = String::from("<svg xmlns=\"http://www.w3.org/2000/svg\"");
    for name in ["width", "height", "viewBox", "preserveAspectRatio", "transform"] {
        if let Some(value) = root.attribute(name) {
            probe.push_str(&format!(" {name}=\"{}\"", escaped(value)));
        }
    }
    probe.push_str("><path d=\"M0 0H1V1z\"/></svg>");
    let tree = usvg::Tree::from_str(&probe, &usvg::Options::default())
        .context("the root <svg>'s size, viewBox and transform do not make a viewport")?;
    first_path(tree.root())
        .map(|path| affine(path.abs_transform()))
        .context("the root <svg>'s size, viewBox and transform leave nothing visible")
}

/// The first path in `group`, depth first.
fn first_path(group: &usvg::Group) -> Option<&usvg::Path> {
    group.children().iter().find_map(|node| match node {
        usvg::Node::Path(path) => Some(path.as_ref()),
        usvg::Node::Group(group) => first_path(group),
        usvg::Node::Image(_) | usvg::Node::Text(_) => None,
    })
}

/// `value` as the text of an attribute in double quotes.
fn escaped(value: &str) -> String {
    value.replace('&', "&amp;").replace('<', "&lt;").replace('"', "&quot;")
}

#[cfg(test)]
mod tests {
    use super::*;
    use kurbo::Point;
    use usvg::roxmltree::ParsingOptions;

    /// Where the screen transform for `svg` (a root's attributes) and
    /// `view_box` takes the user-unit points `points`.
    fn placed(root: &str, view_box: Option<ViewBox>, points: &[(f64, f64)]) -> Result<Vec<(f64, f64)>> {
        let text = format!("<svg xmlns=\"http://www.w3.org/2000/svg\" {root}><path d=\"M0 0h1v1z\"/></svg>");
        let document = Document::parse_with_options(&text, ParsingOptions { allow_dtd: true, ..Default::default() })?;
        let tree = usvg::Tree::from_xmltree(&document, &usvg::Options::default())?;
        let to_screen = to_screen(&document, &tree, view_box)?;
        let to_screen = to_screen * affine(first_path(tree.root()).expect("a path").abs_transform());
        Ok(points.iter().map(|&(x, y)| to_screen * Point::new(x, y)).map(|p| (p.x, p.y)).collect())
    }

    #[test]
    fn the_view_box_fills_the_screen_height_centred_across() {
        // 100x100 user units into 320x200: 200x200 pixels from x = 60.
        let corners = placed("viewBox=\"0 0 100 100\"", None, &[(0.0, 0.0), (100.0, 100.0)]).unwrap();
        assert_eq!(corners, [(60.0, 0.0), (260.0, 200.0)]);
        // A wide one fills the width and is centred down.
        let corners = placed("viewBox=\"-10 -10 640 100\"", None, &[(-10.0, -10.0), (630.0, 90.0)]).unwrap();
        assert_eq!(corners, [(0.0, 75.0), (320.0, 125.0)]);
    }

    #[test]
    fn a_view_box_asked_for_is_in_user_units_whatever_the_viewport() {
        // 24 user units shown at 48 pixels: the view box asked for is in
        // the path's units, not the viewport's.
        let root = "width=\"48\" height=\"48\" viewBox=\"0 0 24 24\"";
        let quarter = Some(ViewBox { x: 12.0, y: 12.0, width: 12.0, height: 12.0 });
        let corners = placed(root, quarter, &[(12.0, 12.0), (24.0, 24.0)]).unwrap();
        assert_eq!(corners, [(60.0, 0.0), (260.0, 200.0)]);
        // With no viewBox, user units are the viewport's.
        let corners = placed("width=\"32\" height=\"20\"", None, &[(0.0, 0.0), (32.0, 20.0)]).unwrap();
        assert_eq!(corners, [(0.0, 0.0), (320.0, 200.0)]);
        // preserveAspectRatio and the root's viewport do not move the view box's own fit.
        let root = "width=\"300\" height=\"100\" viewBox=\"0 0 10 10\" preserveAspectRatio=\"xMinYMin slice\"";
        let corners = placed(root, None, &[(0.0, 0.0), (10.0, 10.0)]).unwrap();
        assert_eq!(corners, [(60.0, 0.0), (260.0, 200.0)]);
    }

    #[test]
    fn a_root_that_shows_nothing_is_refused() {
        let error = placed("viewBox=\"0 0 10 10\" transform=\"scale(0)\"", None, &[]).unwrap_err();
        assert_eq!(error.to_string(), "the root <svg>'s size, viewBox and transform leave nothing visible");
    }

    #[test]
    fn attribute_values_are_escaped_for_the_probe() {
        assert_eq!(escaped("a&b<\"c\">"), "a&amp;b&lt;&quot;c&quot;>");
    }
}
