//! The `svg` target: any bytes as an SVG, imported (`svg_import`) with the
//! default options. The import never panics, and what it accepts:
//! - is `clear 0`, then polygons, each of contours of three vertices or
//!   more, coloured from the scene's own palette (entries 1 up);
//! - draws with `exact` inside the screen, which refuses none of its
//!   polygons;
//! - written as a scene file (`scenes::file`, which takes coordinates only
//!   within the `i32` range of 1/256 pixels) parses back to the very same
//!   scene.

use raster::{CoverageSink, MethodId, SCREEN};
use scenes::{file, Op};
use svg_import::{import, Options};

pub fn check(data: &[u8]) {
    let Ok(imported) = import("fuzz", data, &Options::default()) else { return };
    let scene = &imported.scene;
    let (first, polygons) = scene.ops.split_first().expect("an imported scene has operations");
    assert_eq!(first, &Op::Clear(0));
    assert!(!polygons.is_empty(), "an empty drawing was accepted");
    for op in polygons {
        let Op::Fill(polygon) = op else { panic!("{op:?} after the clear") };
        assert!(!polygon.contours.is_empty() && polygon.contours.iter().all(|contour| contour.len() >= 3));
        assert!(scene.palette.iter().any(|entry| entry.index == polygon.color), "colour {} unset", polygon.color);
    }
    let mut sink = CoverageSink::new(SCREEN);
    let report = scene.draw(MethodId::Exact, &mut sink);
    assert_eq!(sink.out_of_bounds(), 0, "exact drew outside the screen");
    assert_eq!(report.refused, 0, "exact refused {:?}", report.first_refusal);
    let written = file::write(scene);
    let again = file::parse("fuzz", &written).unwrap_or_else(|error| panic!("written as {written:?}: {error}"));
    assert_eq!(&again, scene, "written as {written:?}");
}

/// The import's test drawings, good and bad.
pub fn seeds() -> Vec<(String, Vec<u8>)> {
    macro_rules! drawing {
        ($name:literal) => {
            ($name.replace('/', "-"), include_bytes!(concat!("../../svg-import/tests/svg/", $name)).to_vec())
        };
    }
    vec![
        drawing!("transforms.svg"),
        drawing!("holes.svg"),
        drawing!("rules.svg"),
        drawing!("icon.svg"),
        drawing!("strokes.svg"),
        drawing!("paints.svg"),
        drawing!("shapes.svg"),
        drawing!("ignored.svg"),
        drawing!("bad/text.svg"),
        drawing!("bad/image.svg"),
        drawing!("bad/malformed.svg"),
        drawing!("bad/nan.svg"),
        drawing!("bad/huge.svg"),
        drawing!("bad/empty.svg"),
    ]
}

/// Elements, attributes, values and path commands of SVG.
pub fn dictionary() -> Vec<String> {
    [
        "<svg xmlns=\"http://www.w3.org/2000/svg\"",
        "</svg>",
        "viewBox=\"",
        "width=\"",
        "height=\"",
        "preserveAspectRatio=\"",
        "<g",
        "</g>",
        "<defs>",
        "</defs>",
        "<path d=\"",
        "<rect",
        "<circle",
        "<ellipse",
        "<line",
        "<polyline",
        "<polygon",
        "points=\"",
        "<use href=\"#",
        "id=\"",
        "transform=\"",
        "translate(",
        "scale(",
        "rotate(",
        "skewX(",
        "matrix(",
        "fill=\"",
        "fill-rule=\"evenodd\"",
        "fill-opacity=\"",
        "opacity=\"",
        "stroke=\"",
        "stroke-width=\"",
        "stroke-linecap=\"",
        "stroke-linejoin=\"",
        "stroke-dasharray=\"",
        "stroke-miterlimit=\"",
        "round",
        "square",
        "bevel",
        "miter-clip",
        "none",
        "url(#",
        "<linearGradient",
        "<radialGradient",
        "<stop offset=\"",
        "stop-color=\"",
        "<pattern",
        "<clipPath",
        "clip-path=\"",
        "style=\"",
        "<text",
        "<image",
        "/>",
        ">",
        "\"",
        "M",
        "L",
        "H",
        "V",
        "C",
        "S",
        "Q",
        "T",
        "A",
        "Z",
        "#",
        "e29",
        "-",
        ".",
    ]
    .map(String::from)
    .into()
}
