//! Every peer's time over `exact`'s, family by family, each with the
//! interval of that ratio across launches: the project's speed
//! claim as a picture, a bar reaching below 1 being a family where the
//! lead is not sure.

use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;

use super::common::{category_labels, compact, contenders, draw_legend, log_range, FONT};
use crate::results::{Kind, Results, Row};

/// The top of the axis's data: a peer a thousand times slower than `exact`
/// is drawn there (report.md gives its figure).
const CEILING: f64 = 1000.0;

pub(super) fn versus_exact<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, results: &Results) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let families: Vec<&str> = results.families.iter().map(|f| f.name).collect();
    // Each peer with its colour; a peer timed a second way in its first's
    // colour, hollow.
    let colors = contenders(results);
    let peers: Vec<(&str, RGBColor, bool)> = results
        .contenders
        .iter()
        .filter(|c| c.kind == Kind::Peer)
        .filter_map(|c| {
            let first = c.variant_of.unwrap_or(c.name);
            let color = colors.iter().find(|(name, _, _)| *name == first)?.2;
            Some((c.name, color, c.variant_of.is_some()))
        })
        .collect();
    let row = |peer: &str, family: &str| -> Option<&Row> { results.row(peer, family) };
    let ends = peers.iter().flat_map(|(peer, _, _)| {
        families
            .iter()
            .filter_map(|f| row(peer, f)?.time.vs_exact)
            .flat_map(|r| [r.low.unwrap_or(r.ratio), r.high.unwrap_or(r.ratio)])
    });
    let data = log_range(ends.chain([0.8, 2.5]), 0.1);
    // The claim is read near 1 and 2: what lies past CEILING is drawn at it.
    let data = data.start..data.end.min(CEILING);
    let clip = |v: f64| v.min(CEILING);
    // Headroom above the data for the legend: the data take the lower
    // three fifths of the (logarithmic) axis.
    let y_range = data.start..data.start * (data.end / data.start).powf(5.0 / 3.0);
    let mut chart = ChartBuilder::on(root)
        .caption(
            "Each peer's time over exact's, family by family (bars: the 95% interval across launches; cut at 1000)",
            (FONT, 22),
        )
        .margin(20)
        .x_label_area_size(170)
        .y_label_area_size(70)
        .build_cartesian_2d(0.0..families.len().max(1) as f64, y_range.clone().log_scale())?;
    chart
        .configure_mesh()
        .disable_x_mesh()
        .x_labels(0)
        .y_desc("peer's time ÷ exact's (log; above 1: exact is faster)")
        .y_label_formatter(&|v| compact(*v))
        .label_style((FONT, 15))
        .axis_desc_style((FONT, 17))
        .draw()?;
    category_labels(root, &families, |x| chart.backend_coord(&(x, y_range.start)))?;
    let width = families.len().max(1) as f64;
    for (level, label, style) in [
        (1.0, "1: as fast as exact", BLACK.stroke_width(2)),
        (2.0, "2: half exact's speed", RGBColor(120, 120, 120).stroke_width(1)),
    ] {
        chart
            .draw_series(DashedLineSeries::new([(0.0, level), (width, level)], 8, 5, style))?
            .label(label)
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 18, y)], style));
    }
    for (k, &(peer, color, hollow)) in peers.iter().enumerate() {
        let x = |i: usize| i as f64 + 0.08 + 0.84 * (k as f64 + 0.5) / peers.len() as f64;
        let points: Vec<(f64, crate::stats::Ratio)> =
            families.iter().enumerate().filter_map(|(i, f)| Some((x(i), row(peer, f)?.time.vs_exact?))).collect();
        chart.draw_series(points.iter().filter_map(|(x, r)| {
            Some(ErrorBar::new_vertical(*x, clip(r.low?), clip(r.ratio), clip(r.high?), color.stroke_width(2), 5))
        }))?;
        let style = if hollow { color.stroke_width(2) } else { color.filled() };
        chart
            .draw_series(points.iter().map(|(x, r)| Circle::new((*x, clip(r.ratio)), 4, style)))?
            .label(peer)
            .legend(move |(x, y)| Circle::new((x + 9, y), 5, style));
    }
    draw_legend(&mut chart, SeriesLabelPosition::UpperRight, 14)
}
