//! The real shapes: outlines no one here drew. The glyphs of a real font
//! (DejaVu Sans, embedded by the `dejavu` crate and read by `ab_glyph`)
//! and the icons of a real icon set (Bootstrap Icons, packaged as SVG path
//! data by the `icondata_bs` crate), their curves flattened to polygons by
//! `kurbo` within [`TOLERANCE`], each placed on the screen at a size and
//! position drawn from the family's generator.
//!
//! A glyph is one polygon, every contour of its outline (holes and all)
//! filled by the non-zero rule, as TrueType outlines are. An icon's paths
//! are drawn one after the other, each a polygon of its own with the fill
//! rule the path asks for (non-zero unless `fill-rule="evenodd"`): one
//! `<path>` element is one polygon.

use std::ops::RangeInclusive;
use std::sync::OnceLock;

use ab_glyph::{Font, FontRef, OutlineCurve};
use kurbo::{Affine, BezPath, PathEl, Point as KPoint};
use rand::RngExt;
use rand_pcg::Pcg64Mcg;
use raster::{FillRule, Point, Polygon};

use super::family::{rng_for, Family, Group};
use super::shapes::{color, snap, HEIGHT, WIDTH};

/// How far a flattened curve may stray from the curve, in pixels.
pub const TOLERANCE: f64 = 0.1;

/// The characters glyphs are drawn from: letters, digits and signs, many
/// with holes (a, e, g, B, 8, @, %, &) and some with diacritics.
const CHARACTERS: &str = "AaBbCcDdEeFfGgHhIiJjKkLlMmNnOoPpQqRrSsTtUuVvWwXxYyZz0123456789@&%$#?!§ßÆØÅéñçü";

/// The glyphs of DejaVu Sans, `count` of them, each of a size in pixels
/// to the em drawn from `sizes`.
pub(super) fn glyphs(
    name: &'static str,
    description: &'static str,
    count: usize,
    sizes: RangeInclusive<f64>,
) -> Family {
    let mut rng = rng_for(name);
    let font = font();
    let characters: Vec<char> = CHARACTERS.chars().collect();
    let polygons = (0..count)
        .map(|_| {
            let character = characters[rng.random_range(0..characters.len())];
            let size = rng.random_range(sizes.clone());
            let origin = place(&mut rng, size);
            glyph(font, character, size, origin, color(&mut rng))
        })
        .collect();
    Family { name, group: Group::Real, description, polygons, tilings: vec![], sweep: None }
}

/// The icons' paths, `count` polygons, each icon of a size in pixels
/// drawn from `sizes` (its 16-unit view box scaled to it).
pub(super) fn icons(name: &'static str, description: &'static str, count: usize, sizes: RangeInclusive<f64>) -> Family {
    let mut rng = rng_for(name);
    let mut polygons = Vec::with_capacity(count);
    while polygons.len() < count {
        let icon = ICONS[rng.random_range(0..ICONS.len())];
        let size = rng.random_range(sizes.clone());
        let (x, y) = place(&mut rng, size);
        let color = color(&mut rng);
        let to_screen = Affine::translate((x, y - size)) * Affine::scale(size / 16.0);
        for (path, rule) in icon_paths(icon.data) {
            if polygons.len() < count {
                polygons.push(flattened(&(to_screen * path), rule, color));
            }
        }
    }
    Family { name, group: Group::Real, description, polygons, tilings: vec![], sweep: None }
}

/// Where a shape of `size` pixels goes: the left end of its baseline
/// (its lower left corner), so that most of it is on the screen.
fn place(rng: &mut Pcg64Mcg, size: f64) -> (f64, f64) {
    (rng.random_range(0.0..(WIDTH - size * 0.8).max(1.0)), rng.random_range(size.min(HEIGHT - 1.0)..HEIGHT))
}

/// DejaVu Sans, read once.
fn font() -> &'static FontRef<'static> {
    static FONT: OnceLock<FontRef<'static>> = OnceLock::new();
    FONT.get_or_init(|| FontRef::try_from_slice(dejavu::sans::regular()).expect("the embedded DejaVu Sans reads"))
}

/// The outline of `character` at `size` pixels to the em, its baseline's
/// left end at `origin`, as one polygon filled by the non-zero rule.
pub(super) fn glyph(font: &FontRef, character: char, size: f64, origin: (f64, f64), color: u8) -> Polygon {
    let scale = size / f64::from(font.units_per_em().unwrap_or(2048.0));
    let outline = font.outline(font.glyph_id(character)).map(|o| o.curves).unwrap_or_default();
    // Font units, y up, to pixels on the screen, y down.
    let at = |p: ab_glyph::Point| KPoint::new(origin.0 + f64::from(p.x) * scale, origin.1 - f64::from(p.y) * scale);
    let mut path = BezPath::new();
    let mut last: Option<ab_glyph::Point> = None;
    for curve in outline {
        let (start, end) = match curve {
            OutlineCurve::Line(a, b) | OutlineCurve::Quad(a, _, b) | OutlineCurve::Cubic(a, _, _, b) => (a, b),
        };
        // A curve that does not start where the last ended starts a contour.
        if last != Some(start) {
            if last.is_some() {
                path.close_path();
            }
            path.move_to(at(start));
        }
        match curve {
            OutlineCurve::Line(_, b) => path.line_to(at(b)),
            OutlineCurve::Quad(_, c, b) => path.quad_to(at(c), at(b)),
            OutlineCurve::Cubic(_, c, d, b) => path.curve_to(at(c), at(d), at(b)),
        }
        last = Some(end);
    }
    if last.is_some() {
        path.close_path();
    }
    flattened(&path, FillRule::NonZero, color)
}

/// `path` flattened within [`TOLERANCE`] and snapped to the subpixel grid,
/// one contour per subpath, repeated vertices dropped.
fn flattened(path: &BezPath, rule: FillRule, color: u8) -> Polygon {
    let mut contours: Vec<Vec<Point>> = Vec::new();
    kurbo::flatten(path, TOLERANCE, |element| match element {
        PathEl::MoveTo(p) => contours.push(vec![snap(p.x, p.y)]),
        PathEl::LineTo(p) => {
            let q = snap(p.x, p.y);
            if let Some(contour) = contours.last_mut().filter(|c| c.last() != Some(&q)) {
                contour.push(q);
            }
        }
        _ => {}
    });
    for contour in &mut contours {
        if contour.len() > 1 && contour.first() == contour.last() {
            contour.pop();
        }
    }
    contours.retain(|c| c.len() >= 3);
    Polygon { contours, color, rule }
}

/// The paths of an icon's SVG elements (all `<path>`: [`ICONS`] holds no
/// other kind), each with its fill rule.
fn icon_paths(svg: &str) -> Vec<(BezPath, FillRule)> {
    svg.split("<path")
        .skip(1)
        .filter_map(|element| {
            let element = &element[..element.find("/>")?];
            let d = attribute(element, "d")?;
            let rule = match attribute(element, "fill-rule") {
                Some("evenodd") => FillRule::EvenOdd,
                _ => FillRule::NonZero,
            };
            Some((BezPath::from_svg(d).ok()?, rule))
        })
        .collect()
}

/// The value of attribute `name` of an element's text.
fn attribute<'a>(element: &'a str, name: &str) -> Option<&'a str> {
    let key = format!(" {name}=\"");
    let start = element.find(&key)? + key.len();
    Some(&element[start..start + element[start..].find('"')?])
}

/// The icons drawn: common ones of user interfaces, each made of paths
/// alone.
const ICONS: [&icondata_core::IconData; 30] = [
    icondata_bs::BsHouseFill,
    icondata_bs::BsGearFill,
    icondata_bs::BsSearch,
    icondata_bs::BsHeartFill,
    icondata_bs::BsStarFill,
    icondata_bs::BsBellFill,
    icondata_bs::BsEnvelopeFill,
    icondata_bs::BsPersonFill,
    icondata_bs::BsTrashFill,
    icondata_bs::BsFolderFill,
    icondata_bs::BsCameraFill,
    icondata_bs::BsCloudFill,
    icondata_bs::BsLockFill,
    icondata_bs::BsCartFill,
    icondata_bs::BsCalendarFill,
    icondata_bs::BsClockFill,
    icondata_bs::BsDownload,
    icondata_bs::BsPlayFill,
    icondata_bs::BsWifi,
    icondata_bs::BsGeoAltFill,
    icondata_bs::BsPrinterFill,
    icondata_bs::BsPencilFill,
    icondata_bs::BsScissors,
    icondata_bs::BsShareFill,
    icondata_bs::BsTrophyFill,
    icondata_bs::BsSunFill,
    icondata_bs::BsGithub,
    icondata_bs::BsPuzzleFill,
    icondata_bs::BsBugFill,
    icondata_bs::BsGlobe,
];

#[cfg(test)]
mod tests {
    use super::*;
    use raster::{classify, Class};

    /// 'o' at 64 px: two contours (the ring and its hole, wound against
    /// each other), their edges within the tolerance of round.
    #[test]
    fn a_glyph_has_its_holes_and_the_non_zero_rule() {
        let o = glyph(font(), 'o', 64.0, (100.0, 150.0), 7);
        assert_eq!(o.contours.len(), 2);
        assert_eq!(o.rule, FillRule::NonZero);
        assert!(o.contours.iter().all(|c| c.len() > 12), "{:?}", o.contours.iter().map(Vec::len).collect::<Vec<_>>());
        assert_eq!(classify(&o), Class::Complex);
        let b = glyph(font(), 'B', 8.0, (10.0, 20.0), 7);
        assert_eq!(b.contours.len(), 3);
        // Between the baseline and an em above it.
        let ys: Vec<i32> = b.contours.iter().flatten().map(|p| p.y).collect();
        assert!(ys.iter().all(|y| ((20 - 8) * 256..=20 * 256).contains(y)), "{ys:?}");
    }

    #[test]
    fn an_icon_paths_rule_is_its_own() {
        let paths = icon_paths(
            r#"<path fill-rule="evenodd" d="M0 0h4v4H0z" />
<path d="M5 5h1v1H5z" />"#,
        );
        assert_eq!(paths.iter().map(|(_, rule)| *rule).collect::<Vec<_>>(), [FillRule::EvenOdd, FillRule::NonZero]);
        assert_eq!(attribute(r#"<path d="M1 2" fill="x""#, "fill"), Some("x"));
    }

    #[test]
    fn every_icon_gives_paths() {
        for icon in ICONS {
            let paths = icon_paths(icon.data);
            assert!(!paths.is_empty(), "{}", icon.data);
            assert_eq!(icon.data.matches('<').count(), paths.len(), "only paths: {}", icon.data);
        }
    }

    #[test]
    fn a_flattened_quarter_circle_stays_within_the_tolerance() {
        let mut path = BezPath::new();
        path.move_to((0.0, 0.0));
        path.line_to((100.0, 0.0));
        path.quad_to((100.0, 100.0), (0.0, 100.0));
        path.close_path();
        let polygon = flattened(&path, FillRule::NonZero, 1);
        let contour = &polygon.contours[0];
        assert!(contour.len() > 10);
        // Every vertex is on the curve (or the straight edges), snapped.
        for p in contour {
            let (x, y) = (f64::from(p.x) / 256.0, f64::from(p.y) / 256.0);
            assert!(x >= -0.01 && y >= -0.01 && x <= 100.01 && y <= 100.01, "({x}, {y})");
        }
    }
}
