//! The general path's first stage: a polygon's edges into the edge table,
//! grouped into chains, with the order the chains join the walk in. Every
//! edge is set up here on its first visible row, so that the setups'
//! divisions do not wait for each other; the walk only steps them.

use core::ops::Range;

use crate::geometry::{Point, PolygonRef};
use crate::target::Size;

use super::super::clip::{right_of_target, visible_rows};
use super::super::edge::Crossing;
use super::tables::{start_key, Chain, Edge, EdgeRoom, EdgeTable};

/// Builds the edge table of `polygon` in `room`: every edge that meets a
/// visible row and can lie left of a visible pixel centre (horizontal
/// edges never meet a row; an edge right of the target counts for no
/// visible pixel), its stepper set up on its first visible row; the chains
/// they make; and the order the chains join in.
///
/// A chain breaks where the direction changes or the rows do not follow
/// on. Each contour is walked from its top vertex, where a chain breaks,
/// so that no chain runs over the contour's end (breaking a chain
/// anywhere else too would only cost the walk an event).
pub(super) fn build<'a, E: Crossing, C: AsRef<[Point]>>(
    polygon: PolygonRef<'_, C>,
    size: Size,
    room: EdgeRoom<'a, E>,
) -> EdgeTable<'a, E> {
    let EdgeRoom { edges: table, chains: chain_table, starts } = room;
    let (mut edges, mut chains) = (0, 0);
    for contour in polygon.contours {
        let contour = contour.as_ref();
        let Some(top) = contour.iter().enumerate().min_by_key(|(_, p)| p.y).map(|(i, _)| i) else { continue };
        let (mut from, mut last) = (contour[top], None::<(i8, Range<i64>)>);
        for &to in contour[top + 1..].iter().chain(&contour[..=top]) {
            let (upper, lower, winding) = if from.y <= to.y { (from, to, 1) } else { (to, from, -1) };
            from = to;
            let rows = visible_rows(upper.y, lower.y, size.height);
            if rows.is_empty() || right_of_target(upper.x.min(lower.x), size.width) {
                continue;
            }
            let stepper = if rows.end - rows.start == 1 {
                E::at_last_row(upper, lower, rows.start)
            } else {
                E::at_row(upper, lower, rows.start)
            };
            // Visible rows are in `0..height`, `i32`s.
            let (start_row, end_row) = (rows.start as i32, rows.end as i32);
            table[edges] = Edge { stepper, end_row };
            // Down a chain each edge starts where the last ended; up one
            // (built bottom up) each ends where the last started.
            let follows = last.as_ref().is_some_and(|(w, last)| {
                *w == winding && if winding > 0 { last.end == rows.start } else { rows.end == last.start }
            });
            if follows {
                let chain = &mut chain_table[chains - 1];
                chain.end += 1;
                (chain.start_row, chain.end_row) = (chain.start_row.min(start_row), chain.end_row.max(end_row));
            } else {
                if last.is_some() {
                    close_chain(table, chain_table[chains - 1]);
                }
                chain_table[chains] = Chain { first: edges as u32, end: edges as u32 + 1, start_row, end_row, winding };
                chains += 1;
            }
            last = Some((winding, rows));
            edges += 1;
        }
        if last.is_some() {
            close_chain(table, chain_table[chains - 1]);
        }
    }
    for (i, (start, chain)) in starts.iter_mut().zip(&chain_table[..chains]).enumerate() {
        *start = start_key(chain.start_row, i);
    }
    let starts = &mut starts[..chains];
    starts.sort_unstable();
    EdgeTable { edges: table, chains: chain_table, starts }
}

/// Puts the edges of `chain`, which is complete, top to bottom: an upward
/// chain is built bottom up.
fn close_chain<E>(edges: &mut [Edge<E>], chain: Chain) {
    if chain.winding < 0 {
        edges[chain.first as usize..chain.end as usize].reverse();
    }
}
