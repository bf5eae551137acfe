//! The charts, each drawn once as SVG and once as PNG from the same code:
//! speed against accuracy, the stability map, the rotation sweep, the
//! scaling of cost with area and vertex count, and what modelling costs.

use std::fs::File;
use std::io::BufWriter;
use std::path::Path;
use std::sync::OnceLock;

use anyhow::{anyhow, Context, Result};
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use plotters::style::FontTransform;

use crate::corpus::{Axis, Group};
use crate::results::{Kind, Results};
use crate::stats::pareto_front;
use crate::{EXACT, ZERO_FLOOR};

const FONT: &str = "sans-serif";

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Chart {
    SpeedVsAccuracy,
    Stability,
    Rotation,
    Scaling,
    ModellingCost,
}

impl Chart {
    pub const ALL: [Chart; 5] =
        [Chart::SpeedVsAccuracy, Chart::Stability, Chart::Rotation, Chart::Scaling, Chart::ModellingCost];

    /// The file name, without extension.
    pub const fn name(self) -> &'static str {
        match self {
            Chart::SpeedVsAccuracy => "speed_vs_accuracy",
            Chart::Stability => "stability",
            Chart::Rotation => "rotation",
            Chart::Scaling => "scaling",
            Chart::ModellingCost => "modelling_cost",
        }
    }

    const fn size(self) -> (u32, u32) {
        match self {
            Chart::SpeedVsAccuracy => (1200, 800),
            Chart::Stability => (1300, 640),
            Chart::Rotation => (1200, 900),
            Chart::Scaling => (1400, 700),
            Chart::ModellingCost => (1600, 760),
        }
    }

    fn draw<DB: DrawingBackend>(self, root: &DrawingArea<DB, Shift>, results: &Results) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        root.fill(&WHITE)?;
        match self {
            Chart::SpeedVsAccuracy => speed_vs_accuracy(root, results),
            Chart::Stability => stability(root, results),
            Chart::Rotation => rotation(root, results),
            Chart::Scaling => scaling(root, results),
            Chart::ModellingCost => modelling_cost(root, results),
        }
    }
}

/// Draws every chart into `out` as `NAME.svg` and `NAME.png`.
pub fn draw_all(results: &Results, out: &Path) -> Result<()> {
    register_font()?;
    for chart in Chart::ALL {
        let svg = out.join(format!("{}.svg", chart.name()));
        let root = SVGBackend::new(&svg, chart.size()).into_drawing_area();
        chart.draw(&root, results).with_context(|| format!("failed to draw {}", svg.display()))?;
        root.present().with_context(|| format!("failed to write {}", svg.display()))?;
        drop(root);
        let png = out.join(format!("{}.png", chart.name()));
        let (width, height) = chart.size();
        let mut rgb = vec![0; width as usize * height as usize * 3];
        let root = BitMapBackend::with_buffer(&mut rgb, chart.size()).into_drawing_area();
        chart.draw(&root, results).with_context(|| format!("failed to draw {}", png.display()))?;
        root.present().with_context(|| format!("failed to draw {}", png.display()))?;
        drop(root);
        write_png(&png, (width, height), &rgb).with_context(|| format!("failed to write {}", png.display()))?;
    }
    Ok(())
}

/// Makes the embedded DejaVu Sans the charts' [`FONT`], once per process:
/// the charts look the same on every machine and need no font installed.
fn register_font() -> Result<()> {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    let registered = REGISTERED
        .get_or_init(|| plotters::style::register_font(FONT, FontStyle::Normal, dejavu::sans::regular()).is_ok());
    if *registered {
        Ok(())
    } else {
        Err(anyhow!("the embedded DejaVu Sans font did not load"))
    }
}

/// Writes 8-bit RGB pixels, row after row, as a PNG.
fn write_png(path: &Path, (width, height): (u32, u32), rgb: &[u8]) -> Result<()> {
    let file = File::create(path)?;
    let mut encoder = png::Encoder::new(BufWriter::new(file), width, height);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header()?;
    writer.write_image_data(rgb)?;
    writer.finish()?;
    Ok(())
}

/// Methods and peers, in results order, each with its colour.
fn contenders(results: &Results) -> Vec<(&'static str, Kind, RGBColor)> {
    const PALETTE: [RGBColor; 11] = [
        RGBColor(31, 119, 180),
        RGBColor(255, 127, 14),
        RGBColor(44, 160, 44),
        RGBColor(214, 39, 40),
        RGBColor(148, 103, 189),
        RGBColor(140, 86, 75),
        RGBColor(227, 119, 194),
        RGBColor(188, 189, 34),
        RGBColor(23, 190, 207),
        RGBColor(255, 187, 120),
        RGBColor(152, 223, 138),
    ];
    let mut next = PALETTE.iter().cycle();
    results
        .contenders
        .iter()
        .filter(|c| c.kind != Kind::Bound)
        .map(|c| (c.name, c.kind, if c.name == EXACT { BLACK } else { *next.next().unwrap_or(&BLACK) }))
        .collect()
}

/// A marker for a point of `kind`, `size` pixels: circles for methods,
/// triangles for peers.
fn marker<DB: DrawingBackend, C: Clone + 'static>(
    kind: Kind,
    at: C,
    size: i32,
    style: ShapeStyle,
) -> DynElement<'static, DB, C> {
    match kind {
        Kind::Peer => TriangleMarker::new(at, size + size / 3, style).into_dyn(),
        _ => Circle::new(at, size, style).into_dyn(),
    }
}

/// Numbers for log axes: 1, 10, 100, 1k, 10k, 1M ...; `0` at the zero floor.
fn compact(v: f64) -> String {
    let magnitude = v.abs();
    if magnitude >= 1e6 {
        format!("{}M", trim(v / 1e6))
    } else if magnitude >= 1e3 {
        format!("{}k", trim(v / 1e3))
    } else {
        trim(v)
    }
}

fn trim(v: f64) -> String {
    let text = format!("{v:.3}");
    let text = text.trim_end_matches('0').trim_end_matches('.');
    text.to_string()
}

/// A log range around `values`, padded by a factor on each side.
fn log_range(values: impl Iterator<Item = f64>, floor: f64) -> std::ops::Range<f64> {
    let (low, high) = values.fold((f64::MAX, f64::MIN), |(lo, hi), v| (lo.min(v), hi.max(v)));
    if low > high {
        return floor.max(1e-3)..1.0;
    }
    (low / 1.6).max(floor)..(high * 1.6).max(low * 2.0)
}

fn speed_vs_accuracy<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, results: &Results) -> Result<()>
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

    // The front is the edge of the region its points dominate: down from
    // the top to the first, across and down point by point, on to the right.
    let coordinates: Vec<(f64, f64)> = means.iter().map(|m| m.at).collect();
    let front: Vec<(f64, f64)> = pareto_front(&coordinates).into_iter().map(|i| coordinates[i]).collect();
    let mut staircase = Vec::new();
    if let (Some(first), Some(last)) = (front.first(), front.last()) {
        staircase.push((first.0, y_range.end));
        for (i, &(x, y)) in front.iter().enumerate() {
            staircase.push((x, y));
            let next_x = front.get(i + 1).map_or(x_range.end, |next| next.0);
            staircase.push((next_x, y));
        }
        staircase.push((x_range.end, last.1));
    }
    let front_style = RGBColor(90, 90, 90).stroke_width(3);
    chart
        .draw_series(DashedLineSeries::new(staircase, 12, 6, front_style))?
        .label("Pareto front of the means: nothing right of or above it beats a point on it")
        .legend(move |(x, y)| PathElement::new([(x, y), (x + 18, y)], front_style));

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

    // Every large marker, then every name, is a box a name must not cover.
    let centres: Vec<(i32, i32)> = means.iter().map(|m| chart.backend_coord(&m.at)).collect();
    let mut taken: Vec<(i32, i32, i32, i32)> = centres.iter().map(|&(x, y)| (x - 12, y - 12, x + 12, y + 12)).collect();
    for (mean, &(px, py)) in means.iter().zip(&centres) {
        let color = color_of(mean.name);
        chart.draw_series([
            marker::<DB, _>(mean.kind, mean.at, 11, BLACK.filled()),
            marker::<DB, _>(mean.kind, mean.at, 9, color.filled()),
        ])?;
        let label = match mean.kind {
            Kind::Peer => format!("{} ({} families)", mean.name, mean.families),
            _ => mean.name.to_string(),
        };
        // The nearest place right or left of the point, going out up and
        // down, where the name covers no marker and no name; a line leads
        // to it from the point when it had to move.
        let width = 9 * label.chars().count() as i32;
        let free = |(x, y): (i32, i32)| {
            taken.iter().all(|&(x0, y0, x1, y1)| x + width <= x0 || x1 <= x || y + 9 <= y0 || y1 <= y - 9)
        };
        let candidates = (0..16).flat_map(|k: i32| {
            let dy = if k % 2 == 0 { k / 2 * 20 } else { -(k / 2 + 1) * 20 };
            [(px + 16, py + dy), (px - 16 - width, py + dy)]
        });
        let (x, y) = candidates.clone().find(|&at| free(at)).unwrap_or((px + 16, py));
        taken.push((x, y - 9, x + width, y + 9));
        if y != py {
            let end = if x > px { x - 2 } else { x + width + 2 };
            root.draw(&PathElement::new([(px, py), (end, y)], BLACK.mix(0.5).stroke_width(1)))?;
        }
        let text = TextStyle::from((FONT, 16).into_font()).pos(Pos::new(HPos::Left, VPos::Center));
        root.draw(&Text::new(label, (x, y), text))?;
    }
    draw_legend(&mut chart, SeriesLabelPosition::LowerRight, 15)?;
    Ok(())
}

/// The legend box every chart uses, at `position` with `size`-point text.
fn draw_legend<'a, DB, CT>(chart: &mut ChartContext<'a, DB, CT>, position: SeriesLabelPosition, size: u32) -> Result<()>
where
    DB: DrawingBackend + 'a,
    DB::ErrorType: 'static,
    CT: CoordTranslate,
{
    chart
        .configure_series_labels()
        .position(position)
        .background_style(WHITE.mix(0.9))
        .border_style(BLACK.mix(0.3))
        .label_font((FONT, size))
        .draw()?;
    Ok(())
}

fn stability<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, results: &Results) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let families: Vec<&str> = results.families.iter().filter(|f| f.group == Group::Stress).map(|f| f.name).collect();
    let rows: Vec<(&str, Kind, RGBColor)> = contenders(results);
    let (width, height) = root.dim_in_pixel();
    let (left, top, bottom) = (190i32, 120i32, 60i32);
    let cell_w = (width as i32 - left - 20) / families.len().max(1) as i32;
    let cell_h = (height as i32 - top - bottom) / rows.len().max(1) as i32;
    let centred = |size: i32| TextStyle::from((FONT, size).into_font()).pos(Pos::new(HPos::Center, VPos::Center));

    root.draw(&Text::new(
        "Stability: pixels wrong by the method's own convention, overdrawn or left as gaps",
        (width as i32 / 2, 24),
        centred(24),
    ))?;
    for (j, family) in families.iter().enumerate() {
        let x = left + j as i32 * cell_w + cell_w / 2;
        for (line, part) in split_name(family).iter().enumerate() {
            root.draw(&Text::new(part.clone(), (x, top - 42 + line as i32 * 18), centred(15)))?;
        }
    }
    for (i, (name, _, _)) in rows.iter().enumerate() {
        let y = top + i as i32 * cell_h + cell_h / 2;
        let style = TextStyle::from((FONT, 16).into_font()).pos(Pos::new(HPos::Right, VPos::Center));
        root.draw(&Text::new(name.to_string(), (left - 10, y), style))?;
        for (j, family) in families.iter().enumerate() {
            let (x0, y0) = (left + j as i32 * cell_w, top + i as i32 * cell_h);
            let cell = [(x0 + 1, y0 + 1), (x0 + cell_w - 1, y0 + cell_h - 1)];
            let centre = (x0 + cell_w / 2, y0 + cell_h / 2);
            let Some(row) = results.row(name, family) else {
                root.draw(&Rectangle::new(cell, RGBColor(225, 225, 225).filled()))?;
                root.draw(&Text::new("n/a", centre, centred(14)))?;
                continue;
            };
            let damaged = row.damaged_pixels().unwrap_or(0);
            // Where the exact fill draws nothing, any pixel drawn is all wrong.
            let (rate, label) = match row.damage_rate() {
                Some(rate) => (rate, percent(rate)),
                None => (if damaged > 0 { 1.0 } else { 0.0 }, format!("{damaged} px")),
            };
            let shade = heat(rate);
            root.draw(&Rectangle::new(cell, shade.filled()))?;
            let failures = row.failures.unwrap_or(0);
            if failures > 0 {
                root.draw(&Rectangle::new(
                    [(x0 + 3, y0 + 3), (x0 + cell_w - 3, y0 + cell_h - 3)],
                    BLACK.stroke_width(3),
                ))?;
            }
            let dark = u32::from(shade.0) + u32::from(shade.1) + u32::from(shade.2) < 400;
            let text_color = if dark { WHITE } else { BLACK };
            let mut lines = vec![label];
            if failures > 0 {
                lines.push(format!("{failures} failed"));
            }
            if row.refusals.unwrap_or(0) > 0 {
                lines.push(format!("{} declined", row.refusals.unwrap_or(0)));
            }
            let first = centre.1 - (lines.len() as i32 - 1) * 8;
            for (k, line) in lines.into_iter().enumerate() {
                let size = if k == 0 { 16 } else { 12 };
                root.draw(&Text::new(line, (centre.0, first + k as i32 * 16), centred(size).color(&text_color)))?;
            }
        }
    }
    root.draw(&Text::new(
        "share of the exact pixels (a count where there are none), log colour scale: white 0, yellow 0.1%, red ≥ 100%; \
         black frame: failures (panics, stray spans); grey: peer does not take the family",
        (width as i32 / 2, height as i32 - bottom / 2),
        centred(15),
    ))?;
    Ok(())
}

/// A family name on at most two lines, split at an underscore.
fn split_name(name: &str) -> Vec<String> {
    match name.split_once('_') {
        Some((a, b)) => vec![a.to_string(), b.replace('_', " ")],
        None => vec![name.to_string()],
    }
}

/// A rate as a percentage with two significant digits.
fn percent(rate: f64) -> String {
    let p = rate * 100.0;
    match p {
        0.0 => "0".to_string(),
        p if p >= 10.0 => format!("{p:.0}%"),
        p if p >= 1.0 => format!("{p:.1}%"),
        p => format!("{:.1$}%", p, (1 - p.log10().floor() as i32).max(0) as usize),
    }
}

/// White at 0, then on a log scale from white at 1e-6 through yellow at
/// 1e-3 to red at 1 and beyond.
fn heat(rate: f64) -> RGBColor {
    if rate <= 0.0 {
        return WHITE;
    }
    let t = ((rate.log10() + 6.0) / 6.0).clamp(0.0, 1.0);
    let channel = |from: f64, to: f64, t: f64| (from + (to - from) * t).round() as u8;
    if t < 0.5 {
        let u = t * 2.0;
        RGBColor(255, channel(255.0, 220.0, u), channel(255.0, 60.0, u))
    } else {
        let u = (t - 0.5) * 2.0;
        RGBColor(channel(255.0, 190.0, u), channel(220.0, 20.0, u), channel(60.0, 30.0, u))
    }
}

fn rotation<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, results: &Results) -> Result<()>
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
            // Headroom above the lines for the legend.
            .build_cartesian_2d(0.0..360.0, 0.0..top * 1.6)?;
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
        for (name, _, color) in contenders(results) {
            let line = points(name);
            if line.is_empty() {
                continue;
            }
            let width = if name == EXACT { 3 } else { 2 };
            chart
                .draw_series(LineSeries::new(line, color.stroke_width(width)))?
                .label(name)
                .legend(move |(x, y)| PathElement::new([(x, y), (x + 18, y)], color.stroke_width(3)));
        }
        draw_legend(&mut chart, SeriesLabelPosition::UpperRight, 13)?;
    }
    Ok(())
}

fn scaling<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, results: &Results) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let panels = root.split_evenly((1, 2));
    for (panel, axis) in panels.iter().zip([Axis::Area, Axis::Vertices]) {
        let sweeps: Vec<_> = results.sweeps.iter().filter(|s| s.axis == axis && s.ns_per_polygon.is_some()).collect();
        let x_range = log_range(sweeps.iter().map(|s| s.value), 1e-3);
        let y_range = log_range(sweeps.iter().filter_map(|s| s.ns_per_polygon), 1e-2);
        let mut chart = ChartBuilder::on(panel)
            .caption(format!("Time per polygon against {}", axis.label()), (FONT, 22))
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
        let line = |name: &str| -> Vec<(f64, f64)> {
            sweeps.iter().filter(|s| s.name == name).filter_map(|s| Some((s.value, s.ns_per_polygon?))).collect()
        };
        for (name, kind, color) in contenders(results) {
            let points = line(name);
            if points.is_empty() {
                continue;
            }
            let width = if name == EXACT { 3 } else { 2 };
            let label = if kind == Kind::Peer { format!("{name} (peer)") } else { name.to_string() };
            chart
                .draw_series(LineSeries::new(points, color.stroke_width(width)))?
                .label(label)
                .legend(move |(x, y)| PathElement::new([(x, y), (x + 18, y)], color.stroke_width(3)));
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

/// Writes `names` under a chart whose x axis has one unit per name, each
/// turned to read downwards from under the middle of its unit.
fn category_labels<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    chart: &ChartContext<'_, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    names: &[&str],
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let style = TextStyle::from((FONT, 14).into_font()).transform(FontTransform::Rotate90);
    let (left, top) = area.get_base_pixel();
    for (i, name) in names.iter().enumerate() {
        let (x, y) = chart.backend_coord(&(i as f64 + 0.5, 0.0));
        area.draw(&Text::new(name.to_string(), (x - left + 7, y - top + 8), style.clone()))?;
    }
    Ok(())
}

/// What modelling costs: per family, each of exact's paths and fill_auto
/// against the cheapest path that takes the whole family, fill_auto's
/// choice marked and its classification's share shaded; beside it, the
/// show's shaded entries as they need and over-modelled.
fn modelling_cost<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, results: &Results) -> Result<()>
where
    DB::ErrorType: 'static,
{
    const LANES: [(&str, RGBColor); 4] = [
        ("triangle", RGBColor(44, 160, 44)),
        ("monotone", RGBColor(31, 119, 180)),
        ("active edges", RGBColor(214, 39, 40)),
        ("fill_auto", RGBColor(60, 60, 60)),
    ];
    const TOP: f64 = 3.0;
    let (families_area, show_area) = root.split_horizontally(1240);
    let families: Vec<&str> = results.families.iter().map(|f| f.name).collect();
    let row = |family: &str, lane: &str| results.modelling.iter().find(|r| r.family == family && r.lane == lane);
    let mut chart = ChartBuilder::on(&families_area)
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
    category_labels(&families_area, &chart, &families)?;
    let width = 0.8 / LANES.len() as f64;
    for (i, family) in families.iter().enumerate() {
        for (k, (lane, color)) in LANES.iter().enumerate() {
            let x0 = i as f64 + 0.1 + k as f64 * width;
            let Some(r) = row(family, lane) else { continue };
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
                let dispatch = row(family, "dispatch").and_then(|d| d.ns_per_polygon);
                if let (Some(dispatch), Some(total)) = (dispatch, r.ns_per_polygon) {
                    let share = top * (dispatch / total).min(1.0);
                    chart.draw_series([Rectangle::new([(x0, 0.0), (x0 + width * 0.9, share)], BLACK.filled())])?;
                }
            }
            if r.chosen_by_fill_auto.unwrap_or(0) > 0 {
                chart.draw_series([TriangleMarker::new((x0 + width * 0.45, top + 0.12), 6, BLACK.filled())])?;
            }
        }
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
    draw_legend(&mut chart, SeriesLabelPosition::UpperLeft, 14)?;

    let entries: Vec<&str> =
        results.show_modelling.iter().filter(|r| r.modelling == "needed").map(|r| r.entry).collect();
    let most = results.show_modelling.iter().filter_map(|r| r.time_vs_needed).fold(1.0, f64::max);
    let mut show = ChartBuilder::on(&show_area)
        .caption("The show: over-modelled ÷ as needed", (FONT, 18))
        .margin(15)
        .x_label_area_size(150)
        .y_label_area_size(45)
        .build_cartesian_2d(0.0..entries.len().max(1) as f64, 0.0..most * 1.15)?;
    show.configure_mesh().disable_x_mesh().x_labels(0).label_style((FONT, 14)).draw()?;
    category_labels(&show_area, &show, &entries)?;
    for (i, entry) in entries.iter().enumerate() {
        let forced = results.show_modelling.iter().find(|r| r.entry == *entry && r.modelling == "forced");
        for (k, (ratio, color)) in
            [(Some(1.0), RGBColor(31, 119, 180)), (forced.and_then(|r| r.time_vs_needed), RGBColor(214, 39, 40))]
                .into_iter()
                .enumerate()
        {
            let Some(ratio) = ratio else { continue };
            let x0 = i as f64 + 0.15 + k as f64 * 0.35;
            show.draw_series([Rectangle::new([(x0, 0.0), (x0 + 0.32, ratio)], color.mix(0.75).filled())])?;
            let style = TextStyle::from((FONT, 13).into_font()).pos(Pos::new(HPos::Center, VPos::Bottom));
            show.draw_series([Text::new(format!("{ratio:.1}×"), (x0 + 0.16, ratio + most * 0.01), style)])?;
        }
    }
    let blue = RGBColor(31, 119, 180).mix(0.75);
    let red = RGBColor(214, 39, 40).mix(0.75);
    show.draw_series(std::iter::empty::<Rectangle<(f64, f64)>>())?
        .label("as needed")
        .legend(move |(x, y)| Rectangle::new([(x, y - 5), (x + 14, y + 5)], blue.filled()));
    show.draw_series(std::iter::empty::<Rectangle<(f64, f64)>>())?
        .label("4 attributes + depth buffer")
        .legend(move |(x, y)| Rectangle::new([(x, y - 5), (x + 14, y + 5)], red.filled()));
    draw_legend(&mut show, SeriesLabelPosition::UpperLeft, 13)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn compact_numbers_read_like_axis_labels() {
        assert_eq!(compact(1500.0), "1.5k");
        assert_eq!(compact(2_000_000.0), "2M");
        assert_eq!(compact(0.25), "0.25");
        assert_eq!(compact(10.0), "10");
    }

    #[test]
    fn heat_runs_from_white_to_red() {
        assert_eq!(heat(0.0), RGBColor(255, 255, 255));
        assert_eq!(heat(1e-3), RGBColor(255, 220, 60));
        assert_eq!(heat(1.0), RGBColor(190, 20, 30));
        assert_eq!(heat(5.0), heat(1.0));
    }

    #[test]
    fn percentages_keep_two_significant_digits() {
        assert_eq!(percent(0.0), "0");
        assert_eq!(percent(0.5), "50%");
        assert_eq!(percent(0.0123), "1.2%");
        assert_eq!(percent(0.000123), "0.012%");
    }

    #[test]
    fn long_family_names_split_at_the_first_underscore() {
        assert_eq!(split_name("subpixel_translation"), ["subpixel", "translation"]);
        assert_eq!(split_name("degenerate"), ["degenerate"]);
    }
}
