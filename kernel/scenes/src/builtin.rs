//! The built-in scenes: the sample programs of the seeds, as data, each
//! with the method its source draws it with. This table is the only place
//! that pairs a page with its method; the show's still entries are made
//! from it.

use alloc::string::ToString;
use alloc::vec::Vec;

use raster::{MethodId, Polygon};

use crate::scene::{Op, Scene};

/// One built-in scene: a page of a seed's sample program.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BuiltinPage {
    pub name: &'static str,
    /// The method of the scene's source.
    pub method: MethodId,
    page: Page,
}

/// Which program, and how far into it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Page {
    /// Listing 38.3 up to its n-th keypress.
    Listing38_3(u32),
    /// Listing 40.4 up to its n-th keypress.
    Listing40_4(u32),
    LamotheTriangle,
    WgtTriangle,
    World,
}

impl BuiltinPage {
    const fn new(name: &'static str, method: MethodId, page: Page) -> Self {
        Self { name, method, page }
    }

    /// The scene's operations, built afresh.
    pub fn scene(&self) -> Scene {
        let ops = match self.page {
            Page::Listing38_3(page) => listing_38_3(page),
            Page::Listing40_4(page) => listing_40_4(page),
            Page::LamotheTriangle => lamothe_triangle(),
            Page::WgtTriangle => wgt_triangle(),
            Page::World => world(),
        };
        Scene::new(self.name.to_string(), ops, self.method)
    }
}

pub const ABRASH38_1: BuiltinPage = BuiltinPage::new("abrash38-1", MethodId::AbrashFloat, Page::Listing38_3(1));
pub const ABRASH38_2: BuiltinPage = BuiltinPage::new("abrash38-2", MethodId::AbrashFloat, Page::Listing38_3(2));
pub const ABRASH38_3: BuiltinPage = BuiltinPage::new("abrash38-3", MethodId::AbrashFloat, Page::Listing38_3(3));
pub const ABRASH40_1: BuiltinPage = BuiltinPage::new("abrash40-1", MethodId::AbrashAet, Page::Listing40_4(1));
pub const ABRASH40_2: BuiltinPage = BuiltinPage::new("abrash40-2", MethodId::AbrashAet, Page::Listing40_4(2));
pub const ABRASH40_3: BuiltinPage = BuiltinPage::new("abrash40-3", MethodId::AbrashAet, Page::Listing40_4(3));
pub const ABRASH40_4: BuiltinPage = BuiltinPage::new("abrash40-4", MethodId::AbrashAet, Page::Listing40_4(4));
pub const LAMOTHE_TRIANGLE: BuiltinPage =
    BuiltinPage::new("lamothe-triangle", MethodId::Lamothe, Page::LamotheTriangle);
pub const WGT_TRIANGLE: BuiltinPage = BuiltinPage::new("wgt-triangle", MethodId::Wgt, Page::WgtTriangle);
pub const WORLD: BuiltinPage = BuiltinPage::new("world", MethodId::Exact, Page::World);

/// Every built-in scene, in demo order.
pub const ALL: [BuiltinPage; 10] = [
    ABRASH38_1,
    ABRASH38_2,
    ABRASH38_3,
    ABRASH40_1,
    ABRASH40_2,
    ABRASH40_3,
    ABRASH40_4,
    LAMOTHE_TRIANGLE,
    WGT_TRIANGLE,
    WORLD,
];

/// The built-in scene called `name`.
pub fn named(name: &str) -> Option<&'static BuiltinPage> {
    ALL.iter().find(|builtin| builtin.name == name)
}

/// The built-in scene called `name`, built.
pub fn scene(name: &str) -> Option<Scene> {
    named(name).map(BuiltinPage::scene)
}

/// The land of the world at 1:110m, a real many-vertex shape: 129 polygons
/// of 3 to 1,370 vertices, 6,384 in all, in the VGA default palette's
/// blue (1) and green (2). `art/world.scene`, which `cargo xtask convert`
/// makes from `art/world.svg` (`art/README.md` says where the outlines
/// come from). Drawn with `exact`: no book's method draws it right.
fn world() -> Vec<Op> {
    // The file is checked to parse by this module's tests.
    crate::file::parse("world", include_str!("../art/world.scene")).map_or_else(|_| Vec::new(), |scene| scene.ops)
}

/// Listing 40.4 up to its `page`-th keypress (the book's chapter 40;
/// `docs/scenes.md#chapter-40-sample-program`): the odd/even examples,
/// the rectangle whose hole is cut by a bridge edge traversed in and back
/// out, and the V shapes that tile without overlap. The screen starts
/// black after the mode set and is never cleared.
fn listing_40_4(page: u32) -> Vec<Op> {
    const POLYGON_1: &[(i32, i32)] = &[(0, 0), (100, 150), (320, 0), (0, 200), (220, 50), (320, 200)];
    const POLYGON_2: &[(i32, i32)] =
        &[(0, 0), (320, 0), (320, 200), (0, 200), (0, 0), (50, 50), (270, 50), (270, 150), (50, 150), (50, 50)];
    const POLYGON_3: &[(i32, i32)] = &[
        (0, 0),
        (10, 0),
        (105, 185),
        (260, 30),
        (15, 150),
        (5, 150),
        (5, 140),
        (260, 5),
        (300, 5),
        (300, 15),
        (110, 200),
        (100, 200),
        (0, 10),
    ];
    const POLYGON_4: &[(i32, i32)] = &[(0, 0), (30, -20), (30, 0), (0, 20), (-30, 0), (-30, -20)];

    let fill =
        |points: &[(i32, i32)], offset: (i32, i32), color: u8| Op::Fill(Polygon::from_pixels(points, offset, color));
    let mut ops = Vec::from([Op::Clear(0)]);
    for (shape, color) in [(POLYGON_1, 15), (POLYGON_2, 5), (POLYGON_3, 3)].into_iter().take(page as usize) {
        ops.push(fill(shape, (0, 0), color));
    }
    if page >= 4 {
        for i in 0..5u8 {
            for j in 0..8u8 {
                let offset = (40 + 60 * i32::from(i), 30 + 20 * i32::from(j));
                ops.push(fill(POLYGON_4, offset, 16 + 8 * i + j));
            }
        }
    }
    ops
}

/// LaMothe's example call `Draw_Triangle_2D(100,100, 200,150, 40,200, 30,
/// ...)` (his "Solid Filled Polygons" article; `docs/methods.md`), on the black screen of a mode set.
/// He drew it on a 640x480 screen, where row 200 is in the middle; mode 13h's
/// rows are 0..=199, so here the bottom vertex lies on the clip edge: his
/// y clip (`if (y3>max_clip_y) y3=max_clip_y`) drops the one-pixel line of
/// row 200, and under our convention no pixel centre (y + 0.5) reaches
/// y = 200 anyway, so every method draws the triangle down to row 199.
fn lamothe_triangle() -> Vec<Op> {
    Vec::from([Op::Clear(0), Op::Fill(Polygon::from_pixels(&[(100, 100), (200, 150), (40, 200)], (0, 0), 30))])
}

/// The WGT tutorial's test triangle, (160,30), (50,150), (270,180)
/// (Egerter's WGT tutorial 1; `docs/methods.md`). The tutorial leaves the colour to its
/// `line` routine; white (15) on black is our choice.
fn wgt_triangle() -> Vec<Op> {
    Vec::from([Op::Clear(0), Op::Fill(Polygon::from_pixels(&[(160, 30), (50, 150), (270, 180)], (0, 0), 15))])
}

/// Listing 38.3 up to its `page`-th keypress (the book's chapter 38;
/// `docs/scenes.md#chapter-38-sample-program`). The book never clears
/// between stages, so each page holds the ones before it.
fn listing_38_3(page: u32) -> Vec<Op> {
    const SCREEN_RECTANGLE: &[(i32, i32)] = &[(0, 0), (320, 0), (320, 200), (0, 200)];
    const CONVEX_SHAPE: &[(i32, i32)] = &[
        (0, 0),
        (121, 0),
        (320, 0),
        (200, 51),
        (301, 51),
        (250, 51),
        (319, 143),
        (320, 200),
        (22, 200),
        (0, 200),
        (50, 180),
        (20, 160),
        (50, 140),
        (20, 120),
        (50, 100),
        (20, 80),
        (50, 60),
        (20, 40),
        (50, 20),
    ];
    const TRIANGLE_1: &[(i32, i32)] = &[(30, 0), (15, 20), (0, 0)];
    const TRIANGLE_2: &[(i32, i32)] = &[(30, 20), (15, 0), (0, 20)];
    const TRIANGLE_3: &[(i32, i32)] = &[(0, 20), (20, 10), (0, 0)];
    const TRIANGLE_4: &[(i32, i32)] = &[(20, 20), (20, 0), (0, 10)];

    let fill =
        |points: &[(i32, i32)], offset: (i32, i32), color: u8| Op::Fill(Polygon::from_pixels(points, offset, color));
    let mut ops = Vec::new();
    ops.push(fill(SCREEN_RECTANGLE, (0, 0), 3));
    ops.push(fill(CONVEX_SHAPE, (0, 0), 6));
    if page < 2 {
        return ops;
    }
    for j in (0..=80).step_by(20) {
        for i in (0..290).step_by(30) {
            ops.push(fill(TRIANGLE_1, (i, j), 2));
            ops.push(fill(TRIANGLE_2, (i + 15, j), 4));
        }
    }
    for j in (100..=170).step_by(20) {
        for i in (0..290).step_by(20) {
            ops.push(fill(TRIANGLE_3, (i, j), 40));
        }
        for i in (0..290).step_by(20) {
            ops.push(fill(TRIANGLE_4, (i, j + 10), 1));
        }
    }
    if page < 3 {
        return ops;
    }
    // The book edits the hexagon's static vertices in place after each draw:
    // X moves 3 toward zero and Y 2 (sign test `>= 0`), or, where X is 0, Y
    // moves 3 toward zero.
    let mut hexagon = [(90, -50), (0, -90), (-90, -50), (-90, 50), (0, 90), (90, 50)];
    for color in 0..16u8 {
        ops.push(fill(&hexagon, (160, 100), color));
        for (x, y) in hexagon.iter_mut() {
            let toward_zero = |v: i32, by: i32| if v >= 0 { v - by } else { v + by };
            if *x != 0 {
                *x = toward_zero(*x, 3);
                *y = toward_zero(*y, 2);
            } else {
                *y = toward_zero(*y, 3);
            }
        }
    }
    ops
}

#[cfg(test)]
mod tests {
    use super::*;
    use raster::{Framebuffer, Point, SCREEN};

    #[test]
    fn every_name_resolves() {
        for builtin in &ALL {
            assert_eq!(named(builtin.name), Some(builtin));
            assert_eq!(builtin.scene().name, builtin.name);
        }
        assert!(named("nope").is_none());
    }

    /// The ops of each scene in `ALL[range]`, counted.
    fn op_counts(range: core::ops::Range<usize>) -> Vec<usize> {
        ALL[range].iter().map(|builtin| builtin.scene().ops.len()).collect()
    }

    #[test]
    fn the_world_parses_to_many_polygons_in_two_colours_on_the_screen() {
        let text = include_str!("../art/world.scene");
        let parsed = crate::file::parse("world", text).expect("art/world.scene parses");
        assert_eq!(WORLD.scene().ops, parsed.ops);
        assert!(parsed.palette.is_empty(), "the world is in the VGA default palette");
        let polygons: Vec<&Polygon> = parsed.polygons().collect();
        let vertices: usize = polygons.iter().map(|polygon| polygon.vertex_count()).sum();
        let largest = polygons.iter().map(|polygon| polygon.vertex_count()).max();
        assert_eq!((polygons.len(), vertices, largest), (129, 6384, Some(1370)));
        assert!(polygons.iter().all(|polygon| [1, 2].contains(&polygon.color)));
    }

    #[test]
    fn every_page_written_as_a_scene_file_parses_back_to_its_operations() {
        for page in ALL {
            let scene = page.scene();
            let written = crate::file::write(&scene);
            assert_eq!(crate::file::parse(page.name, &written).unwrap().ops, scene.ops, "{}", page.name);
        }
    }

    #[test]
    fn pages_are_cumulative() {
        let counts = op_counts(0..3);
        // 2 shapes; 5x10 pairs of triangles and 4x(15+15) more; 16 hexagons.
        assert_eq!(counts, [2, 2 + 100 + 120, 2 + 100 + 120 + 16]);
    }

    #[test]
    fn listing_40_4_pages_add_their_polygons_to_a_black_screen() {
        let counts = op_counts(3..7);
        // A clear, then polygons 1-3 one page at a time, then 5x8 V shapes.
        assert_eq!(counts, [2, 3, 4, 4 + 40]);
        let Some(Op::Fill(last)) = ABRASH40_4.scene().ops.last().cloned() else { panic!("no V") };
        assert_eq!(last.color, 16 + 8 * 4 + 7);
        assert_eq!(last.contours[0][0], Point::from_pixels(40 + 240, 30 + 140));
    }

    #[test]
    fn scenes_name_the_method_of_their_source() {
        let methods: Vec<&str> = ALL.iter().map(|builtin| builtin.scene().method.name()).collect();
        assert_eq!(methods[..3], ["abrash_float"; 3]);
        assert_eq!(methods[3..7], ["abrash_aet"; 4]);
        assert_eq!(methods[7..], ["lamothe", "wgt", "exact"]);
    }

    #[test]
    fn lamothe_triangle_reaches_the_bottom_row() {
        let scene = LAMOTHE_TRIANGLE.scene();
        let mut target = Framebuffer::new(SCREEN);
        let report = scene.draw(scene.method, &mut target);
        assert_eq!((report.polygons, report.refused, target.stray_spans()), (1, 0, 0));
        let rows: Vec<usize> = target
            .pixels()
            .chunks(SCREEN.width as usize)
            .enumerate()
            .filter(|(_, row)| row.contains(&30))
            .map(|(y, _)| y)
            .collect();
        assert_eq!(rows, (100..200).collect::<Vec<_>>());
        assert!(target.pixels().iter().all(|&p| p == 0 || p == 30));
    }

    #[test]
    fn last_hexagon_matches_the_book() {
        let scene = ABRASH38_3.scene();
        let Some(Op::Fill(last)) = scene.ops.last() else { panic!("no hexagon") };
        let expected: Vec<Point> = [(45, -20), (0, -45), (-45, -20), (-45, 20), (0, 45), (45, 20)]
            .iter()
            .map(|&(x, y)| Point::from_pixels(x + 160, y + 100))
            .collect();
        assert_eq!(last.contours[0], expected);
        assert_eq!(last.color, 15);
    }
}
