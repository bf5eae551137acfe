//! What LaMothe's two triangle fillers share (`docs/methods.md#lamothe`):
//! the polygon-to-triangle decomposition, `Draw_Triangle_2D` and the scan
//! loop of the two flat halves, over the edge arithmetic each variant
//! supplies ([`EdgePair`]).

use crate::geometry::{PixelPoint, Polygon};
use crate::methods::info::Refusal;
use crate::target::{Size, SpanSink};

/// His clipping globals `min_clip_x` .. `max_clip_y`, inclusive.
#[derive(Clone, Copy, Debug)]
pub(super) struct ClipRect {
    min_x: i32,
    max_x: i32,
    min_y: i32,
    max_y: i32,
}

impl ClipRect {
    /// The whole sink, or `None` when it has no pixels.
    fn of(size: Size) -> Option<Self> {
        (size.width > 0 && size.height > 0).then(|| Self {
            min_x: 0,
            max_x: size.width - 1,
            min_y: 0,
            max_y: size.height - 1,
        })
    }

    fn contains_x(&self, x: i32) -> bool {
        (self.min_x..=self.max_x).contains(&x)
    }
}

/// The left (`xs`) and right (`xe`) edge positions of one flat half and
/// their steps per line (`dx_left`, `dx_right`), in a variant's arithmetic.
pub(super) trait EdgePair {
    /// `xs += dx_left * lines; xe += dx_right * lines`: the y clip's jump
    /// over the lines above the clip rectangle.
    fn skip_lines(&mut self, lines: i32);
    /// The next line: `xs += dx_left; xe += dx_right`.
    fn step(&mut self);
    /// First pixel and pixel count of the no-x-clip path's `memset`.
    fn memset_span(&self) -> (i64, i64);
    /// `left` and `right` (both drawn) of the x-clip path.
    fn ends(&self) -> (i32, i32);
}

/// A variant's setup of `Draw_Top_Tri` and `Draw_Bottom_Tri`: the swap of
/// the two x values on the flat side, the slopes and starting points.
/// Arguments are in his parameter order; `None` is his degenerate test.
pub(super) trait FlatHalves {
    type Edges: EdgePair;
    /// Flat top: `p1` and `p2` on the top line, `p3` below.
    fn top(&self, p1: PixelPoint, p2: PixelPoint, p3: PixelPoint) -> Option<Self::Edges>;
    /// Flat bottom: `p1` on top, `p2` and `p3` on the bottom line.
    fn bottom(&self, p1: PixelPoint, p2: PixelPoint, p3: PixelPoint) -> Option<Self::Edges>;
}

/// `Method::fill` for both variants: one contour, rounded to pixels, cut
/// into triangles (module doc), each drawn by `Draw_Triangle_2D`.
pub(super) fn fill_polygon<S: SpanSink + ?Sized>(
    variant: &impl FlatHalves,
    polygon: &Polygon,
    sink: &mut S,
) -> Result<(), Refusal> {
    let contour = polygon.single_contour().ok_or(Refusal::MultipleContours)?;
    let Some(clip) = ClipRect::of(sink.size()) else {
        return Ok(());
    };
    // Rounded where used, so no vertex list is allocated.
    let v = |i: usize| contour[i].round_to_pixel();
    let mut draw = |triangle| draw_triangle_2d(variant, triangle, clip, polygon.color, sink);
    if contour.len() == 4 {
        draw([v(0), v(1), v(3)]);
        draw([v(1), v(2), v(3)]);
    } else {
        for i in 2..contour.len() {
            draw([v(0), v(i - 1), v(i)]);
        }
    }
    Ok(())
}

/// `Draw_Triangle_2D` / `Draw_TriangleFP_2D` (the two differ only in the
/// halves they call).
fn draw_triangle_2d<S: SpanSink + ?Sized>(
    variant: &impl FlatHalves,
    [p1, p2, p3]: [PixelPoint; 3],
    clip: ClipRect,
    color: u8,
    sink: &mut S,
) {
    // "test for h lines and v lines"
    if (p1.x == p2.x && p2.x == p3.x) || (p1.y == p2.y && p2.y == p3.y) {
        return;
    }
    // His three compare-and-swaps, strict `<`, so ties keep their order.
    let (mut p1, mut p2, mut p3) = (p1, p2, p3);
    if p2.y < p1.y {
        core::mem::swap(&mut p1, &mut p2);
    }
    if p3.y < p1.y {
        core::mem::swap(&mut p1, &mut p3);
    }
    if p3.y < p2.y {
        core::mem::swap(&mut p2, &mut p3);
    }
    let xs = [p1.x, p2.x, p3.x];
    let rejected = p3.y < clip.min_y
        || p1.y > clip.max_y
        || xs.iter().all(|&x| x < clip.min_x)
        || xs.iter().all(|&x| x > clip.max_x);
    if rejected {
        return;
    }
    let mut half = |edges: Option<_>, a: PixelPoint, b: PixelPoint, c: PixelPoint| {
        if let Some(edges) = edges {
            scan_half(edges, [a.x, b.x, c.x], a.y, c.y, clip, color, sink);
        }
    };
    if p1.y == p2.y {
        half(variant.top(p1, p2, p3), p1, p2, p3);
    } else if p2.y == p3.y {
        half(variant.bottom(p1, p2, p3), p1, p2, p3);
    } else {
        let split = PixelPoint { x: p1.x + long_edge_offset(p1, p2, p3), y: p2.y };
        half(variant.bottom(p1, split, p2), p1, split, p2);
        half(variant.top(p2, split, p3), p2, split, p3);
    }
}

/// `(int)(0.5+(float)(y2-y1)*(float)(x3-x1)/(float)(y3-y1))`: the long
/// edge's x offset at the middle vertex's row, products and quotient in
/// `float`, the `0.5` a `double` literal, then truncated toward zero (so
/// negative offsets round up, his bias). Only called with `y1 < y2 < y3`.
fn long_edge_offset(p1: PixelPoint, p2: PixelPoint, p3: PixelPoint) -> i32 {
    let quotient = (p2.y - p1.y) as f32 * (p3.x - p1.x) as f32 / (p3.y - p1.y) as f32;
    (0.5 + f64::from(quotient)) as i32
}

/// The body shared by `Draw_Top_Tri`, `Draw_Bottom_Tri` and their FP twins
/// after the setup: y clip, then lines `y1..=y3` by the no-x-clip path when
/// all three x lie inside the clip rectangle, else by the x-clip path.
fn scan_half<S: SpanSink + ?Sized>(
    mut edges: impl EdgePair,
    xs: [i32; 3],
    mut y1: i32,
    mut y3: i32,
    clip: ClipRect,
    color: u8,
    sink: &mut S,
) {
    if y1 < clip.min_y {
        edges.skip_lines(clip.min_y - y1);
        y1 = clip.min_y;
    }
    if y3 > clip.max_y {
        y3 = clip.max_y;
    }
    let needs_x_clip = !xs.iter().all(|&x| clip.contains_x(x));
    for y in y1..=y3 {
        if !needs_x_clip {
            let (start, count) = edges.memset_span();
            edges.step();
            memset(sink, y, start, count, color);
            continue;
        }
        let (mut left, mut right) = edges.ends();
        edges.step();
        if left < clip.min_x {
            left = clip.min_x;
            if right < clip.min_x {
                continue;
            }
        }
        if right > clip.max_x {
            right = clip.max_x;
            if left > clip.max_x {
                continue;
            }
        }
        memset(sink, y, i64::from(left), i64::from(right) - i64::from(left) + 1, color);
    }
}

/// `memset(dest_addr + start, color, count)` on line `y`, cut to the sink
/// (module doc: a negative count draws nothing).
fn memset<S: SpanSink + ?Sized>(sink: &mut S, y: i32, start: i64, count: i64, color: u8) {
    let width = i64::from(sink.size().width);
    let (x0, x1) = (start.max(0), start.saturating_add(count).min(width));
    if x0 < x1 {
        sink.span(y, x0 as i32, x1 as i32, color);
    }
}
