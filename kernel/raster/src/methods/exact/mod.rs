//! `exact`: ours, and the one the project stakes itself on. Exactly the rule
//! of `docs/conventions.md#what-exact-means`, for any polygon.
//!
//! - Convention: pixel (x, y) is in when its centre (x + 0.5, y + 0.5) is:
//!   a scan line meets an edge when `y_top <= y_centre < y_bottom`, and the
//!   crossings at or left of `x_centre` decide, by their count (even-odd) or
//!   their signed sum (non-zero). Ties go to left and top edges, so polygons
//!   sharing an edge draw every pixel once and only once.
//! - Arithmetic: integers decide every pixel. Vertices in 1/256 px
//!   (`i32`); each edge's setup is two `i64` divisions (one `i128`
//!   division for an edge longer than 2^23 px), then every row is a
//!   branch-free `i64` step with an error term; a polygon whose drawn
//!   edges lie in a box under 512 px both ways sets up each edge with one
//!   division instead and steps it with one addition to a fixed-point
//!   crossing, exact for edges that short (`edge.rs` gives the bounds);
//!   such an edge under a pixel wide that meets one row only, as the
//!   many short pieces of a flattened curve do, is set up with one
//!   comparison and no division (but in the kernel, where a division
//!   counts as one instruction).
//!   That one division is the only place a float enters, and only on a
//!   machine with a floating-point unit: an `f64` quotient, several times
//!   quicker than an `i64` one, estimates it, and the integer remainder
//!   corrects the estimate to the exact ceiling (the kernel divides in
//!   `i64`).
//! - Range: exact for every `i32` vertex coordinate and every target
//!   [`Size`], so nothing is refused as out of range; the only
//!   refusals are [`Refusal::OutOfMemory`] when the edge tables of a
//!   polygon too large for the stack cannot be allocated, and
//!   [`Refusal::TooManyVertices`] when they do not fit a caller's
//!   [`FixedScratch`] (or, without the `alloc` feature, there is none).
//! - Classes: all ([`Class::Complex`]): several contours, holes,
//!   self-intersections, both fill rules.
//! - Work: rows are clipped to the target before any is visited, so a
//!   polygon spanning the whole `i32` plane costs the target's rows times
//!   its edges, never 2^24 rows; no pixel is emitted twice within a fill.
//!
//! - Speed: triangles and monotone polygons cost two edge steps and one
//!   span per row; polygons of many edges for their box flag their
//!   crossings in a grid of bits, read in order with no sort; the rest
//!   walk monotone chains, each inside run as two edges between vertices
//!   where no crossings swap, else one row at a time, sorting only where
//!   edges cross (or, where there is a crossing for every four columns,
//!   summing them per column instead).
//! - Memory: nothing is allocated for a polygon of up to 256 edges (64
//!   when they may be 512 px or longer); a larger one takes its tables from
//!   a [`Scratch`] on the heap (feature `alloc`) or a [`FixedScratch`],
//!   which the caller may keep ([`fill_auto_with`]).
//!
//! Every fill goes one way through its stages, no file calling back into
//! one it was called from: [`fill_auto`] chooses an [`ExactPath`] (the one
//! enum of the paths, carrying what each takes of the polygon) and
//! [`ExactPath::fill`] dispatches it (the one dispatcher): to `monotone.rs`
//! (the triangle fill and the two-side walk), `edge_flags/` (the flag
//! grid) or `active_edges/` (the edge table), the last two with the box
//! of the polygon's vertices that the choice between them found
//! (`bounds.rs`). Each cuts the polygon to the target in `clip.rs`, steps
//! its edges with `edge.rs` and hands their spans to the sink in
//! `spans.rs`.

mod active_edges;
mod bounds;
mod clip;
mod edge;
mod edge_flags;
mod monotone;
mod spans;

#[cfg(feature = "alloc")]
pub use active_edges::Scratch;
pub use active_edges::{FixedScratch, ScratchMut};
pub use bounds::Bounds;
use monotone::{fill_monotone, fill_triangle};

use crate::classify::is_monotone;
#[cfg(feature = "alloc")]
use crate::classify::Class;
#[cfg(target_os = "none")]
use crate::classify::Shape;
#[cfg(not(target_os = "none"))]
use crate::geometry::FillRule;
#[cfg(feature = "alloc")]
use crate::geometry::Polygon;
use crate::geometry::{Point, PolygonRef};
use crate::methods::info::Refusal;
#[cfg(feature = "alloc")]
use crate::methods::info::{Heap, MethodInfo};
#[cfg(feature = "alloc")]
use crate::methods::interface::Builtin;
#[cfg(feature = "alloc")]
use crate::reference::Convention;
use crate::target::{Size, SpanSink};

/// The exact method, as one of the crate's [`Method`](crate::Method)s.
#[cfg(feature = "alloc")]
pub struct Exact;

/// Whether the edge flags fill `polygon`, of this box and `edges` edges,
/// faster than the active edge table, on the machine it is built for.
/// On the host, where a fill is timed: where the box holds at most 64
/// words of flags (64 columns of a row each) per edge, but only 8 for a
/// polygon of one contour under the non-zero rule: one that crosses
/// itself, as a star does, nearly always has two crossings of one
/// direction in a cell somewhere, so it needs the byte counters, which
/// make every crossing dearer to flag and to read. The flags step and
/// read more instructions than the edge table's walk does, but branch the
/// same way from row to row and polygon to polygon, while the edge
/// table's sorting and events do not, and a polygon of several contours
/// (a shape with holes, a glyph) gives the edge table more chains to start
/// and merge, so 64 for it too made the holes quicker (the lab's "What
/// modelling costs" times each path alone, family by family;
/// docs/lab-history.md#2026-11-28-several-contours-on-the-edge-flags-87d14f1
/// says how the bounds were chosen).
#[cfg(not(target_os = "none"))]
#[inline(always)]
fn flags_pay<C>(bounds: &Bounds, edges: i64, polygon: PolygonRef<'_, C>) -> bool {
    let per_edge = match (polygon.rule, polygon.contours.len()) {
        (FillRule::NonZero, 1) => 8,
        _ => 64,
    };
    bounds.words() <= per_edge * edges
}

/// [`flags_pay`] in the kernel, measured in instructions (`cargo xtask
/// kbench`, QEMU counting them): where the box has at most 2 rows per
/// edge. Past that the flags' extra instructions cost more than the edge
/// table's: the Black Book page of 40 V shapes (40 rows, 6 edges each)
/// took more instructions with the host's bound
/// (docs/lab-history.md#2026-11-28-the-edge-flags-chosen-more-3359300-d58c787-3c99766).
#[cfg(target_os = "none")]
#[inline(always)]
fn flags_pay<C>(bounds: &Bounds, edges: i64, _polygon: PolygonRef<'_, C>) -> bool {
    bounds.rows() <= 2 * edges
}

#[cfg(feature = "alloc")]
static INFO: MethodInfo = MethodInfo {
    name: "exact",
    source: "ours",
    convention: Convention {
        sample_x: edge::SAMPLE_OFFSET,
        sample_y: edge::SAMPLE_OFFSET,
        summary: "pixel centres, exact; left edges and flat tops in, right edges and flat bottoms out",
    },
    numeric:
        "i32 vertices in 1/256 px; i64 edge setup (i128 for edges over 2^23 px), i64 error-term stepping (exact fixed point for polygons under 512 px, its step's quotient estimated in f64 where there is an FPU and corrected in i64)",
    handles: Class::Complex,
    rules: &[crate::FillRule::EvenOdd, crate::FillRule::NonZero],
    heap: Heap::ManyEdges,
};

#[cfg(feature = "alloc")]
impl Builtin for Exact {
    const INFO: &'static MethodInfo = &INFO;

    /// The automatic path: the cheapest exact stage for the polygon's class.
    fn fill_into<S: SpanSink + ?Sized>(&self, polygon: &Polygon, sink: &mut S) -> Result<(), Refusal> {
        fill_auto(polygon, sink)
    }
}

/// One of the paths `exact` fills by, with what it takes of a polygon:
/// from the narrowest class of polygon to the widest, each exact on the
/// polygons of its class. [`ExactPath::choose`] picks the cheapest for a
/// polygon, as [`fill_auto`] does; [`ExactPath::alone`] asks for one path
/// by its place in [`ExactPath::NAMES`], refusing a polygon outside its
/// class; [`ExactPath::fill`] fills by it. Only those two make one, so a
/// path never holds a polygon outside its class.
///
/// It reads the polygon through a [`PolygonRef`], whose contours are of
/// any type `C` that lends a slice of points (a [`Polygon`](crate::Polygon)'s
/// are `Vec<Point>`s).
///
/// ```
/// use raster::{CoverageSink, ExactPath, Polygon, Refusal, Size};
///
/// let square = Polygon::from_pixels(&[(0, 0), (3, 0), (3, 3), (0, 3)], (0, 0), 1);
/// assert_eq!(ExactPath::alone(0, &square).map(|path| path.name()), Err(Refusal::OutsideClass));
/// let monotone = ExactPath::alone(1, &square).unwrap();
/// assert_eq!(monotone.name(), "monotone");
/// let mut drawn = CoverageSink::new(Size { width: 4, height: 4 });
/// assert_eq!(monotone.fill(&mut drawn), Ok(()));
/// assert_eq!(drawn.ascii(), "###.\n###.\n###.\n....\n");
/// ```
#[derive(Debug)]
pub enum ExactPath<'a, C = &'a [Point]> {
    /// One contour of three vertices, its `corners`: its long edge and
    /// the short edge meeting each row, one span per row, no allocation.
    #[non_exhaustive]
    Triangle { corners: [Point; 3], polygon: PolygonRef<'a, C> },
    /// The one contour of `polygon` that encloses anything, monotone in y:
    /// two sides from the top vertex down, one span per row, no allocation.
    #[non_exhaustive]
    Monotone { contour: &'a [Point], polygon: PolygonRef<'a, C> },
    /// Any polygon, with the box of its vertices: the active edge table,
    /// on the stack or in a caller's scratch ([`ScratchMut`]).
    #[non_exhaustive]
    ActiveEdges { polygon: PolygonRef<'a, C>, bounds: Bounds },
    /// A polygon within 512 px across (of under 256 edges under the
    /// non-zero rule), with the box of its vertices: the edge flags, on
    /// the stack.
    #[non_exhaustive]
    EdgeFlags { polygon: PolygonRef<'a, C>, bounds: Bounds },
}

// By hand, for every `C`, as the polygon's.
impl<C> Clone for ExactPath<'_, C> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<C> Copy for ExactPath<'_, C> {}

impl ExactPath<'_> {
    /// The paths' names, from the narrowest class to the widest: the
    /// places [`ExactPath::alone`] asks for them by.
    pub const NAMES: [&'static str; 4] = NAMES;
}

/// [`ExactPath::NAMES`], for paths of any kind of contour.
const NAMES: [&str; 4] = ["triangle", "monotone", "active edges", "edge flags"];

impl<'a, C: AsRef<[Point]>> ExactPath<'a, C> {
    /// The path [`fill_auto`] fills `polygon` by, or `None` when it has
    /// no contour: in linear time, with no classification.
    ///
    /// The common case, one contour, skips the collinearity test (which
    /// there only tells drawing nothing from filling): a contour of three
    /// vertices goes to the triangle fill, one monotone in y to the
    /// monotone fill, any other to the active edge table, and each draws
    /// nothing for a collinear contour. All its crossings on a row are at
    /// one column, so no pixel lies between them (the edge table drops
    /// edges right of the target whole, so on a row it keeps all of them or
    /// the column is past the target). Several contours go to a path that
    /// takes any polygon, with no test either: one that encloses nothing
    /// adds nothing there, as the rule says. Dropping such contours first,
    /// so that one monotone contour among them took the monotone fill,
    /// cost the glyphs time, and the families of several contours have
    /// none (docs/lab-history.md#2026-11-29-no-classification-for-several-contours-b3d2f46).
    #[inline]
    pub fn choose(polygon: impl Into<PolygonRef<'a, C>>) -> Option<Self> {
        let polygon = polygon.into();
        if let [contour] = polygon.contours {
            let contour = contour.as_ref();
            return Some(match contour {
                &[a, b, c] => ExactPath::Triangle { corners: [a, b, c], polygon },
                _ if is_monotone(contour) => ExactPath::Monotone { contour, polygon },
                _ => Self::general(polygon),
            });
        }
        Self::several(polygon)
    }

    /// [`ExactPath::choose`] for a polygon of no contour or several, on
    /// the host: a path that takes any polygon, with no test.
    #[cfg(not(target_os = "none"))]
    #[inline(always)]
    fn several(polygon: PolygonRef<'a, C>) -> Option<Self> {
        (!polygon.contours.is_empty()).then(|| Self::general(polygon))
    }

    /// [`ExactPath::several`] in the kernel, where the contours that
    /// enclose nothing are dropped first, as on the host before: none left
    /// draws nothing, one monotone contour takes the monotone fill. Without
    /// the test the compiler inlined the kernel's dispatch otherwise, and
    /// `cargo xtask kbench` counted 9 to 2,214 more instructions a page,
    /// though no demo page has a polygon of several contours.
    #[cfg(target_os = "none")]
    #[inline(always)]
    fn several(polygon: PolygonRef<'a, C>) -> Option<Self> {
        match Shape::of(polygon) {
            Shape::Empty => None,
            Shape::Monotone(contour) => Some(ExactPath::Monotone { contour, polygon }),
            Shape::Contour(_) | Shape::Contours => Some(Self::general(polygon)),
        }
    }

    /// The cheaper of the two paths that take any polygon (the second
    /// only within its class): the edge flags where the polygon's box
    /// holds few words of flags for its edges, the active edge table
    /// otherwise.
    #[inline(always)]
    fn general(polygon: PolygonRef<'a, C>) -> Self {
        let (bounds, edges) = (Bounds::of(polygon), polygon.vertex_count());
        if flags_pay(&bounds, edges as i64, polygon) && bounds.takes(edges, polygon.rule) {
            ExactPath::EdgeFlags { polygon, bounds }
        } else {
            ExactPath::ActiveEdges { polygon, bounds }
        }
    }

    /// The path named `NAMES[which]`, asked for alone: `polygon` as it
    /// takes it, or [`Refusal::OutsideClass`] when the polygon is not of
    /// its class (or `which` names no path).
    pub fn alone(which: usize, polygon: impl Into<PolygonRef<'a, C>>) -> Result<Self, Refusal> {
        let polygon = polygon.into();
        match (which, polygon.contours) {
            (0, [contour]) if contour.as_ref().len() == 3 => {
                let contour = contour.as_ref();
                Ok(ExactPath::Triangle { corners: [contour[0], contour[1], contour[2]], polygon })
            }
            (1, [contour]) if contour.as_ref().len() == 3 || is_monotone(contour.as_ref()) => {
                Ok(ExactPath::Monotone { contour: contour.as_ref(), polygon })
            }
            (2, _) => Ok(ExactPath::ActiveEdges { polygon, bounds: Bounds::of(polygon) }),
            (3, _) => {
                let bounds = Bounds::of(polygon);
                let takes = bounds.takes(polygon.vertex_count(), polygon.rule);
                takes.then_some(ExactPath::EdgeFlags { polygon, bounds }).ok_or(Refusal::OutsideClass)
            }
            _ => Err(Refusal::OutsideClass),
        }
    }

    /// Every path that takes `polygon` alone ([`ExactPath::alone`]),
    /// narrowest first.
    pub fn every(polygon: impl Into<PolygonRef<'a, C>>) -> impl Iterator<Item = Self> + 'a {
        let polygon = polygon.into();
        (0..NAMES.len()).filter_map(move |which| Self::alone(which, polygon).ok())
    }

    /// Its place in [`ExactPath::NAMES`].
    pub const fn index(&self) -> usize {
        match self {
            ExactPath::Triangle { .. } => 0,
            ExactPath::Monotone { .. } => 1,
            ExactPath::ActiveEdges { .. } => 2,
            ExactPath::EdgeFlags { .. } => 3,
        }
    }

    pub const fn name(&self) -> &'static str {
        NAMES[self.index()]
    }

    /// Fills what the path holds exactly into `sink`. Only the active edge
    /// table may refuse, and only for a polygon too large for the stack:
    /// when allocating its tables fails ([`Refusal::OutOfMemory`]), or
    /// without the `alloc` feature ([`Refusal::TooManyVertices`]).
    pub fn fill<S: SpanSink + ?Sized>(self, sink: &mut S) -> Result<(), Refusal> {
        self.fill_in(sink, None)
    }

    /// [`ExactPath::fill`] with the caller's scratch (a
    /// [`Scratch`](crate::Scratch) or a [`FixedScratch`], `&mut scratch`)
    /// for polygons too large for the tables the active-edge path keeps
    /// on the stack.
    pub fn fill_with<'s, S: SpanSink + ?Sized>(
        self,
        sink: &mut S,
        scratch: impl Into<ScratchMut<'s>>,
    ) -> Result<(), Refusal> {
        self.fill_in(sink, Some(scratch.into()))
    }

    /// [`ExactPath::fill_with`], with or without a caller's scratch.
    #[inline(always)]
    fn fill_in<S: SpanSink + ?Sized>(self, sink: &mut S, scratch: Option<ScratchMut<'_>>) -> Result<(), Refusal> {
        match drawable(sink) {
            Some(size) => self.dispatch(size, sink, scratch),
            None => Ok(()),
        }
    }

    /// The one dispatcher: fills by this path into `sink`, of `size`,
    /// with or without a caller's scratch.
    #[inline(always)]
    fn dispatch<S: SpanSink + ?Sized>(
        self,
        size: Size,
        sink: &mut S,
        scratch: Option<ScratchMut<'_>>,
    ) -> Result<(), Refusal> {
        match self {
            ExactPath::Triangle { corners, polygon } => {
                fill_triangle(corners, polygon.color, size, sink);
                Ok(())
            }
            ExactPath::Monotone { contour, polygon } => {
                fill_monotone(contour, polygon.color, size, sink);
                Ok(())
            }
            ExactPath::ActiveEdges { polygon, bounds } => active_edges::fill(polygon, bounds, size, sink, scratch),
            ExactPath::EdgeFlags { polygon, bounds } => {
                edge_flags::fill(polygon, bounds, size, sink);
                Ok(())
            }
        }
    }
}

/// The size of `sink`'s target, if it has pixels: one without draws
/// nothing, whatever the path.
#[inline(always)]
fn drawable<S: SpanSink + ?Sized>(sink: &S) -> Option<Size> {
    let size = sink.size();
    (size.width > 0 && size.height > 0).then_some(size)
}

/// Fills `polygon` exactly (`docs/conventions.md`) by the cheapest path correct for
/// its class ([`ExactPath::choose`]): degenerate polygons (and targets without
/// pixels) draw nothing, triangles take the triangle path, monotone
/// contours the two-side path, everything else the edge flags (when it
/// has many edges for its height) or the active edge table. Simple and
/// complex polygons share those paths, so telling them apart would cost
/// without saving anything.
///
/// It takes a [`Polygon`](crate::Polygon) (`&polygon`) or any
/// [`PolygonRef`]. A polygon too large for the tables on the stack (over
/// 256 edges, or over 64 when they may be 512 px or longer) takes its
/// tables from a new [`Scratch`](crate::Scratch) on the heap, or without
/// the `alloc` feature is refused ([`Refusal::TooManyVertices`]; lend it a
/// [`FixedScratch`] through [`fill_auto_with`]).
///
/// # Examples
///
/// A square with a square hole, one contour each: the even-odd rule leaves
/// the hole empty, and so does the non-zero rule, the hole going round the
/// other way. Its class is [`Class::Complex`](crate::Class) (several
/// contours), and it has 8 edges for 6 rows, so it takes the edge flags:
///
/// ```
/// use raster::{classify, fill_auto, Class, ExactPath, FillRule, Framebuffer, Point, Polygon, Size};
///
/// let square = |from: i32, to: i32| -> Vec<Point> {
///     [(from, from), (to, from), (to, to), (from, to)].map(|(x, y)| Point::from_pixels(x, y)).to_vec()
/// };
/// let mut hole = square(2, 4);
/// hole.reverse();
/// let framed = Polygon { contours: vec![square(0, 6), hole], color: 1, rule: FillRule::NonZero };
/// assert_eq!(classify(&framed), Class::Complex);
/// let path = |polygon: &Polygon| ExactPath::choose(polygon).map(|path| path.name());
/// assert_eq!(path(&framed), Some("edge flags"));
///
/// let mut target = Framebuffer::new(Size { width: 6, height: 6 });
/// fill_auto(&framed, &mut target).unwrap();
/// let row = |y: usize| &target.pixels()[y * 6..y * 6 + 6];
/// assert_eq!(row(1), [1, 1, 1, 1, 1, 1]);
/// assert_eq!(row(3), [1, 1, 0, 0, 1, 1]);
///
/// // A triangle takes the triangle path, a convex polygon the two sides.
/// assert_eq!(path(&Polygon::from_pixels(&[(0, 0), (4, 1), (1, 4)], (0, 0), 1)), Some("triangle"));
/// assert_eq!(path(&Polygon::new(square(0, 3), 1)), Some("monotone"));
/// ```
pub fn fill_auto<'a, C: AsRef<[Point]> + 'a, S: SpanSink + ?Sized>(
    polygon: impl Into<PolygonRef<'a, C>>,
    sink: &mut S,
) -> Result<(), Refusal> {
    fill_auto_in(polygon.into(), sink, None)
}

/// [`fill_auto`] with the caller's scratch, for polygons too large for
/// the tables the active-edge path keeps on the stack (over 256 edges, or
/// over 64 when they may be 512 px or longer): a [`Scratch`](crate::Scratch)
/// (feature `alloc`) or a [`FixedScratch`], as `&mut scratch`. Kept from
/// fill to fill, a `Scratch` allocates only when a polygon needs more room
/// than every one before it, so a caller drawing frame after frame
/// allocates nothing once it has drawn the largest polygon; a
/// `FixedScratch` never allocates, and refuses a polygon of more edges than
/// it holds ([`Refusal::TooManyVertices`]).
///
/// # Examples
///
/// ```
/// use raster::{fill_auto_with, Framebuffer, Point, Polygon, Scratch, SCREEN};
///
/// // A comb of 150 teeth 1 px wide, hanging from a bar 50 px deep: 600
/// // edges, too many for the tables on the stack.
/// let mut comb = vec![Point::from_pixels(0, 0), Point::from_pixels(300, 0)];
/// for tooth in (0..150).rev() {
///     let x = 2 * tooth;
///     comb.extend([Point::from_pixels(x + 1, 100), Point::from_pixels(x, 100)]);
///     if tooth > 0 {
///         comb.extend([Point::from_pixels(x, 50), Point::from_pixels(x - 1, 50)]);
///     }
/// }
/// let comb = Polygon::new(comb, 9);
/// let (mut scratch, mut screen) = (Scratch::new(), Framebuffer::new(SCREEN));
/// for _frame in 0..3 {
///     // The first frame grows the scratch; the others take nothing.
///     fill_auto_with(&comb, &mut screen, &mut scratch).unwrap();
/// }
/// assert_eq!((screen.get(1, 25), screen.get(0, 75), screen.get(1, 75)), (Some(9), Some(9), Some(0)));
/// ```
pub fn fill_auto_with<'a, 's, C: AsRef<[Point]> + 'a, S: SpanSink + ?Sized>(
    polygon: impl Into<PolygonRef<'a, C>>,
    sink: &mut S,
    scratch: impl Into<ScratchMut<'s>>,
) -> Result<(), Refusal> {
    fill_auto_in(polygon.into(), sink, Some(scratch.into()))
}

/// [`fill_auto_with`], with or without a caller's scratch. The target is
/// looked at first, so that the path chosen goes straight to its fill.
#[inline(always)]
fn fill_auto_in<C: AsRef<[Point]>, S: SpanSink + ?Sized>(
    polygon: PolygonRef<'_, C>,
    sink: &mut S,
    scratch: Option<ScratchMut<'_>>,
) -> Result<(), Refusal> {
    let Some(size) = drawable(sink) else { return Ok(()) };
    match ExactPath::choose(polygon) {
        Some(path) => path.dispatch(size, sink, scratch),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Point;
    use crate::methods::interface::Method;
    use crate::methods::test_support::fill;
    use crate::target::Size;

    fn draw(polygon: &Polygon) -> alloc::string::String {
        fill(&Exact, polygon, Size { width: 8, height: 5 }).ascii()
    }

    #[test]
    fn convention_is_the_references_centre() {
        assert_eq!(
            crate::reference::SampleOffset::of(&Exact.info().convention),
            crate::reference::SampleOffset::CENTRE
        );
    }

    #[test]
    fn rectangle_on_the_pixel_grid_covers_the_pixels_inside_it() {
        let rectangle = Polygon::from_pixels(&[(1, 1), (5, 1), (5, 4), (1, 4)], (0, 0), 1);
        assert_eq!(draw(&rectangle), "........\n.####...\n.####...\n.####...\n........\n");
    }

    #[test]
    fn triangle_through_centres_keeps_its_left_edge_only() {
        // Apex on the centre of (3, 0), where both edges cross at once (in
        // on the left, out on the right: nothing); both slanted edges pass
        // through centres; the flat bottom runs through row 3's centres.
        let c = |x: i32, y: i32| Point::new(x * 256 + 128, y * 256 + 128);
        let triangle = Polygon::new(alloc::vec![c(3, 0), c(6, 3), c(0, 3)], 1);
        assert_eq!(draw(&triangle), "........\n..##....\n.####...\n........\n........\n");
    }

    #[test]
    fn holes_follow_the_fill_rule() {
        let square = |from: i32, to: i32| -> alloc::vec::Vec<Point> {
            [(from, from), (to, from), (to, to), (from, to)].iter().map(|&(x, y)| Point::from_pixels(x, y)).collect()
        };
        let mut inner = square(2, 3);
        let mut polygon =
            Polygon { contours: alloc::vec![square(1, 4), inner.clone()], color: 1, rule: FillRule::EvenOdd };
        assert_eq!(draw(&polygon), "........\n.###....\n.#.#....\n.###....\n........\n");
        polygon.rule = FillRule::NonZero;
        assert_eq!(draw(&polygon), "........\n.###....\n.###....\n.###....\n........\n");
        inner.reverse();
        polygon.contours[1] = inner;
        assert_eq!(draw(&polygon), "........\n.###....\n.#.#....\n.###....\n........\n");
    }
}
