//! The SVGs in `tests/svg/` imported and drawn with `exact`, each held to
//! pixels worked out by hand from the SVG's geometry (a pixel's centre
//! is at +0.5), and the bad ones in `tests/svg/bad/` refused.

use std::path::{Path, PathBuf};

use raster::{FillRule, Framebuffer, MethodId, SCREEN};
use scenes::palette::VGA_DEFAULT;
use scenes::{Op, Scene};
use svg_import::{import, import_file, Imported, Options, PaletteChoice, ViewBox};

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/svg").join(name)
}

fn imported(name: &str) -> Imported {
    import_file(&fixture(name), &Options::default()).unwrap_or_else(|error| panic!("{name}: {error:#}"))
}

/// The scene drawn with `exact`, as 6-bit colours by pixel.
struct Drawn {
    pixels: Vec<[u8; 3]>,
}

impl Drawn {
    fn new(scene: &Scene) -> Self {
        let mut framebuffer = Framebuffer::new(SCREEN);
        let report = scene.draw(MethodId::Exact, &mut framebuffer);
        assert_eq!(report.refused, 0, "{:?}", report.first_refusal);
        let dac = scene.dac();
        Self { pixels: framebuffer.pixels().iter().map(|&index| dac[usize::from(index)]).collect() }
    }

    fn at(&self, x: usize, y: usize) -> [u8; 3] {
        self.pixels[y * SCREEN.width as usize + x]
    }

    /// Asserts each pixel `(x, y)` is `colour`.
    fn expect(&self, colour: [u8; 3], pixels: &[(usize, usize)], what: &str) {
        for &(x, y) in pixels {
            assert_eq!(self.at(x, y), colour, "{what}: pixel ({x}, {y})");
        }
    }
}

const BACKGROUND: [u8; 3] = [0, 0, 0];
const RED: [u8; 3] = [63, 0, 0];
const GREEN: [u8; 3] = [0, 63, 0];
const BLUE: [u8; 3] = [0, 0, 63];
const YELLOW: [u8; 3] = [63, 63, 0];
const WHITE: [u8; 3] = [63, 63, 63];
const MAGENTA: [u8; 3] = [63, 0, 63];

fn polygons(scene: &Scene) -> Vec<&raster::Polygon> {
    scene.polygons().collect()
}

#[test]
fn transforms_move_scale_turn_shear_and_nest() {
    let imported = imported("transforms.svg");
    assert_eq!(imported.scene.name, "transforms");
    assert_eq!(imported.scene.ops[0], Op::Clear(0));
    assert!(imported.notes.is_empty(), "{:?}", imported.notes);
    let drawn = Drawn::new(&imported.scene);
    // translate(20 20) scale(3) of a 10x10 square: 20 to 50.
    drawn.expect(RED, &[(20, 20), (49, 49), (35, 20)], "scaled");
    drawn.expect(BACKGROUND, &[(19, 35), (50, 35), (35, 50)], "around the scaled");
    // rotate(45) about (120, 40): a diamond reaching 28.28 from its centre.
    drawn.expect(GREEN, &[(120, 40), (120, 14), (147, 40), (93, 40)], "turned");
    drawn.expect(BACKGROUND, &[(101, 21), (138, 58), (120, 11)], "the square's corners, turned away");
    // matrix(1 0 0.5 1 200 20): row y moves right by y/2.
    drawn.expect(BLUE, &[(238, 21), (255, 58), (203, 21)], "sheared");
    drawn.expect(BACKGROUND, &[(245, 21), (205, 58)], "beside the sheared");
    // translate(0 100) scale(2) of a circle of radius 20 at (30, 30).
    drawn.expect(YELLOW, &[(60, 160), (60, 121), (99, 160), (21, 160)], "nested");
    drawn.expect(BACKGROUND, &[(60, 118), (30, 130), (101, 160)], "outside the nested");
}

#[test]
fn holes_come_from_winding_under_nonzero_and_from_evenodd() {
    let imported = imported("holes.svg");
    let scene = &imported.scene;
    let rules: Vec<FillRule> = polygons(scene).iter().map(|polygon| polygon.rule).collect();
    assert_eq!(rules, [FillRule::NonZero, FillRule::NonZero, FillRule::EvenOdd]);
    let contours: Vec<usize> = polygons(scene).iter().map(|polygon| polygon.contours.len()).collect();
    assert_eq!(contours, [2, 1, 5], "each subpath a contour");
    let drawn = Drawn::new(scene);
    // 64x40 user units at 5 pixels each: the ring's centre at (100, 100),
    // radii 90 and 50; the dot's radius 20.
    let ring = [55, 40, 8]; // #e0a020
    drawn.expect(ring, &[(100, 30), (100, 170), (30, 100), (155, 100)], "the ring");
    drawn.expect(BACKGROUND, &[(100, 70), (130, 100), (100, 8)], "the ring's hole and outside it");
    drawn.expect([47, 8, 8], &[(100, 100), (100, 81)], "the dot in the hole"); // #c02020
                                                                               // The window's frame, x 210-310 and y 20-180, its panes cut out.
    let frame = [8, 24, 47]; // #2060c0
    drawn.expect(frame, &[(215, 60), (260, 60), (240, 97), (305, 175)], "the frame");
    drawn.expect(BACKGROUND, &[(240, 60), (280, 60), (240, 140), (280, 140)], "the panes");
}

#[test]
fn the_fill_rule_decides_the_stars_middle() {
    let imported = imported("rules.svg");
    let drawn = Drawn::new(&imported.scene);
    drawn.expect(BACKGROUND, &[(80, 100)], "even-odd: the middle pentagon is out");
    drawn.expect(YELLOW, &[(240, 100)], "non-zero: the middle pentagon is in");
    drawn.expect(WHITE, &[(80, 40), (20, 78)], "even-odd: the points are in");
    drawn.expect(YELLOW, &[(240, 40), (180, 78)], "non-zero: the points are in");
}

#[test]
fn an_icon_of_nested_groups_strokes_and_uses() {
    let imported = imported("icon.svg");
    let scene = &imported.scene;
    // The sheet (fill, stroke), the fold, three lines from <use>, the
    // glass (fill, stroke), the handle.
    assert_eq!(polygons(scene).len(), 9);
    assert!(polygons(scene)[2..].iter().all(|polygon| polygon.rule == FillRule::NonZero));
    let drawn = Drawn::new(scene);
    // 24 user units over 200 pixels from x = 60: a unit is 25/3 pixels.
    let ink = [13, 13, 13]; // #333333, inherited from the outer group
    drawn.expect(ink, &[(150, 83), (150, 108)], "the first two lines");
    let sheet = [59, 59, 59]; // #f0f0f0
    drawn.expect(sheet, &[(150, 95), (110, 60)], "the sheet between them");
    // The third line is scaled by a quarter across, its stroke with it:
    // it ends at x = 7 + 2 units, its round cap a quarter as long, at 9.19
    // units (136.6 pixels), not 9.75.
    drawn.expect(ink, &[(130, 133), (135, 133)], "the third line");
    drawn.expect(sheet, &[(139, 133)], "past the third line's end");
    // The lens at (15, 15) units, (185, 125) pixels: white glass, a red
    // rim 2 units wide round a radius of 3.5.
    let rim = [47, 12, 12]; // #c03030
    drawn.expect(WHITE, &[(185, 125)], "the glass");
    drawn.expect(rim, &[(185, 96), (214, 125)], "the rim");
    drawn.expect(rim, &[(230, 170)], "the handle");
    drawn.expect(ink, &[(101, 175)], "the sheet's outline (a round join)");
}

#[test]
fn strokes_keep_their_width_caps_dashes_and_joins() {
    let imported = imported("strokes.svg");
    let drawn = Drawn::new(&imported.scene);
    // Butt caps end at the path's ends; square caps 5 beyond; round caps
    // round off.
    drawn.expect(RED, &[(40, 25), (279, 34), (160, 30)], "butt");
    drawn.expect(BACKGROUND, &[(39, 30), (280, 30), (160, 24), (160, 35)], "beyond the butt");
    drawn.expect(GREEN, &[(35, 60), (284, 60), (35, 55)], "square");
    drawn.expect(BACKGROUND, &[(34, 60), (285, 60)], "beyond the square");
    drawn.expect(BLUE, &[(36, 90), (36, 86)], "round");
    drawn.expect(BACKGROUND, &[(35, 85), (36, 85)], "the round cap's corner");
    // Dashes of 20 with gaps of 10 from x = 40.
    drawn.expect(WHITE, &[(40, 120), (59, 120), (70, 120), (269, 120)], "the dashes");
    drawn.expect(BACKGROUND, &[(60, 120), (69, 120), (90, 120), (270, 120), (279, 120)], "the gaps");
    // A right angle at (80, 150) and (240, 150): the miter reaches 7.07
    // above it, the bevel cuts it at 3.54.
    drawn.expect(YELLOW, &[(80, 144)], "the miter's point");
    drawn.expect(BACKGROUND, &[(240, 144)], "cut by the bevel");
    drawn.expect(MAGENTA, &[(240, 148)], "below the bevel");
    // The same angle at (160, 155) with a miter limit of 1: bevelled.
    drawn.expect(BACKGROUND, &[(160, 150)], "the miter past its limit");
    drawn.expect([0, 63, 63], &[(160, 153)], "below the limited miter's bevel");
}

#[test]
fn every_basic_shape_styles_and_paint_order() {
    let imported = imported("shapes.svg");
    let drawn = Drawn::new(&imported.scene);
    drawn.expect(WHITE, &[(10, 8), (99, 11)], "the line's stroke, 4 wide");
    drawn.expect(BACKGROUND, &[(10, 7), (100, 10)], "beside the line");
    drawn.expect(GREEN, &[(60, 60), (21, 60), (60, 41)], "the ellipse");
    drawn.expect(BACKGROUND, &[(60, 39), (30, 45)], "outside the ellipse");
    drawn.expect([63, 32, 0], &[(150, 40)], "the polygon, orange from the style sheet");
    drawn.expect(YELLOW, &[(30, 160)], "the path, yellow from its style attribute");
    // paint-order="stroke": the stroke first, the fill over its inner half.
    let polygons = polygons(&imported.scene);
    assert_eq!([polygons[3].contours.len(), polygons[4].contours.len()], [2, 1], "the stroke, then the fill");
    drawn.expect(RED, &[(210, 10), (219, 50), (289, 89)], "the stroke's outer half");
    drawn.expect(BLUE, &[(220, 20), (229, 50), (279, 79)], "the fill over the stroke's inner half");
}

#[test]
fn what_is_ignored_or_drawn_otherwise_is_noted() {
    let imported = imported("ignored.svg");
    assert_eq!(
        imported.notes,
        [
            "clip paths ignored, drawn unclipped: group #clipped",
            "masks ignored, drawn unmasked: group #masked",
            "filters ignored: group #blurred",
            "blend modes ignored, drawn normally: group #multiplied",
            "opacity 0, not drawn: the fill of shape #invisible",
            "opacity below 1, drawn opaque: the fill of shape 6 (no id) at 0.25; the stroke of shape 6 (no id) at 0.50",
            "miter-clip joins drawn as miter joins: shape 6 (no id)",
            "1 of the 6 polygons are black, the background's colour: they show only where they cover others",
        ]
    );
    let drawn = Drawn::new(&imported.scene);
    // The clip path would leave only x < 50 of the red square.
    drawn.expect(RED, &[(10, 10), (89, 89)], "unclipped");
    drawn.expect(BACKGROUND, &[(150, 150)], "the invisible square is not drawn");
}

#[test]
fn a_paints_opacity_is_its_own_times_its_groups() {
    let svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 10 10\"><g opacity=\"0.5\">\
               <g opacity=\"0.5\"><rect id=\"r\" width=\"5\" height=\"5\" fill-opacity=\"0.5\"/></g></g></svg>";
    let imported = import("x", svg.as_bytes(), &Options::default()).unwrap();
    assert_eq!(imported.notes[0], "opacity below 1, drawn opaque: the fill of shape #r at 0.12");
}

#[test]
fn strokes_too_wide_or_too_finely_dashed_are_refused() {
    let svg = |stroke: &str| {
        format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 320 200\">\
             <path id=\"s\" d=\"M10 10 H310\" stroke=\"#fff\" {stroke}/></svg>"
        )
    };
    let refusal = |stroke: &str| format!("{:#}", import("x", svg(stroke).as_bytes(), &Options::default()).unwrap_err());
    assert_eq!(
        refusal("stroke-width=\"2e7\""),
        "shape #s's stroke is 20000000 pixels wide once fitted to the screen, past the 16777216 taken"
    );
    // Just under the widest: its outline, 8,000,000 pixels each side of
    // the line, is still within the subpixels' range.
    assert!(import("x", svg("stroke-width=\"1.6e7\"").as_bytes(), &Options::default()).is_ok());
    assert_eq!(
        refusal("stroke-dasharray=\"0.001\""),
        "shape #s's dash pattern cuts its stroke into about 150000 dashes, past the 100000 taken"
    );
    assert!(import("x", svg("stroke-dasharray=\"0.002\"").as_bytes(), &Options::default()).is_ok(), "75000");
}

#[test]
fn gradients_and_patterns_are_drawn_flat_and_named_in_the_notes() {
    let imported = imported("paints.svg");
    assert_eq!(
        imported.notes,
        [
            "gradients drawn flat in the mean of their stops' colours: the fill of shape #sky, linear gradient \
             #sunset of 2 stops, as #800080; the fill of shape #sun, radial gradient #glow of 3 stops, as #ffd555",
            "opacity below 1, drawn opaque: the fill of shape #ground at 0.50",
            "patterns drawn flat in the mean of the colours they paint: the fill of shape #ground, pattern #checks \
             of 2 colours, as #808080",
        ]
    );
    let drawn = Drawn::new(&imported.scene);
    drawn.expect([32, 0, 32], &[(0, 0), (319, 99)], "the sky, red and blue's mean");
    drawn.expect([63, 53, 21], &[(160, 100)], "the sun, its three stops' mean");
    drawn.expect([32, 32, 32], &[(0, 150), (319, 199)], "the ground, grey");
}

#[test]
fn colours_take_their_own_entries_at_6_bits_or_the_vga_default() {
    // Every 6-bit level once in each channel, given at 8 bits.
    let eight_bit = |level: u32| (level * 255 + 31) / 63;
    let mut svg = String::from("<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 64 3\">");
    for level in 0..64 {
        for (row, rgb) in [[level, 0, 0], [0, level, 63 - level], [level, level, level]].iter().enumerate() {
            let [r, g, b] = rgb.map(eight_bit);
            svg.push_str(&format!(
                "<rect x=\"{level}\" y=\"{row}\" width=\"1\" height=\"1\" fill=\"rgb({r},{g},{b})\"/>"
            ));
        }
    }
    svg.push_str("</svg>");
    let own = import("levels", svg.as_bytes(), &Options::default()).unwrap();
    let polygons = polygons(&own.scene);
    assert_eq!(polygons.len(), 192);
    // Distinct colours, entries from 1 in order: (0,0,0) twice (the red
    // row's and the grey row's first) shares one.
    assert_eq!(own.scene.palette.len(), 191);
    let dac = own.scene.dac();
    for (i, polygon) in polygons.iter().enumerate() {
        let level = (i / 3) as u8;
        let expected = [[level, 0, 0], [0, level, 63 - level], [level, level, level]][i % 3];
        assert_eq!(dac[usize::from(polygon.color)], expected, "polygon {i}");
    }
    assert!(own.notes.iter().any(|note| note.starts_with("2 of the 192 polygons are black")), "{:?}", own.notes);
    // The same file written and read back keeps its palette.
    let text = scenes::file::write(&own.scene);
    assert_eq!(scenes::file::parse("levels", &text).unwrap(), own.scene);

    let vga = Options { palette: PaletteChoice::VgaDefault, ..Options::default() };
    let vga = import("levels", svg.as_bytes(), &vga).unwrap();
    assert!(vga.scene.palette.is_empty());
    assert!(!scenes::file::write(&vga.scene).contains("palette"));
    let polygons = self::polygons(&vga.scene);
    // Pure red, the last of the first row, is entry 40; the greys go to
    // the grey ramp or the EGA greys.
    assert_eq!(polygons[63 * 3].color, 40);
    assert_eq!(VGA_DEFAULT[usize::from(polygons[63 * 3 + 2].color)], [63, 63, 63]);
    assert_eq!(VGA_DEFAULT[usize::from(polygons[28 * 3 + 2].color)], [28, 28, 28]);
}

#[test]
fn the_view_box_is_fitted_and_another_can_be_asked_for() {
    // holes.svg is 64x40 units: the whole screen at 5 pixels a unit. Its
    // right half, 32x40 units, fits by its height (5 pixels a unit) and is
    // centred: x from 32 units lands at 160 - 80 = 80.
    let right = Some(ViewBox { x: 32.0, y: 0.0, width: 32.0, height: 40.0 });
    let options = Options { view_box: right, ..Options::default() };
    let imported = import_file(&fixture("holes.svg"), &options).unwrap();
    let drawn = Drawn::new(&imported.scene);
    let frame = [8, 24, 47];
    // The frame's left edge, 42 units, at 80 + 10 * 5 = 130.
    drawn.expect(frame, &[(130, 100), (229, 100)], "the frame");
    drawn.expect(BACKGROUND, &[(129, 100), (230, 100)], "beside the frame");
    // The ring's right edge, 38 units, at 80 + 6 * 5 = 110.
    drawn.expect([55, 40, 8], &[(109, 100)], "the ring's right edge");
    drawn.expect(BACKGROUND, &[(111, 100)], "past the ring");
}

#[test]
fn what_cannot_be_drawn_or_is_bad_is_refused_naming_it() {
    let refusal = |name: &str| format!("{:#}", import_file(&fixture(name), &Options::default()).unwrap_err());
    let cases = [
        ("bad/text.svg", "<text id=\"caption\"> at line 4 cannot be imported: text is not drawn"),
        ("bad/image.svg", "<image id=\"photo\"> at line 4 cannot be imported: raster images are not drawn"),
        ("bad/malformed.svg", "malformed XML: expected 'rect' tag, not 'g' at 5:3"),
        ("bad/nan.svg", "<path id=\"broken\"> at line 3: bad path data: "),
        ("bad/huge.svg", "shape #far reaches 100000000 pixels once fitted to the screen, past the range"),
        ("bad/empty.svg", "nothing to draw: no shape in it is filled or stroked with an area that shows"),
    ];
    for (name, expected) in cases {
        let error = refusal(name);
        let path = fixture(name);
        let head = format!("{}: not imported: {expected}", path.display());
        assert!(error.starts_with(&head), "{name}:\n  {error}\nnot\n  {head}");
    }
    let missing = refusal("no-such.svg");
    assert!(missing.starts_with("failed to read "), "{missing}");
}

#[test]
fn bytes_that_are_not_an_svg_are_refused() {
    let refused = |bytes: &[u8]| format!("{:#}", import("x", bytes, &Options::default()).unwrap_err());
    assert_eq!(refused(&[0x1f, 0x8b, 8, 0]), "a compressed SVG (gzip, .svgz): decompress it first");
    assert!(refused(&[b'<', 0xff, b'>']).starts_with("not UTF-8 text: "));
    assert_eq!(refused(b""), "malformed XML: the document does not have a root node");
    let error = refused(b"<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"0\" height=\"10\"/>");
    assert!(error.starts_with("usvg cannot read it: "), "{error}");
    let tolerance = Options { tolerance: 0.0, ..Options::default() };
    let error = import("x", b"<svg/>", &tolerance).unwrap_err().to_string();
    assert!(error.starts_with("the tolerance must be"), "{error}");
}
