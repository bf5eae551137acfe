//! The exact method's fast path: one contour that is monotone in y
//! (Abrash's "convex", Black Book ch. 41), triangles included.
//!
//! The boundary of such a contour is two chains from its top vertex down to
//! its bottom one, each meeting every scan line between them exactly once
//! (half-open, horizontal edges never), with opposite directions. So every
//! row has exactly two crossings and the inside is the span between them
//! under either fill rule, even where the chains cross each other. This is
//! chapter 39's two-chain walk, done with the exact steppers of [`super::edge`].

use crate::geometry::Point;
use crate::sink::SpanSink;

use super::edge::{first_sample_at_or_after, visible_column, visible_rows, EdgeStepper};

/// Fills `contour`, which must be monotone in y, with one span per row.
pub(crate) fn fill_monotone(contour: &[Point], color: u8, sink: &mut dyn SpanSink) {
    let size = sink.size();
    let Some((top, top_y)) = contour.iter().enumerate().map(|(i, p)| (i, p.y)).min_by_key(|&(_, y)| y) else {
        return;
    };
    let bottom_y = contour.iter().map(|p| p.y).max().unwrap_or(top_y);
    let mut forward = Chain::new(contour, top, Walk::Forward);
    let mut backward = Chain::new(contour, top, Walk::Backward);
    for row in visible_rows(top_y, bottom_y, size.height) {
        let (Some(a), Some(b)) = (forward.column(row), backward.column(row)) else {
            return;
        };
        let (start, end) = (visible_column(a.min(b), size.width), visible_column(a.max(b), size.width));
        if start < end {
            sink.span(row as i32, start, end, color);
        }
    }
}

/// Which way round the contour a chain goes from the top vertex.
#[derive(Clone, Copy)]
enum Walk {
    Forward,
    Backward,
}

/// One boundary chain, walked down one scan line at a time.
struct Chain<'a> {
    contour: &'a [Point],
    walk: Walk,
    /// The upper vertex of the next edge to take.
    vertex: usize,
    /// Edges not taken yet: bounds the walk on any input.
    edges_left: usize,
    /// The current edge and the row it ends before.
    edge: Option<(EdgeStepper, i64)>,
}

impl<'a> Chain<'a> {
    fn new(contour: &'a [Point], top: usize, walk: Walk) -> Self {
        Self { contour, walk, vertex: top, edges_left: contour.len(), edge: None }
    }

    /// The chain's crossing column on `row`. Rows must come one after the
    /// other, top down. `None` only if the chain runs out of edges, which a
    /// monotone contour never does above its bottom row.
    fn column(&mut self, row: i64) -> Option<i64> {
        match &mut self.edge {
            Some((stepper, end_row)) if row < *end_row => stepper.step(),
            _ => self.seek(row)?,
        }
        self.edge.map(|(stepper, _)| stepper.column)
    }

    /// Takes edges until one meets `row`, and puts its stepper on that row.
    fn seek(&mut self, row: i64) -> Option<()> {
        let n = self.contour.len();
        while self.edges_left > 0 {
            self.edges_left -= 1;
            let next = match self.walk {
                Walk::Forward => (self.vertex + 1) % n,
                Walk::Backward => (self.vertex + n - 1) % n,
            };
            let (top, bottom) = (self.contour[self.vertex], self.contour[next]);
            self.vertex = next;
            let end_row = first_sample_at_or_after(bottom.y.into());
            if first_sample_at_or_after(top.y.into()) <= row && row < end_row {
                self.edge = Some((EdgeStepper::at_row(top, bottom, row), end_row));
                return Some(());
            }
        }
        None
    }
}
