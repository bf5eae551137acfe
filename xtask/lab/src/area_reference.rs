//! The reference for a fill that decides by area rather than at a point:
//! vello_cpu's aliasing threshold paints a pixel when the part of it the
//! polygon covers is above a threshold, which no single sample point
//! stands for. Its "own convention" is judged against this.
//!
//! The covered part is estimated from a grid of 16 x 16 sample points a
//! pixel, each decided exactly by the polygon's fill rule: sampling at a
//! point `(dx, dy)` subpixels from a pixel's centre is sampling at the
//! centres of the polygon moved by `(-dx, -dy)`, which `exact` fills
//! exactly as the reference would (`kernel/raster/tests/exact_reference.rs`)
//! and far faster. A pixel whose true coverage lies within a sixteenth or
//! so of the threshold may be estimated on the other side of it, so a fill
//! with exact areas can differ from this in a few such pixels. Vertices
//! within 128 subpixels of the `i32` limits cannot be moved that far and
//! stop at them.

use raster::{CoverageSink, MethodId, Point, Polygon, SpanSink, SCREEN, SUBPIXEL_ONE};

use crate::spans;

/// Sample points per pixel along each axis.
const GRID: i32 = 16;

/// Draws into `sink` (the screen's size) every pixel whose area covered by
/// `polygon` is estimated above `threshold / 255` of the pixel.
pub fn fill(polygon: &Polygon, threshold: u8, sink: &mut dyn SpanSink) {
    let mut samples_inside = CoverageSink::new(SCREEN);
    let step = SUBPIXEL_ONE / GRID;
    for j in 0..GRID {
        for i in 0..GRID {
            // Point (i, j) of the grid, from the pixel's centre.
            let (dx, dy) = (step * i + step / 2 - SUBPIXEL_ONE / 2, step * j + step / 2 - SUBPIXEL_ONE / 2);
            let mut moved = polygon.clone();
            for p in moved.contours.iter_mut().flatten() {
                *p = Point::new(p.x.saturating_sub(dx), p.y.saturating_sub(dy));
            }
            // `exact` takes every polygon.
            let _ = MethodId::Exact.fill(&moved, &mut samples_inside);
        }
    }
    let samples = (GRID * GRID) as u32;
    let above_threshold = |count: u32| count * 255 > u32::from(threshold) * samples;
    spans::emit_covered(&samples_inside, above_threshold, polygon.color, sink);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spans::Recorder;

    fn spans(polygon: &Polygon, threshold: u8) -> Vec<(i32, i32, i32)> {
        let mut recorder = Recorder::default();
        fill(polygon, threshold, &mut recorder);
        recorder.spans.iter().map(|s| (s.y, s.x_start, s.x_end)).collect()
    }

    #[test]
    fn a_square_on_the_grid_covers_its_pixels_whole() {
        let square = Polygon::from_pixels(&[(2, 3), (6, 3), (6, 5), (2, 5)], (0, 0), 1);
        assert_eq!(spans(&square, 127), [(3, 2, 6), (4, 2, 6)]);
        assert_eq!(spans(&square, 254), [(3, 2, 6), (4, 2, 6)]);
    }

    /// A square from 0.25 to 2.75 px covers its corner pixels by 0.75 x
    /// 0.75 (56%), its edge pixels by 75% and its middle whole.
    #[test]
    fn partly_covered_pixels_follow_the_threshold() {
        let q = SUBPIXEL_ONE / 4;
        let square = Polygon::new(
            vec![Point::new(q, q), Point::new(11 * q, q), Point::new(11 * q, 11 * q), Point::new(q, 11 * q)],
            1,
        );
        // Above half: all nine pixels; above 60%: the corners drop out.
        assert_eq!(spans(&square, 127), [(0, 0, 3), (1, 0, 3), (2, 0, 3)]);
        assert_eq!(spans(&square, 153), [(0, 1, 2), (1, 0, 3), (2, 1, 2)]);
    }
}
