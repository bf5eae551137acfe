//! The stability map: for every method and peer on every stress family,
//! the pixels it drew wrong by its own convention, drew twice or left as
//! gaps, as a share of the exact pixels, with its failures and refusals.

use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::common::{contenders, FONT};
use crate::corpus::Group;
use crate::results::{Results, Row};

/// Where the grid lies: the left edge of its first column, its top, and
/// a cell's width and height, in pixels.
#[derive(Clone, Copy)]
struct Grid {
    left: i32,
    top: i32,
    cell_w: i32,
    cell_h: i32,
}

fn centred(size: u32) -> TextStyle<'static> {
    TextStyle::from((FONT, size).into_font()).pos(Pos::new(HPos::Center, VPos::Center))
}

pub(super) fn stability<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, results: &Results) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let families: Vec<&str> = results.families.iter().filter(|f| f.group == Group::Stress).map(|f| f.name).collect();
    let names: Vec<&str> = contenders(results).into_iter().map(|(name, _, _)| name).collect();
    let (width, height) = root.dim_in_pixel();
    let (left, top, bottom) = (190i32, 120i32, 60i32);
    let grid = Grid {
        left,
        top,
        cell_w: (width as i32 - left - 20) / families.len().max(1) as i32,
        cell_h: (height as i32 - top - bottom) / names.len().max(1) as i32,
    };
    root.draw(&Text::new(
        "Stability: pixels wrong by the method's own convention, overdrawn or left as gaps",
        (width as i32 / 2, 24),
        centred(24),
    ))?;
    for (j, family) in families.iter().enumerate() {
        let x = left + j as i32 * grid.cell_w + grid.cell_w / 2;
        for (line, part) in split_name(family).iter().enumerate() {
            root.draw(&Text::new(part.clone(), (x, top - 42 + line as i32 * 18), centred(15)))?;
        }
    }
    for (i, name) in names.iter().enumerate() {
        let y = top + i as i32 * grid.cell_h + grid.cell_h / 2;
        let style = TextStyle::from((FONT, 16).into_font()).pos(Pos::new(HPos::Right, VPos::Center));
        root.draw(&Text::new(name.to_string(), (left - 10, y), style))?;
        for (j, family) in families.iter().enumerate() {
            draw_cell(root, grid, (i, j), results.row(name, family))?;
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

/// The cell of row `i`, column `j` of `grid`: the contender's `row` on the
/// family, or grey where it does not take it.
fn draw_cell<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    grid: Grid,
    (i, j): (usize, usize),
    row: Option<&Row>,
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let (x0, y0) = (grid.left + j as i32 * grid.cell_w, grid.top + i as i32 * grid.cell_h);
    let cell = [(x0 + 1, y0 + 1), (x0 + grid.cell_w - 1, y0 + grid.cell_h - 1)];
    let centre = (x0 + grid.cell_w / 2, y0 + grid.cell_h / 2);
    let Some(row) = row else {
        root.draw(&Rectangle::new(cell, RGBColor(225, 225, 225).filled()))?;
        root.draw(&Text::new("n/a", centre, centred(14)))?;
        return Ok(());
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
            [(x0 + 3, y0 + 3), (x0 + grid.cell_w - 3, y0 + grid.cell_h - 3)],
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

#[cfg(test)]
mod tests {
    use super::*;

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
