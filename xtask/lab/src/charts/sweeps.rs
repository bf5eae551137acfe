//! The sweeps: wrong pixels against rotation, and time per polygon
//! against area and vertex count.

use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;

use super::common::{compact, contenders, draw_legend, log_range, FONT};
use crate::corpus::Axis;
use crate::results::{Kind, Results, EXACT};
use crate::stats::Spread;

pub(super) fn rotation<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, results: &Results) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let families: Vec<&str> = results
        .families
        .iter()
        .filter(|f| results.sweeps.iter().any(|s| s.family == f.name && s.axis == Axis::Angle))
        .map(|f| f.name)
        .collect();
    let panels = root.split_evenly((families.len().max(1), 1));
    for (panel, family) in panels.iter().zip(&families) {
        let points = |name: &str| -> Vec<(f64, f64)> {
            results
                .sweeps
                .iter()
                .filter(|s| s.family == *family && s.name == name)
                .filter_map(|s| Some((s.value, s.wrong_pixels_own? as f64)))
                .collect()
        };
        let top = results
            .sweeps
            .iter()
            .filter(|s| s.family == *family)
            .filter_map(|s| s.wrong_pixels_own)
            .max()
            .unwrap_or(1)
            .max(1) as f64;
        let mut chart = ChartBuilder::on(panel)
            .caption(format!("Rotation sweep, {family}: wrong pixels against angle"), (FONT, 22))
            .margin(15)
            .x_label_area_size(45)
            .y_label_area_size(70)
            // Headroom above the lines for the legend of sixteen.
            .build_cartesian_2d(0.0..360.0, 0.0..top * 2.8)?;
        chart
            .configure_mesh()
            .x_labels(13)
            .x_label_formatter(&|v| format!("{v:.0}°"))
            .x_desc("rotation (degrees)")
            .y_desc("wrong pixels (own convention)")
            .y_label_formatter(&|v| compact(*v))
            .label_style((FONT, 14))
            .axis_desc_style((FONT, 16))
            .draw()?;
        for (name, kind, color) in contenders(results) {
            let line = points(name);
            if line.is_empty() {
                continue;
            }
            let width = if name == EXACT { 3 } else { 2 };
            chart
                .draw_series(LineSeries::new(line, color.stroke_width(width)))?
                .label(peer_label(name, kind))
                .legend(move |(x, y)| PathElement::new([(x, y), (x + 18, y)], color.stroke_width(3)));
        }
        draw_legend(&mut chart, SeriesLabelPosition::UpperRight, 13)?;
    }
    Ok(())
}

pub(super) fn scaling<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, results: &Results) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let panels = root.split_evenly((1, 2));
    for (panel, axis) in panels.iter().zip([Axis::Area, Axis::Vertices]) {
        let sweeps: Vec<_> = results.sweeps.iter().filter(|s| s.axis == axis && s.ns_per_polygon.is_some()).collect();
        let x_range = log_range(sweeps.iter().map(|s| s.value), 1e-3);
        let y_range = log_range(sweeps.iter().filter_map(|s| s.ns_per_polygon).flat_map(|t| [t.min, t.max]), 1e-2);
        let mut chart = ChartBuilder::on(panel)
            .caption(
                format!("Time per polygon against {} (bars: least to most of the repeats)", axis.label()),
                (FONT, 22),
            )
            .margin(15)
            .x_label_area_size(45)
            .y_label_area_size(70)
            .build_cartesian_2d(x_range.log_scale(), y_range.log_scale())?;
        chart
            .configure_mesh()
            .x_desc(format!("{} (log)", axis.label()))
            .y_desc("ns per polygon (log)")
            .x_label_formatter(&|v| compact(*v))
            .y_label_formatter(&|v| compact(*v))
            .label_style((FONT, 14))
            .axis_desc_style((FONT, 16))
            .draw()?;
        let spread = |name: &str| -> Vec<(f64, Spread)> {
            sweeps.iter().filter(|s| s.name == name).filter_map(|s| Some((s.value, s.ns_per_polygon?))).collect()
        };
        let line = |name: &str| -> Vec<(f64, f64)> { spread(name).into_iter().map(|(x, t)| (x, t.median)).collect() };
        for (name, kind, color) in contenders(results) {
            let points = line(name);
            if points.is_empty() {
                continue;
            }
            let width = if name == EXACT { 3 } else { 2 };
            chart
                .draw_series(LineSeries::new(points, color.stroke_width(width)))?
                .label(peer_label(name, kind))
                .legend(move |(x, y)| PathElement::new([(x, y), (x + 18, y)], color.stroke_width(3)));
            // The least and the most of the repeats at every value.
            chart.draw_series(
                spread(name).into_iter().map(|(x, t)| ErrorBar::new_vertical(x, t.min, t.median, t.max, color, 6)),
            )?;
        }
        let dashes = [(10, 5, BLACK), (3, 4, RGBColor(110, 110, 110))];
        for (bound, (dash, gap, color)) in results.contenders.iter().filter(|c| c.kind == Kind::Bound).zip(dashes) {
            let points = line(bound.name);
            if points.is_empty() {
                continue;
            }
            let style = color.stroke_width(2);
            chart
                .draw_series(DashedLineSeries::new(points, dash, gap, style))?
                .label(bound.name)
                .legend(move |(x, y)| PathElement::new([(x, y), (x + 18, y)], style));
        }
        draw_legend(&mut chart, SeriesLabelPosition::UpperLeft, 13)?;
    }
    Ok(())
}

/// A legend's name for a contender: peers say so.
fn peer_label(name: &str, kind: Kind) -> String {
    if kind == Kind::Peer {
        format!("{name} (peer)")
    } else {
        name.to_string()
    }
}
