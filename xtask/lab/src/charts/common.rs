//! What every chart shares: the font, the contenders' colours and
//! markers, axis numbers, log ranges, the legend box and category labels.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::FontTransform;

use anyhow::Result;

use crate::results::{Kind, Results, EXACT};

/// The charts' font: DejaVu Sans, embedded (`super::register_font`).
pub(super) const FONT: &str = "sans-serif";

/// Methods and peers, in results order, each with its colour; a peer
/// timed a second way draws the same pixels as its first and is left out.
pub(super) fn contenders(results: &Results) -> Vec<(&'static str, Kind, RGBColor)> {
    const PALETTE: [RGBColor; 15] = [
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
        RGBColor(0, 0, 128),
        RGBColor(0, 128, 128),
        RGBColor(204, 163, 0),
        RGBColor(230, 0, 230),
    ];
    let mut next = PALETTE.iter().cycle();
    results
        .contenders
        .iter()
        .filter(|c| c.kind != Kind::Bound && c.variant_of.is_none())
        .map(|c| (c.name, c.kind, if c.name == EXACT { BLACK } else { *next.next().unwrap_or(&BLACK) }))
        .collect()
}

/// A marker for a point of `kind`, `size` pixels: circles for methods,
/// triangles for peers.
pub(super) fn marker<DB: DrawingBackend, C: Clone + 'static>(
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
pub(super) fn compact(v: f64) -> String {
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
pub(super) fn log_range(values: impl Iterator<Item = f64>, floor: f64) -> std::ops::Range<f64> {
    let (low, high) = values.fold((f64::MAX, f64::MIN), |(lo, hi), v| (lo.min(v), hi.max(v)));
    if low > high {
        return floor.max(1e-3)..1.0;
    }
    (low / 1.6).max(floor)..(high * 1.6).max(low * 2.0)
}

/// The legend box every chart uses, at `position` with `size`-point text.
pub(super) fn draw_legend<'a, DB, CT>(
    chart: &mut ChartContext<'a, DB, CT>,
    position: SeriesLabelPosition,
    size: u32,
) -> Result<()>
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

/// Writes `names` under a chart whose x axis has one unit per name, each
/// turned to read downwards from under the middle of its unit; `bottom`
/// gives the pixel at the foot of the chart at x.
pub(super) fn category_labels<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    names: &[&str],
    bottom: impl Fn(f64) -> (i32, i32),
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let style = TextStyle::from((FONT, 14).into_font()).transform(FontTransform::Rotate90);
    let (left, top) = area.get_base_pixel();
    for (i, name) in names.iter().enumerate() {
        let (x, y) = bottom(i as f64 + 0.5);
        area.draw(&Text::new(name.to_string(), (x - left + 7, y - top + 8), style.clone()))?;
    }
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
}
