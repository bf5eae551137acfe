//! Polygon classes ("model no more than a scene needs": `docs/conventions.md`).
//! The exact method's automatic fill ([`fill_auto`](crate::fill_auto))
//! asks `Shape` (the linear-time part of [`classify`]) which path to take.
//!
//! Without the `alloc` feature only the tests `exact` asks are here.
//!
//! Contours whose vertices all lie on one line enclose nothing and are left
//! out of every class: walking such a contour, a scan line is crossed as often
//! downward as upward and always at the same point, so it adds nothing to
//! any pixel's crossing count parity or winding sum.

use core::cmp::Ordering;

#[cfg(feature = "alloc")]
use alloc::vec::Vec;

use crate::geometry::Point;
#[cfg(feature = "alloc")]
use crate::geometry::Polygon;
#[cfg(any(feature = "alloc", target_os = "none"))]
use crate::geometry::PolygonRef;

#[cfg(feature = "alloc")]
/// Polygon classes, from cheapest to most general (Abrash ch. 41 naming in
/// brackets).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Class {
    /// Fewer than three distinct vertices, or no area.
    Degenerate,
    /// Exactly three vertices.
    Triangle,
    /// Monotone in y: every horizontal line meets the boundary at most
    /// twice (Abrash's "convex", chapter 41's "monotone-vertical").
    Convex,
    /// Edges do not cross (Abrash's "nonconvex").
    Simple,
    /// Anything: self-intersecting, several contours (Abrash's "complex").
    Complex,
}

#[cfg(feature = "alloc")]
impl Class {
    pub const fn name(self) -> &'static str {
        match self {
            Class::Degenerate => "degenerate",
            Class::Triangle => "triangle",
            Class::Convex => "convex",
            Class::Simple => "simple",
            Class::Complex => "complex",
        }
    }
}

/// The class of `polygon`: [`Class::Degenerate`] when no contour encloses
/// anything (fewer than three distinct vertices, or all on one line);
/// [`Class::Triangle`] for one contour of three distinct vertices;
/// [`Class::Convex`] for one contour monotone in y (Abrash's sense: exactly
/// two reversals of y direction, horizontal edges ignored);
/// [`Class::Simple`] for one contour whose edges neither cross nor touch
/// except neighbours at their shared vertex; [`Class::Complex`] otherwise,
/// including every polygon with several enclosing contours.
///
/// The simplicity test compares every pair of edges: quadratic in the
/// vertex count, which is why the exact method's automatic fill never asks
/// for it.
///
/// # Examples
///
/// ```
/// use raster::{classify, Class, Polygon};
///
/// let class = |points: &[(i32, i32)]| classify(&Polygon::from_pixels(points, (0, 0), 1));
/// assert_eq!(class(&[(0, 0), (5, 5), (9, 9)]), Class::Degenerate);
/// assert_eq!(class(&[(0, 0), (9, 0), (0, 9)]), Class::Triangle);
/// assert_eq!(class(&[(0, 0), (9, 0), (5, 4), (9, 9), (0, 9)]), Class::Convex);
/// assert_eq!(class(&[(0, 0), (9, 0), (9, 9), (5, 4), (0, 9)]), Class::Simple);
/// assert_eq!(class(&[(0, 0), (9, 9), (9, 0), (0, 9)]), Class::Complex);
/// ```
#[cfg(feature = "alloc")]
pub fn classify(polygon: &Polygon) -> Class {
    match Shape::of(PolygonRef::from(polygon)) {
        Shape::Empty => Class::Degenerate,
        Shape::Monotone(contour) if distinct_vertices(contour).len() == 3 => Class::Triangle,
        Shape::Monotone(_) => Class::Convex,
        Shape::Contour(contour) if is_simple(&distinct_vertices(contour)) => Class::Simple,
        Shape::Contour(_) | Shape::Contours => Class::Complex,
    }
}

#[cfg(any(feature = "alloc", target_os = "none"))]
/// The linear-time part of [`classify`]: which of a polygon's contours
/// enclose anything, and whether the one that does is monotone (what the
/// kernel's `fill_auto` asks of a polygon of several contours).
pub(crate) enum Shape<'a> {
    /// No contour encloses anything.
    Empty,
    /// One enclosing contour, monotone in y.
    Monotone(&'a [Point]),
    /// One enclosing contour, not monotone (which only [`classify`] reads).
    #[cfg_attr(not(feature = "alloc"), allow(dead_code))]
    Contour(&'a [Point]),
    /// Several enclosing contours.
    Contours,
}

#[cfg(any(feature = "alloc", target_os = "none"))]
impl<'a> Shape<'a> {
    pub(crate) fn of<C: AsRef<[Point]>>(polygon: PolygonRef<'a, C>) -> Self {
        let mut enclosing = polygon.contours.iter().map(AsRef::as_ref).filter(|contour| !is_collinear(contour));
        match (enclosing.next(), enclosing.next()) {
            (None, _) => Shape::Empty,
            (Some(contour), None) if is_monotone(contour) => Shape::Monotone(contour),
            (Some(contour), None) => Shape::Contour(contour),
            (Some(_), Some(_)) => Shape::Contours,
        }
    }
}

#[cfg(any(feature = "alloc", target_os = "none"))]
/// Whether every vertex lies on one line (fewer than three distinct
/// vertices included).
fn is_collinear(contour: &[Point]) -> bool {
    let Some(&first) = contour.first() else {
        return true;
    };
    let Some(&second) = contour.iter().find(|&&p| p != first) else {
        return true;
    };
    contour.iter().all(|&p| orientation(first, second, p) == Ordering::Equal)
}

/// Whether the contour reverses its y direction exactly twice, going round
/// once and skipping horizontal edges (Abrash ch. 41's monotone-vertical
/// test). A closed contour that is not horizontal everywhere reverses at
/// least twice, at its top and its bottom.
pub(crate) fn is_monotone(contour: &[Point]) -> bool {
    let (mut first, mut last, mut reversals) = (Ordering::Equal, Ordering::Equal, 0);
    let following = contour.iter().skip(1).chain(contour.first());
    for (a, b) in contour.iter().zip(following) {
        let direction = a.y.cmp(&b.y);
        if direction == Ordering::Equal || direction == last {
            continue;
        }
        if first == Ordering::Equal {
            (first, last) = (direction, direction);
            continue;
        }
        reversals += 1;
        last = direction;
        if reversals > 2 {
            return false;
        }
    }
    if last != first {
        reversals += 1;
    }
    first != Ordering::Equal && reversals == 2
}

#[cfg(feature = "alloc")]
/// The contour without vertices equal to the one before them (the last
/// compared with the first too), so that every edge has length.
fn distinct_vertices(contour: &[Point]) -> Vec<Point> {
    let mut vertices: Vec<Point> = Vec::with_capacity(contour.len());
    for &p in contour {
        if vertices.last() != Some(&p) {
            vertices.push(p);
        }
    }
    while vertices.len() > 1 && vertices.first() == vertices.last() {
        vertices.pop();
    }
    vertices
}

#[cfg(feature = "alloc")]
/// Whether no two edges of a contour without repeated neighbours meet,
/// except neighbouring edges at their shared vertex. Neighbours need no
/// test of their own: if one folds back over the other, the fold's end
/// vertex lies on an edge that is not its neighbour (a contour that folds
/// back with three vertices is collinear and never gets here).
fn is_simple(vertices: &[Point]) -> bool {
    let n = vertices.len();
    let edge = |i: usize| (vertices[i], vertices[(i + 1) % n]);
    let neighbours = |i: usize, j: usize| j == i + 1 || (i == 0 && j == n - 1);
    (0..n).all(|i| {
        (i + 1..n).filter(|&j| !neighbours(i, j)).all(|j| {
            let ((a, b), (c, d)) = (edge(i), edge(j));
            !segments_meet(a, b, c, d)
        })
    })
}

#[cfg(feature = "alloc")]
/// Whether the closed segments `a-b` and `c-d` share a point.
fn segments_meet(a: Point, b: Point, c: Point, d: Point) -> bool {
    let (abc, abd) = (orientation(a, b, c), orientation(a, b, d));
    let (cda, cdb) = (orientation(c, d, a), orientation(c, d, b));
    if abc != abd
        && cda != cdb
        && abc != Ordering::Equal
        && abd != Ordering::Equal
        && cda != Ordering::Equal
        && cdb != Ordering::Equal
    {
        return true;
    }
    (abc == Ordering::Equal && within_box(a, b, c))
        || (abd == Ordering::Equal && within_box(a, b, d))
        || (cda == Ordering::Equal && within_box(c, d, a))
        || (cdb == Ordering::Equal && within_box(c, d, b))
}

#[cfg(feature = "alloc")]
/// Whether `p`, collinear with `a-b`, lies on that segment.
fn within_box(a: Point, b: Point, p: Point) -> bool {
    (a.x.min(b.x)..=a.x.max(b.x)).contains(&p.x) && (a.y.min(b.y)..=a.y.max(b.y)).contains(&p.y)
}

#[cfg(any(feature = "alloc", target_os = "none"))]
/// The turn from `a-b` to `a-c`: the sign of their cross product, exact for
/// any `i32` coordinates (differences need 33 bits, products 66).
fn orientation(a: Point, b: Point, c: Point) -> Ordering {
    let d = |p: Point, q: Point| (i128::from(q.x) - i128::from(p.x), i128::from(q.y) - i128::from(p.y));
    let ((bx, by), (cx, cy)) = (d(a, b), d(a, c));
    (bx * cy).cmp(&(by * cx))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::FillRule;
    use crate::test_rng::xorshift;

    fn polygon(points: &[(i32, i32)]) -> Polygon {
        Polygon::from_pixels(points, (0, 0), 1)
    }

    #[test]
    fn too_few_or_collinear_vertices_are_degenerate() {
        assert_eq!(classify(&Polygon::default()), Class::Degenerate);
        assert_eq!(classify(&polygon(&[])), Class::Degenerate);
        assert_eq!(classify(&polygon(&[(1, 1), (1, 1), (5, 5), (1, 1)])), Class::Degenerate);
        assert_eq!(classify(&polygon(&[(0, 0), (2, 1), (6, 3), (4, 2)])), Class::Degenerate);
        assert_eq!(classify(&polygon(&[(0, 4), (9, 4), (3, 4)])), Class::Degenerate);
    }

    #[test]
    fn three_distinct_vertices_make_a_triangle() {
        assert_eq!(classify(&polygon(&[(0, 0), (5, 0), (0, 5)])), Class::Triangle);
        assert_eq!(classify(&polygon(&[(0, 0), (5, 0), (5, 0), (0, 5), (0, 0)])), Class::Triangle);
    }

    #[test]
    fn monotone_in_y_is_convex_even_when_concave_sideways() {
        // Abrash's chapter 41 point: a sideways notch keeps the polygon
        // monotone-vertical, so one span per line still fills it.
        assert_eq!(classify(&polygon(&[(0, 0), (9, 0), (4, 4), (9, 8), (0, 8)])), Class::Convex);
        // The flat top and bottom are no reversals.
        assert_eq!(classify(&polygon(&[(0, 0), (3, 0), (6, 0), (6, 3), (3, 3), (0, 3)])), Class::Convex);
    }

    /// The walk against a plain count: the contour's
    /// directions in y with the level ones dropped, read round as a
    /// circle, change exactly twice. Small coordinates make level edges,
    /// repeated vertices and zigzags common; contours of 0 to 9 vertices.
    #[test]
    fn the_monotone_walk_counts_reversals_round_the_contour() {
        let mut draw = xorshift(0x9e37_79b9_7f4a_7c15);
        let mut next = |modulus: u64| (draw() % modulus) as i32;
        let mut seen = [0; 2];
        for _ in 0..20_000 {
            let len = next(10) as usize;
            let contour: Vec<Point> = (0..len).map(|_| Point::new(next(4), next(4))).collect();
            let directions: Vec<i32> =
                (0..len).map(|i| (contour[(i + 1) % len].y - contour[i].y).signum()).filter(|&d| d != 0).collect();
            let changes = (0..directions.len())
                .filter(|&i| directions[i] != directions[(i + directions.len() - 1) % directions.len()])
                .count();
            let expected = changes == 2;
            assert_eq!(is_monotone(&contour), expected, "{contour:?}");
            seen[usize::from(expected)] += 1;
        }
        // Both answers are common in the sample.
        assert!(seen[0] > 1000 && seen[1] > 1000, "{seen:?}");
    }

    #[test]
    fn a_notch_from_below_makes_it_simple() {
        assert_eq!(classify(&polygon(&[(0, 0), (9, 0), (9, 8), (4, 3), (0, 8)])), Class::Simple);
    }

    #[test]
    fn crossing_edges_and_several_contours_are_complex() {
        // A W-shaped contour whose middle edges cross the outer ones.
        assert_eq!(classify(&polygon(&[(0, 0), (9, 6), (9, 0), (0, 6), (4, 9)])), Class::Complex);
        // Touching at a vertex counts: the bowtie's two loops share (4, 4).
        assert_eq!(classify(&polygon(&[(0, 0), (4, 4), (8, 0), (8, 8), (4, 4), (0, 8)])), Class::Complex);
        let two = Polygon {
            contours: alloc::vec![
                polygon(&[(0, 0), (4, 0), (0, 4)]).contours.remove(0),
                polygon(&[(5, 5), (9, 5), (5, 9)]).contours.remove(0)
            ],
            color: 1,
            rule: FillRule::NonZero,
        };
        assert_eq!(classify(&two), Class::Complex);
    }

    #[test]
    fn contours_enclosing_nothing_do_not_count() {
        let mut triangle = polygon(&[(0, 0), (5, 0), (0, 5)]);
        triangle.contours.push(alloc::vec![Point::new(7, 7), Point::new(900, 900)]);
        triangle.contours.push(alloc::vec![]);
        assert_eq!(classify(&triangle), Class::Triangle);
    }

    #[test]
    fn folding_back_along_an_edge_is_not_simple() {
        // (6, 0) -> (3, 0) runs back over (0, 0) -> (6, 0)'s end; the notch
        // from below at (3, 7) keeps it from being monotone.
        let folded = polygon(&[(0, 0), (6, 0), (3, 0), (3, 5), (6, 9), (3, 7), (0, 9), (2, 5)]);
        assert_eq!(classify(&folded), Class::Complex);
    }

    #[test]
    fn coordinates_at_the_i32_extremes_classify_exactly() {
        let (lo, hi) = (i32::MIN, i32::MAX);
        let square = Polygon::new(
            alloc::vec![Point::new(lo, lo), Point::new(hi, lo), Point::new(hi, hi), Point::new(lo, hi)],
            1,
        );
        assert_eq!(classify(&square), Class::Convex);
        let sliver = Polygon::new(alloc::vec![Point::new(lo, lo), Point::new(hi, hi), Point::new(hi - 1, hi)], 1);
        assert_eq!(classify(&sliver), Class::Triangle);
        let line = Polygon::new(alloc::vec![Point::new(lo, lo), Point::new(hi, hi), Point::new(0, 0)], 1);
        assert_eq!(classify(&line), Class::Degenerate);
    }
}
