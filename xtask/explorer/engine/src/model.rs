//! The scene being explored: where it came from, which polygon is selected,
//! and the vertex edits made by dragging. Input from the page (pasted scene
//! files, URL fragments) is bounded here, so that no input can make a
//! redraw take seconds: the work of a redraw grows with the vertices times
//! the screen's rows and columns, and these limits keep it to milliseconds.

use std::fmt;

use raster::{Point, Polygon, SCREEN, SUBPIXEL_BITS};
use scenes::builtin::{self, BuiltinPage};
use scenes::file::{self, LineError, Statement};
use scenes::{Op, Scene};

use crate::judge::{exact_coverage, CountCache};

/// Longest scene text taken (pasted, loaded or in a URL fragment).
pub const MAX_TEXT_BYTES: usize = 1 << 20;
/// Most vertices in one polygon: real outlines fit (the show's world has
/// one of 1,370, the lab's flags one of 3,198).
pub const MAX_POLYGON_VERTICES: usize = 4096;
/// Most vertices in a whole scene: four polygons of the largest kind (the
/// world has 6,384 in all).
pub const MAX_SCENE_VERTICES: usize = 16384;
/// Most operations (`clear` and `poly` lines) in a scene.
pub const MAX_OPS: usize = 4096;

/// Why a scene, or an edit of it, was not taken. The page shows it and
/// keeps what it had.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum InputError {
    UnknownScene(String),
    TooLong { bytes: usize },
    Line { line: usize, error: LineError },
    TooManyOps,
    PolygonTooLarge { line: usize, vertices: usize },
    SceneTooLarge,
    BadEdit(String),
    NoSuchVertex { polygon: usize, vertex: usize },
}

impl fmt::Display for InputError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            InputError::UnknownScene(name) => {
                let names: Vec<&str> = builtin::ALL.iter().map(|b| b.name).collect();
                write!(f, "unknown scene `{name}`; the scenes are {}", names.join(", "))
            }
            InputError::TooLong { bytes } => {
                write!(f, "the scene text has {bytes} bytes; the explorer takes at most {MAX_TEXT_BYTES}")
            }
            InputError::Line { line, error } => write!(f, "line {line}: {error}"),
            InputError::TooManyOps => write!(f, "more than {MAX_OPS} operations; the explorer takes at most that"),
            InputError::PolygonTooLarge { line, vertices } => write!(
                f,
                "line {line}: a polygon of {vertices} vertices; the explorer takes at most {MAX_POLYGON_VERTICES} \
                 per polygon"
            ),
            InputError::SceneTooLarge => {
                write!(f, "more than {MAX_SCENE_VERTICES} vertices in the scene; the explorer takes at most that")
            }
            InputError::BadEdit(edit) => {
                write!(f, "bad edit `{edit}` (expected polygon.vertex.x.y, in subpixels)")
            }
            InputError::NoSuchVertex { polygon, vertex } => write!(f, "no vertex {vertex} in polygon {polygon}"),
        }
    }
}

/// Where the scene came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Origin {
    /// A built-in page; its edits are what differs from the page as built.
    Builtin(&'static BuiltinPage),
    /// A scene file, pasted or loaded; its text is the whole state.
    File,
}

/// The scene being explored and the selected polygon.
#[derive(Debug)]
pub struct Explorer {
    scene: Scene,
    origin: Origin,
    /// Indices in `scene.ops` of the polygons, in drawing order.
    polygons: Vec<usize>,
    selected: usize,
    pub(crate) counts: CountCache,
}

impl Default for Explorer {
    fn default() -> Self {
        Self::with_builtin(&builtin::ABRASH38_3)
    }
}

impl Explorer {
    fn new(scene: Scene, origin: Origin) -> Self {
        let polygons: Vec<usize> =
            scene.ops.iter().enumerate().filter_map(|(i, op)| matches!(op, Op::Fill(_)).then_some(i)).collect();
        let counts = CountCache::new(polygons.len());
        Self { scene, origin, polygons, selected: 0, counts }
    }

    /// A built-in page, as built.
    pub fn with_builtin(page: &'static BuiltinPage) -> Self {
        Self::new(page.scene(), Origin::Builtin(page))
    }

    /// The built-in page called `name`.
    pub fn builtin(name: &str) -> Result<Self, InputError> {
        builtin::named(name).map(Self::with_builtin).ok_or_else(|| InputError::UnknownScene(name.to_string()))
    }

    /// A scene file, checked against the limits line by line, so that a
    /// huge file is turned away at its first line past a limit.
    pub fn from_text(text: &str) -> Result<Self, InputError> {
        if text.len() > MAX_TEXT_BYTES {
            return Err(InputError::TooLong { bytes: text.len() });
        }
        let mut ops = Vec::new();
        let mut palette = Vec::new();
        let mut scene_vertices = 0;
        for (i, line) in text.lines().enumerate() {
            let line_number = i + 1;
            let op = file::parse_line(line).map_err(|error| InputError::Line { line: line_number, error })?;
            let op = match op {
                Some(Statement::Op(op)) => op,
                Some(Statement::Palette(entries)) => {
                    palette.extend(entries);
                    continue;
                }
                None => continue,
            };
            if let Op::Fill(polygon) = &op {
                let vertices = polygon.vertex_count();
                if vertices > MAX_POLYGON_VERTICES {
                    return Err(InputError::PolygonTooLarge { line: line_number, vertices });
                }
                scene_vertices += vertices;
                if scene_vertices > MAX_SCENE_VERTICES {
                    return Err(InputError::SceneTooLarge);
                }
            }
            if ops.len() == MAX_OPS {
                return Err(InputError::TooManyOps);
            }
            ops.push(op);
        }
        let scene = Scene { palette, ..Scene::new("scene file".to_string(), ops, raster::MethodId::Exact) };
        Ok(Self::new(scene, Origin::File))
    }

    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    pub fn origin(&self) -> Origin {
        self.origin
    }

    pub fn polygon_count(&self) -> usize {
        self.polygons.len()
    }

    /// Polygon `index` (in drawing order).
    pub fn polygon(&self, index: usize) -> Option<&Polygon> {
        match self.scene.ops.get(*self.polygons.get(index)?) {
            Some(Op::Fill(polygon)) => Some(polygon),
            _ => None,
        }
    }

    pub fn polygons(&self) -> impl Iterator<Item = &Polygon> {
        (0..self.polygons.len()).filter_map(|i| self.polygon(i))
    }

    /// The selected polygon's index; 0 in a scene without polygons.
    pub fn selected(&self) -> usize {
        self.selected
    }

    pub fn selected_polygon(&self) -> Option<&Polygon> {
        self.polygon(self.selected)
    }

    /// Selects polygon `index`, clamped to the polygons there are.
    pub fn select(&mut self, index: usize) {
        self.selected = index.min(self.polygons.len().saturating_sub(1));
    }

    /// Moves vertex `vertex` (counted across the contours in order) of
    /// polygon `polygon` to `to`.
    pub fn set_vertex(&mut self, polygon: usize, vertex: usize, to: Point) -> Result<(), InputError> {
        let missing = InputError::NoSuchVertex { polygon, vertex };
        let op = self.polygons.get(polygon).ok_or(missing.clone())?;
        let Some(Op::Fill(filled)) = self.scene.ops.get_mut(*op) else { return Err(missing) };
        let point = filled.contours.iter_mut().flatten().nth(vertex).ok_or(missing)?;
        if *point != to {
            *point = to;
            self.counts.forget(polygon);
        }
        Ok(())
    }

    /// The vertex edits of a built-in page, `polygon.vertex.x.y` (subpixels)
    /// joined by commas: with the page's name, all a URL needs to rebuild
    /// the scene. Empty for a scene file, whose text says it all.
    pub fn edits(&self) -> String {
        let Origin::Builtin(page) = self.origin else { return String::new() };
        let built = Explorer::with_builtin(page);
        let mut edits = Vec::new();
        for (index, (now, before)) in self.polygons().zip(built.polygons()).enumerate() {
            let pairs = now.contours.iter().flatten().zip(before.contours.iter().flatten());
            for (vertex, (p, q)) in pairs.enumerate() {
                if p != q {
                    edits.push(format!("{index}.{vertex}.{}.{}", p.x, p.y));
                }
            }
        }
        edits.join(",")
    }

    /// Applies edits written by [`Explorer::edits`]; none is applied unless
    /// all are good.
    pub fn apply_edits(&mut self, edits: &str) -> Result<(), InputError> {
        let mut parsed = Vec::new();
        for edit in edits.split(',').filter(|e| !e.is_empty()) {
            let bad = || InputError::BadEdit(edit.chars().take(80).collect());
            let fields: Vec<&str> = edit.split('.').collect();
            let [polygon, vertex, x, y] = fields[..] else { return Err(bad()) };
            let polygon: usize = polygon.parse().map_err(|_| bad())?;
            let vertex: usize = vertex.parse().map_err(|_| bad())?;
            let point = Point::new(x.parse().map_err(|_| bad())?, y.parse().map_err(|_| bad())?);
            let exists = self.polygon(polygon).is_some_and(|p| vertex < p.vertex_count());
            if !exists {
                return Err(InputError::NoSuchVertex { polygon, vertex });
            }
            parsed.push((polygon, vertex, point));
        }
        for (polygon, vertex, point) in parsed {
            self.set_vertex(polygon, vertex, point)?;
        }
        Ok(())
    }

    /// The scene as a scene file.
    pub fn scene_text(&self) -> String {
        file::write(&self.scene)
    }

    /// The last-drawn polygon whose exact fill covers pixel (x, y), the one
    /// a click on that pixel means.
    pub fn polygon_at(&self, x: i32, y: i32) -> Option<usize> {
        if !(0..SCREEN.width).contains(&x) || !(0..SCREEN.height).contains(&y) {
            return None;
        }
        let corner = (i64::from(x) << SUBPIXEL_BITS, i64::from(y) << SUBPIXEL_BITS);
        let one = 1i64 << SUBPIXEL_BITS;
        (0..self.polygons.len()).rev().find(|&index| {
            let Some(polygon) = self.polygon(index) else { return false };
            let mut points = polygon.contours.iter().flatten();
            let Some(first) = points.next() else { return false };
            let (mut low, mut high) = ((first.x, first.y), (first.x, first.y));
            for p in points {
                low = (low.0.min(p.x), low.1.min(p.y));
                high = (high.0.max(p.x), high.1.max(p.y));
            }
            let overlaps = i64::from(low.0) < corner.0 + one
                && corner.0 <= i64::from(high.0)
                && i64::from(low.1) < corner.1 + one
                && corner.1 <= i64::from(high.1);
            overlaps && exact_coverage(polygon).count(x, y) > 0
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn built_in_pages_open_by_name_and_unknown_names_list_the_pages() {
        let explorer = Explorer::builtin("abrash38-3").unwrap();
        assert_eq!(explorer.polygon_count(), 238);
        let error = Explorer::builtin("abrash39").unwrap_err().to_string();
        assert!(error.starts_with("unknown scene `abrash39`; the scenes are abrash38-1, "), "{error}");
    }

    #[test]
    fn bad_scene_files_are_refused_naming_the_line() {
        let error = Explorer::from_text("clear 1\npoly color=2 0,0 NaN,3 4,4\n").unwrap_err();
        assert_eq!(error.to_string(), "line 2: bad vertex `NaN` (expected x,y)");
    }

    #[test]
    fn polygons_past_the_vertex_limit_are_refused_before_any_drawing() {
        let vertices: Vec<String> = (0..5000).map(|i| format!("{},{}", i % 320, (i * 7) % 200)).collect();
        let text = format!("clear 0\npoly color=3 {}\n", vertices.join(" "));
        let error = Explorer::from_text(&text).unwrap_err();
        assert_eq!(error, InputError::PolygonTooLarge { line: 2, vertices: 5000 });
        let small: Vec<String> = (0..4000).map(|i| format!("{},1", i % 320)).collect();
        let many = format!("poly color=3 {}\n", small.join(" ")).repeat(5);
        assert_eq!(Explorer::from_text(&many).unwrap_err(), InputError::SceneTooLarge);
        assert_eq!(Explorer::from_text(&"clear 1\n".repeat(MAX_OPS + 1)).unwrap_err(), InputError::TooManyOps);
        let long = "#".repeat(MAX_TEXT_BYTES + 1);
        assert_eq!(Explorer::from_text(&long).unwrap_err(), InputError::TooLong { bytes: MAX_TEXT_BYTES + 1 });
    }

    #[test]
    fn edits_of_a_built_in_page_round_trip() {
        let mut explorer = Explorer::builtin("abrash38-1").unwrap();
        assert_eq!(explorer.edits(), "");
        explorer.set_vertex(1, 3, Point::new(-5, i32::MAX)).unwrap();
        assert_eq!(explorer.edits(), format!("1.3.-5.{}", i32::MAX));
        let mut again = Explorer::builtin("abrash38-1").unwrap();
        again.apply_edits(&explorer.edits()).unwrap();
        assert_eq!(again.scene(), explorer.scene());
    }

    #[test]
    fn bad_edits_change_nothing() {
        let mut explorer = Explorer::builtin("abrash38-1").unwrap();
        assert_eq!(explorer.apply_edits("0.0.1.1,1.99.0.0"), Err(InputError::NoSuchVertex { polygon: 1, vertex: 99 }));
        assert!(matches!(explorer.apply_edits("0.0.1.NaN"), Err(InputError::BadEdit(_))));
        assert!(matches!(explorer.apply_edits("0.0.99999999999.0"), Err(InputError::BadEdit(_))));
        assert_eq!(explorer.edits(), "");
    }

    #[test]
    fn a_scene_file_written_out_reads_back_the_same() {
        let text = "clear 9\npoly color=5 rule=nonzero 0,0 10.5,0 5,7.25 | 1,1 2,1 2,2\n";
        let explorer = Explorer::from_text(text).unwrap();
        assert_eq!(explorer.scene_text(), text);
        assert_eq!(Explorer::from_text(&explorer.scene_text()).unwrap().scene(), explorer.scene());
    }

    #[test]
    fn a_click_selects_the_topmost_polygon_covering_the_pixel() {
        let explorer = Explorer::builtin("abrash38-3").unwrap();
        // The centre belongs to the last, smallest hexagon; a corner only to
        // the screen rectangle under everything (the convex shape leaves
        // the top right corner).
        assert_eq!(explorer.polygon_at(160, 100), Some(237));
        assert_eq!(explorer.polygon_at(319, 199), Some(1));
        assert_eq!(explorer.polygon_at(318, 1), Some(0));
        assert_eq!(explorer.polygon_at(320, 0), None);
    }
}
