//! The charts, each drawn once as SVG and once as PNG from the same code:
//! speed against accuracy, the stability map, the rotation sweep, the
//! scaling of cost with area and vertex count, what modelling costs, and
//! every peer's time over `exact`'s with its interval.

use std::fs::File;
use std::io::BufWriter;
use std::path::Path;
use std::sync::OnceLock;

use anyhow::{anyhow, Context, Result};
use plotters::coord::Shift;
use plotters::prelude::*;

mod common;
mod modelling;
mod speed;
mod stability;
mod sweeps;
mod versus;

use common::FONT;

use crate::corpus::{Axis, Group};
use crate::results::Results;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Chart {
    SpeedVsAccuracy,
    Stability,
    Rotation,
    Scaling,
    ModellingCost,
    VersusExact,
}

impl Chart {
    pub const ALL: [Chart; 6] = [
        Chart::SpeedVsAccuracy,
        Chart::Stability,
        Chart::Rotation,
        Chart::Scaling,
        Chart::ModellingCost,
        Chart::VersusExact,
    ];

    /// The charts `results` has something to draw on: the rotation
    /// sweep's where a family sweeps the angle, the scaling chart where
    /// one sweeps area or vertex count, the stability map where there are
    /// stress families (the corpus has all three, a user's scene none).
    pub fn drawn(results: &Results) -> impl Iterator<Item = Chart> + '_ {
        let swept = |axes: &[Axis]| results.sweeps.iter().any(|s| axes.contains(&s.axis));
        Chart::ALL.into_iter().filter(move |chart| match chart {
            Chart::Rotation => swept(&[Axis::Angle]),
            Chart::Scaling => swept(&[Axis::Area, Axis::Vertices]),
            Chart::Stability => results.families.iter().any(|f| f.group == Group::Stress),
            Chart::SpeedVsAccuracy | Chart::ModellingCost | Chart::VersusExact => true,
        })
    }

    /// The file name, without extension.
    pub const fn name(self) -> &'static str {
        match self {
            Chart::SpeedVsAccuracy => "speed_vs_accuracy",
            Chart::Stability => "stability",
            Chart::Rotation => "rotation",
            Chart::Scaling => "scaling",
            Chart::ModellingCost => "modelling_cost",
            Chart::VersusExact => "versus_exact",
        }
    }

    const fn size(self) -> (u32, u32) {
        match self {
            Chart::SpeedVsAccuracy => (1200, 800),
            Chart::Stability => (1300, 880),
            Chart::Rotation => (1200, 1100),
            Chart::Scaling => (1400, 700),
            Chart::ModellingCost => (1600, 760),
            Chart::VersusExact => (1700, 900),
        }
    }

    fn draw<DB: DrawingBackend>(self, root: &DrawingArea<DB, Shift>, results: &Results) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        root.fill(&WHITE)?;
        match self {
            Chart::SpeedVsAccuracy => speed::speed_vs_accuracy(root, results),
            Chart::Stability => stability::stability(root, results),
            Chart::Rotation => sweeps::rotation(root, results),
            Chart::Scaling => sweeps::scaling(root, results),
            Chart::ModellingCost => modelling::modelling_cost(root, results),
            Chart::VersusExact => versus::versus_exact(root, results),
        }
    }
}

/// Draws every chart `results` has something for ([`Chart::drawn`]) into
/// `out` as `NAME.svg` and `NAME.png`.
pub fn draw_all(results: &Results, out: &Path) -> Result<()> {
    register_font()?;
    for chart in Chart::drawn(results) {
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

/// Makes the embedded DejaVu Sans the charts' font, once per process:
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
