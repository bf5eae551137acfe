//! What modelling costs: per family, each of exact's paths and fill_auto
//! against the cheapest path that takes the whole family, fill_auto's
//! choice marked and its classification's share shaded; beside it, where
//! the run timed them, the show's shaded entries as they need and
//! over-modelled.

use anyhow::Result;
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::common::{category_labels, draw_legend, FONT};
use crate::results::Results;
use crate::stats::Ratio;

type Chart<'a, DB> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// The lanes drawn per family, each with its colour.
const LANES: [(&str, RGBColor); 5] = [
    ("triangle", RGBColor(44, 160, 44)),
    ("monotone", RGBColor(31, 119, 180)),
    ("active edges", RGBColor(214, 39, 40)),
    ("edge flags", RGBColor(148, 103, 189)),
    ("fill_auto", RGBColor(60, 60, 60)),
];
/// Bars stop at this many times the cheapest path's time.
const TOP: f64 = 3.0;

pub(super) fn modelling_cost<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, results: &Results) -> Result<()>
where
    DB::ErrorType: 'static,
{
    if results.show_modelling.is_empty() {
        return paths(root, results);
    }
    let (families_area, show_area) = root.split_horizontally(1240);
    paths(&families_area, results)?;
    show(&show_area, results)
}

/// The families' panel.
fn paths<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, results: &Results) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let families: Vec<&str> = results.families.iter().map(|f| f.name).collect();
    let mut chart = ChartBuilder::on(area)
        .caption(
            "What modelling costs: time of each path of exact ÷ the cheapest path that takes the family",
            (FONT, 21),
        )
        .margin(15)
        .x_label_area_size(150)
        .y_label_area_size(60)
        .build_cartesian_2d(0.0..families.len() as f64, 0.0..TOP + 0.3)?;
    chart
        .configure_mesh()
        .disable_x_mesh()
        .x_labels(0)
        .y_desc("time ÷ the cheapest path's (1 = the cheapest; bars stop at 3)")
        .label_style((FONT, 14))
        .axis_desc_style((FONT, 16))
        .draw()?;
    category_labels(area, &families, |x| chart.backend_coord(&(x, 0.0)))?;
    for (i, family) in families.iter().enumerate() {
        family_bars(&mut chart, results, i, family)?;
    }
    chart
        .draw_series(DashedLineSeries::new([(0.0, 1.0), (families.len() as f64, 1.0)], 6, 4, BLACK.stroke_width(1)))?
        .label("the cheapest path")
        .legend(|(x, y)| PathElement::new([(x, y), (x + 18, y)], BLACK.stroke_width(1)));
    for (lane, color) in LANES {
        chart
            .draw_series(std::iter::empty::<Rectangle<(f64, f64)>>())?
            .label(if lane == "fill_auto" { "fill_auto (black: its classification)" } else { lane })
            .legend(move |(x, y)| Rectangle::new([(x, y - 5), (x + 14, y + 5)], color.mix(0.75).filled()));
    }
    chart
        .draw_series(std::iter::empty::<Rectangle<(f64, f64)>>())?
        .label("▲ the path fill_auto picks (for some polygon); × refuses part of the family")
        .legend(|(x, y)| TriangleMarker::new((x + 7, y), 6, BLACK.filled()));
    draw_legend(&mut chart, SeriesLabelPosition::UpperLeft, 14)
}

/// The bars of family `family`, the `i`-th: one per lane, × where the
/// lane refuses part of the family.
fn family_bars<'a, DB: DrawingBackend + 'a>(
    chart: &mut Chart<'a, DB>,
    results: &Results,
    i: usize,
    family: &str,
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let row = |lane: &str| results.modelling.iter().find(|r| r.family == family && r.lane == lane);
    let width = 0.8 / LANES.len() as f64;
    for (k, (lane, color)) in LANES.iter().enumerate() {
        let x0 = i as f64 + 0.1 + k as f64 * width;
        let Some(r) = row(lane) else { continue };
        let Some(ratio) = r.time_vs_cheapest else {
            // Refused some polygon: no time on this family.
            let style = TextStyle::from((FONT, 13).into_font()).pos(Pos::new(HPos::Center, VPos::Bottom));
            chart.draw_series([Text::new("×", (x0 + width / 2.0, 0.02), style)])?;
            continue;
        };
        let top = ratio.min(TOP);
        chart.draw_series([Rectangle::new([(x0, 0.0), (x0 + width * 0.9, top)], color.mix(0.75).filled())])?;
        if *lane == "fill_auto" {
            // The share of its time spent classifying, from the bottom.
            let dispatch = row("dispatch").and_then(|d| d.time.ns_per_polygon);
            if let (Some(dispatch), Some(total)) = (dispatch, r.time.ns_per_polygon) {
                let share = top * (dispatch / total).min(1.0);
                chart.draw_series([Rectangle::new([(x0, 0.0), (x0 + width * 0.9, share)], BLACK.filled())])?;
            }
        }
        if r.chosen_by_fill_auto.unwrap_or(0) > 0 {
            chart.draw_series([TriangleMarker::new((x0 + width * 0.45, top + 0.12), 6, BLACK.filled())])?;
        }
    }
    Ok(())
}

/// The show's panel: each shaded entry as needed (1) and over-modelled.
fn show<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, results: &Results) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let entries: Vec<&str> =
        results.show_modelling.iter().filter(|r| r.modelling == "needed").map(|r| r.entry).collect();
    let most = results
        .show_modelling
        .iter()
        .filter_map(|r| r.time_vs_needed.map(|t| t.high.unwrap_or(t.ratio)))
        .fold(1.0, f64::max);
    let mut show = ChartBuilder::on(area)
        .caption("The show: over-modelled ÷ as needed", (FONT, 18))
        .margin(15)
        .x_label_area_size(150)
        .y_label_area_size(45)
        .build_cartesian_2d(0.0..entries.len().max(1) as f64, 0.0..most * 1.15)?;
    show.configure_mesh().disable_x_mesh().x_labels(0).label_style((FONT, 14)).draw()?;
    category_labels(area, &entries, |x| show.backend_coord(&(x, 0.0)))?;
    let (blue, red) = (RGBColor(31, 119, 180), RGBColor(214, 39, 40));
    for (i, entry) in entries.iter().enumerate() {
        let forced = results.show_modelling.iter().find(|r| r.entry == *entry && r.modelling == "forced");
        let needed = Ratio { ratio: 1.0, low: None, high: None, count: 0 };
        let bars = [(Some(needed), blue), (forced.and_then(|r| r.time_vs_needed), red)];
        for (k, (ratio, color)) in bars.into_iter().enumerate() {
            let Some(ratio) = ratio else { continue };
            let x0 = i as f64 + 0.15 + k as f64 * 0.35;
            let top = ratio.ratio;
            show.draw_series([Rectangle::new([(x0, 0.0), (x0 + 0.32, top)], color.mix(0.75).filled())])?;
            if let (Some(low), Some(high)) = (ratio.low, ratio.high) {
                // The ratio's interval across launches.
                show.draw_series([ErrorBar::new_vertical(x0 + 0.16, low, top, high, BLACK.stroke_width(2), 10)])?;
            }
            let label_at = ratio.high.unwrap_or(top) + most * 0.01;
            let style = TextStyle::from((FONT, 13).into_font()).pos(Pos::new(HPos::Center, VPos::Bottom));
            show.draw_series([Text::new(format!("{top:.1}×"), (x0 + 0.16, label_at), style)])?;
        }
    }
    for (label, color) in [("as needed", blue), ("4 attributes + depth buffer (bar: its interval)", red)] {
        show.draw_series(std::iter::empty::<Rectangle<(f64, f64)>>())?
            .label(label)
            .legend(move |(x, y)| Rectangle::new([(x, y - 5), (x + 14, y + 5)], color.mix(0.75).filled()));
    }
    draw_legend(&mut show, SeriesLabelPosition::UpperLeft, 13)
}
