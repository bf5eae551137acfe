//! The SVG's XML read before usvg converts it, for what usvg would drop
//! without a word: text and images (usvg, built without text layout,
//! leaves text out, and an image it cannot load is left out too), path
//! data, points, transforms and shape sizes that do not parse (usvg draws
//! a path up to its first error and ignores a bad transform) or hold
//! numbers too large for its 32-bit floats (a path whose coordinates
//! overflow is dropped).

use anyhow::{bail, Result};
use usvg::roxmltree::{Document, Node};

/// The SVG namespace. Elements in it or in none are SVG's, as usvg takes
/// them; those of others (an editor's own) are not.
const SVG_NAMESPACE: &str = "http://www.w3.org/2000/svg";

/// The largest number taken in geometry. 32-bit floats hold up to about
/// 3.4e38; below this bound, a path's coordinates (which usvg adds up
/// from relative ones) cannot reach it in any file that fits in memory.
const LARGEST_NUMBER: f64 = 1e30;

/// Elements that cannot become polygons, with why.
const REFUSED: [(&str, &str); 3] = [
    ("text", "text is not drawn; convert it to paths first (in Inkscape: Path > Object to Path)"),
    ("image", "raster images are not drawn"),
    ("foreignObject", "foreign (non-SVG) content is not drawn"),
];

/// Each shape element's size and position attributes.
const SHAPE_LENGTHS: [(&str, &[&str]); 4] = [
    ("rect", &["x", "y", "width", "height", "rx", "ry"]),
    ("circle", &["cx", "cy", "r"]),
    ("ellipse", &["cx", "cy", "rx", "ry"]),
    ("line", &["x1", "y1", "x2", "y2"]),
];

/// The document checked: its root is an `svg` element, and no element is
/// one that would be dropped or holds a bad number; an error naming the
/// first that is, by its tag, its id and its line.
pub(crate) fn check(document: &Document) -> Result<()> {
    let root = document.root_element();
    if !(is_svg(root) && root.tag_name().name() == "svg") {
        let namespace = match root.tag_name().namespace() {
            Some(namespace) if namespace != SVG_NAMESPACE => format!(" in namespace {namespace}"),
            _ => String::new(),
        };
        bail!("not an SVG: the root element is <{}>{namespace}, not SVG's <svg>", root.tag_name().name());
    }
    for element in root.descendants().filter(|node| is_svg(*node)) {
        let tag = element.tag_name().name();
        if let Some((_, why)) = REFUSED.iter().find(|(refused, _)| *refused == tag) {
            bail!("{} cannot be imported: {why}", described(document, element));
        }
        check_numbers(element).map_err(|error| error.context(described(document, element)))?;
    }
    Ok(())
}

/// Whether `node` is an SVG element.
fn is_svg(node: Node) -> bool {
    node.is_element() && matches!(node.tag_name().namespace(), None | Some(SVG_NAMESPACE))
}

/// `<TAG id="ID"> at line L`, for messages.
fn described(document: &Document, element: Node) -> String {
    let line = document.text_pos_at(element.range().start).row;
    match element.attribute("id") {
        Some(id) => format!("<{} id=\"{id}\"> at line {line}", element.tag_name().name()),
        None => format!("<{}> at line {line}", element.tag_name().name()),
    }
}

/// The element's path data, points, transform and shape lengths: each
/// parses whole, and holds only numbers within [`LARGEST_NUMBER`].
fn check_numbers(element: Node) -> Result<()> {
    let tag = element.tag_name().name();
    if let Some(transform) = element.attribute("transform") {
        let Ok(t) = transform.parse::<svgtypes::Transform>() else {
            bail!("bad transform `{transform}`");
        };
        within_range("transform", &[t.a, t.b, t.c, t.d, t.e, t.f])?;
    }
    if let ("path", Some(data)) = (tag, element.attribute("d")) {
        for segment in svgtypes::PathParser::from(data) {
            match segment {
                Ok(segment) => within_range("path data", &numbers_of(segment))?,
                Err(error) => bail!("bad path data: {error}"),
            }
        }
    }
    if let ("polygon" | "polyline", Some(points)) = (tag, element.attribute("points")) {
        let mut count = 0;
        for number in svgtypes::NumberListParser::from(points) {
            match number {
                Ok(number) => within_range("points", &[number])?,
                Err(error) => bail!("bad points: {error}"),
            }
            count += 1;
        }
        if count % 2 == 1 {
            bail!("bad points: an odd number of coordinates ({count})");
        }
    }
    if let Some((_, names)) = SHAPE_LENGTHS.iter().find(|(shape, _)| *shape == tag) {
        for name in *names {
            match element.attribute(*name) {
                None | Some("auto") => {}
                Some(value) => match value.parse::<svgtypes::Length>() {
                    Ok(length) => within_range(name, &[length.number])?,
                    Err(_) => bail!("bad {name} `{value}`"),
                },
            }
        }
    }
    Ok(())
}

/// An error naming `what` if any of `numbers` is beyond [`LARGEST_NUMBER`]
/// (or not a number).
fn within_range(what: &str, numbers: &[f64]) -> Result<()> {
    match numbers.iter().find(|number| !(number.abs() <= LARGEST_NUMBER)) {
        Some(number) => bail!("{what} holds {number:e}, beyond the ±{LARGEST_NUMBER:e} taken"),
        None => Ok(()),
    }
}

/// The numbers of one segment of path data (the arc's flags are not).
fn numbers_of(segment: svgtypes::PathSegment) -> Vec<f64> {
    use svgtypes::PathSegment::*;
    match segment {
        MoveTo { x, y, .. } | LineTo { x, y, .. } | SmoothQuadratic { x, y, .. } => vec![x, y],
        HorizontalLineTo { x, .. } => vec![x],
        VerticalLineTo { y, .. } => vec![y],
        CurveTo { x1, y1, x2, y2, x, y, .. } => vec![x1, y1, x2, y2, x, y],
        SmoothCurveTo { x2, y2, x, y, .. } => vec![x2, y2, x, y],
        Quadratic { x1, y1, x, y, .. } => vec![x1, y1, x, y],
        EllipticalArc { rx, ry, x_axis_rotation, x, y, .. } => vec![rx, ry, x_axis_rotation, x, y],
        ClosePath { .. } => Vec::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn checked(body: &str) -> Result<()> {
        let text = format!("<svg xmlns=\"{SVG_NAMESPACE}\" viewBox=\"0 0 10 10\">\n{body}\n</svg>");
        check(&Document::parse(&text).unwrap())
    }

    fn refusal(body: &str) -> String {
        format!("{:#}", checked(body).unwrap_err())
    }

    #[test]
    fn text_images_and_foreign_content_are_refused_by_tag_id_and_line() {
        let error = refusal("<g>\n<text id=\"title\">Hi</text></g>");
        assert!(error.starts_with("<text id=\"title\"> at line 3 cannot be imported: text is not drawn"), "{error}");
        let error = refusal("<image href=\"photo.png\" width=\"5\" height=\"5\"/>");
        assert_eq!(error, "<image> at line 2 cannot be imported: raster images are not drawn");
        let error = refusal("<foreignObject><div xmlns=\"http://www.w3.org/1999/xhtml\">x</div></foreignObject>");
        assert!(error.starts_with("<foreignObject> at line 2 cannot be imported"), "{error}");
        // The same names in another namespace are not SVG's.
        assert!(checked("<x:text xmlns:x=\"urn:editor\">note</x:text>").is_ok());
    }

    #[test]
    fn the_root_must_be_svg() {
        let error = check(&Document::parse("<html><svg/></html>").unwrap()).unwrap_err().to_string();
        assert_eq!(error, "not an SVG: the root element is <html>, not SVG's <svg>");
        let error = check(&Document::parse("<svg xmlns=\"urn:x\"/>").unwrap()).unwrap_err().to_string();
        assert_eq!(error, "not an SVG: the root element is <svg> in namespace urn:x, not SVG's <svg>");
        let error = check(&Document::parse("<svg><text>no namespace</text></svg>").unwrap()).unwrap_err().to_string();
        assert!(error.starts_with("<text> at line 1 cannot be imported"), "{error}");
    }

    #[test]
    fn bad_or_huge_numbers_in_geometry_are_refused_naming_the_element() {
        let error = refusal("<path id=\"p\" d=\"M 0 0 L NaN 5 L 5 5 Z\"/>");
        assert!(error.starts_with("<path id=\"p\"> at line 2: bad path data: "), "{error}");
        let error = refusal("<path d=\"M 0 0 L 1e31 5 L 5 5 Z\"/>");
        assert_eq!(error, "<path> at line 2: path data holds 1e31, beyond the ±1e30 taken");
        // svgtypes takes no number that overflows a double.
        let error = refusal("<path d=\"M 0 0 L 1e999 5 Z\"/>");
        assert_eq!(error, "<path> at line 2: bad path data: invalid number at position 9");
        let error = refusal("<polygon points=\"0,0 5,0 5\"/>");
        assert_eq!(error, "<polygon> at line 2: bad points: an odd number of coordinates (5)");
        assert!(refusal("<polyline points=\"0,0 5,x\"/>").contains("bad points: "));
        let error = refusal("<g transform=\"scale(2e30)\"/>");
        assert_eq!(error, "<g> at line 2: transform holds 2e30, beyond the ±1e30 taken");
        assert_eq!(refusal("<g transform=\"rotate(nan)\"/>"), "<g> at line 2: bad transform `rotate(nan)`");
        assert_eq!(refusal("<rect width=\"NaN\" height=\"3\"/>"), "<rect> at line 2: bad width `NaN`");
        assert_eq!(refusal("<circle r=\"-1e40\"/>"), "<circle> at line 2: r holds -1e40, beyond the ±1e30 taken");
        assert!(checked("<rect width=\"5\" height=\"50%\" rx=\"auto\"/><path d=\"M0 0h1e30v1z\"/>").is_ok());
    }
}
