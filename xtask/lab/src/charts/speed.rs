//! Speed against accuracy: every method's and peer's time over the memset
//! bound's against its share of wrong pixels, per family and as geometric
//! means over the families, with the Pareto front of the means.

use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::common::{compact, contenders, draw_legend, log_range, marker, FONT};
use crate::results::{Kind, MeanPoint, Results, ZERO_FLOOR};
use crate::stats::pareto_front;

type Chart<'a, DB> = ChartContext<'a, DB, Cartesian2d<LogCoord<f64>, LogCoord<f64>>>;

pub(super) fn speed_vs_accuracy<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, results: &Results) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let points = results.speed_accuracy_points(ZERO_FLOOR);
    let means = results.speed_accuracy_means(ZERO_FLOOR);
    let x_range = log_range(points.iter().map(|(_, p)| p.0).chain([1.0]), 1e-3);
    let y_range = log_range(points.iter().map(|(_, p)| p.1), ZERO_FLOOR / 2.0);
    let mut chart = ChartBuilder::on(root)
        .caption(
            "Speed against accuracy: large points are each method's geometric mean over the families, small ones the families",
            (FONT, 22),
        )
        .margin(20)
        .x_label_area_size(55)
        .y_label_area_size(80)
        .build_cartesian_2d(x_range.clone().log_scale(), y_range.clone().log_scale())?;
    chart
        .configure_mesh()
        .x_desc("time per polygon ÷ memset bound's time (log; 1 = writing the pixels as one run)")
        .y_desc("wrong pixels, % of exact pixels (log; bottom row = none)")
        .x_label_formatter(&|v| compact(*v))
        .y_label_formatter(&|v| if *v <= ZERO_FLOOR * 1.01 { "0".to_string() } else { compact(*v) })
        .label_style((FONT, 15))
        .axis_desc_style((FONT, 17))
        .draw()?;
    chart
        .draw_series(DashedLineSeries::new([(1.0, y_range.start), (1.0, y_range.end)], 8, 5, BLACK.stroke_width(2)))?
        .label("memset bound (x = 1)")
        .legend(|(x, y)| PathElement::new([(x, y), (x + 18, y)], BLACK.stroke_width(2)));

    let colors = contenders(results);
    let color_of = |name: &str| colors.iter().find(|c| c.0 == name).map_or(BLACK, |c| c.2);
    // Families first, small and faint, under everything else.
    for (row, p) in &points {
        chart.draw_series([marker::<DB, _>(row.kind, *p, 3, color_of(row.name).mix(0.3).filled())])?;
    }
    let coordinates: Vec<(f64, f64)> = means.iter().map(|m| m.at).collect();
    let front: Vec<(f64, f64)> = pareto_front(&coordinates).into_iter().map(|i| coordinates[i]).collect();
    let front_style = RGBColor(90, 90, 90).stroke_width(3);
    chart
        .draw_series(DashedLineSeries::new(staircase(&front, x_range.end, y_range.end), 12, 6, front_style))?
        .label("Pareto front of the means: nothing right of or above it beats a point on it")
        .legend(move |(x, y)| PathElement::new([(x, y), (x + 18, y)], front_style));
    draw_key(&mut chart)?;
    draw_means(root, &mut chart, &means, &color_of)?;
    draw_legend(&mut chart, SeriesLabelPosition::LowerRight, 15)?;
    Ok(())
}

/// The edge of the region the front's points dominate: down from the top
/// (`top`) to the first, across and down point by point, on to the right
/// (`right`).
fn staircase(front: &[(f64, f64)], right: f64, top: f64) -> Vec<(f64, f64)> {
    let (Some(first), Some(last)) = (front.first(), front.last()) else { return vec![] };
    let mut steps = vec![(first.0, top)];
    for (i, &(x, y)) in front.iter().enumerate() {
        steps.push((x, y));
        steps.push((front.get(i + 1).map_or(right, |next| next.0), y));
    }
    steps.push((right, last.1));
    steps
}

/// The legend's entries for the kinds of marker.
fn draw_key<'a, DB: DrawingBackend + 'a>(chart: &mut Chart<'a, DB>) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let key = RGBColor(110, 110, 110);
    for (kind, size, text) in [
        (Kind::Method, 8, "method, geometric mean over the families"),
        (Kind::Peer, 8, "peer library, the same (over the families it takes)"),
        (Kind::Method, 3, "one family (faint)"),
    ] {
        chart
            .draw_series(std::iter::empty::<Circle<(f64, f64), i32>>())?
            .label(text)
            .legend(move |(x, y)| marker::<DB, _>(kind, (x + 9, y), size, key.filled()));
    }
    Ok(())
}

/// Each mean's marker, then each one's name. Every marker, then every
/// name placed, is a box a name must not cover: a name goes to the nearest
/// place right or left of its point ([`place_label`]), and a line leads to
/// it from the point where it had to move off the point's row.
fn draw_means<'a, DB: DrawingBackend + 'a>(
    root: &DrawingArea<DB, Shift>,
    chart: &mut Chart<'a, DB>,
    means: &[MeanPoint],
    color_of: &dyn Fn(&str) -> RGBColor,
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let centres: Vec<(i32, i32)> = means.iter().map(|m| chart.backend_coord(&m.at)).collect();
    let mut taken: Vec<Box2> = centres.iter().map(|&(x, y)| (x - 12, y - 12, x + 12, y + 12)).collect();
    for mean in means {
        chart.draw_series([
            marker::<DB, _>(mean.kind, mean.at, 11, BLACK.filled()),
            marker::<DB, _>(mean.kind, mean.at, 9, color_of(mean.name).filled()),
        ])?;
    }
    let text = TextStyle::from((FONT, 16).into_font());
    for (mean, &point) in means.iter().zip(&centres) {
        let label = match mean.kind {
            Kind::Peer => format!("{} ({} families)", mean.name, mean.families),
            _ => mean.name.to_string(),
        };
        let (width, height) = root.estimate_text_size(&label, &text)?;
        let placed = place_label(point, (width as i32, height as i32), &taken);
        taken.push(placed.space);
        if let Some(end) = placed.leader {
            root.draw(&PathElement::new([point, end], BLACK.mix(0.7).stroke_width(1)))?;
        }
        let side = if placed.right { HPos::Left } else { HPos::Right };
        root.draw(&Text::new(label, placed.at, text.pos(Pos::new(side, VPos::Center))))?;
    }
    Ok(())
}

/// A box on the chart, in pixels: left, top, right, bottom.
type Box2 = (i32, i32, i32, i32);

/// Pixels between a marker's centre and its name.
const LABEL_GAP: i32 = 16;

/// Where a name goes.
#[derive(Debug, PartialEq)]
struct Placed {
    /// The end of the name nearer its point, at its middle's height: its
    /// left end where it is right of the point, its right end where left.
    at: (i32, i32),
    right: bool,
    /// The box it takes, with a pixel's margin above and below.
    space: Box2,
    /// Where a line from the point ends at the name, if it left the
    /// point's row.
    leader: Option<(i32, i32)>,
}

/// The place of a name `size` (width, height) pixels beside its point at
/// `(px, py)`: the first place free of `taken` of those right of the point
/// (starting [`LABEL_GAP`] right of its centre) or left of it (ending as
/// far left), on the point's row, then 20 pixels higher, lower, 40 higher,
/// and so on; with a leader line where the name is off the point's row.
/// A name left of its point is drawn by its right end, so it ends the gap
/// from the point whatever the font makes of its width.
fn place_label((px, py): (i32, i32), (width, height): (i32, i32), taken: &[Box2]) -> Placed {
    let half = height / 2 + 1;
    let space = |(x, y): (i32, i32), right: bool| {
        if right {
            (x, y - half, x + width, y + half)
        } else {
            (x - width, y - half, x, y + half)
        }
    };
    let free = |b: Box2| taken.iter().all(|&(x0, y0, x1, y1)| b.2 <= x0 || x1 <= b.0 || b.3 <= y0 || y1 <= b.1);
    let mut candidates = (0..16).flat_map(|k: i32| {
        let dy = if k % 2 == 0 { k / 2 * 20 } else { -(k / 2 + 1) * 20 };
        [((px + LABEL_GAP, py + dy), true), ((px - LABEL_GAP, py + dy), false)]
    });
    let (at, right) = candidates.find(|&(at, right)| free(space(at, right))).unwrap_or(((px + LABEL_GAP, py), true));
    let leader = (at.1 != py).then(|| if right { (at.0 - 2, at.1) } else { (at.0 + 2, at.1) });
    Placed { at, right, space: space(at, right), leader }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_staircase_goes_down_to_each_point_and_across() {
        let front = [(1.0, 5.0), (2.0, 3.0)];
        assert_eq!(
            staircase(&front, 9.0, 10.0),
            [(1.0, 10.0), (1.0, 5.0), (2.0, 5.0), (2.0, 3.0), (9.0, 3.0), (9.0, 3.0)]
        );
        assert!(staircase(&[], 9.0, 10.0).is_empty());
    }

    /// A name stands right by its point: on its right where that is free;
    /// on its left where not, ending the same gap from the point; off the
    /// point's row only where both sides are taken, and then with a line
    /// leading from the point to its near end.
    #[test]
    fn a_name_stands_by_its_point_or_is_led_to() {
        let point = (400, 300);
        let marker = (388, 288, 412, 312);
        let right = place_label(point, (150, 18), &[marker]);
        assert_eq!((right.at, right.right, right.leader), ((416, 300), true, None));
        let cairo = (416, 290, 560, 310);
        let left = place_label(point, (150, 18), &[marker, cairo]);
        assert_eq!((left.at, left.right, left.leader), ((400 - 16, 300), false, None));
        assert_eq!(left.space, (234, 290, 384, 310));
        let both = place_label(point, (150, 18), &[marker, cairo, left.space]);
        assert_eq!((both.at, both.right, both.leader), ((416, 280), true, Some((414, 280))));
    }
}
