//! Fills a few polygons exactly into a 320x200 framebuffer and writes it as
//! an indexed-colour PNG: what it takes to use `raster` in a program of
//! one's own.
//!
//! `cargo run -p raster --example png -- OUT.png` (default `polygons.png`).

use std::error::Error;
use std::fs::File;
use std::io::BufWriter;
use std::path::PathBuf;

use raster::{fill_auto, FillRule, Framebuffer, Point, Polygon, SCREEN};

/// The colours of the picture, by pixel value: black, then the polygons'.
const PALETTE: [[u8; 3]; 5] = [[0, 0, 0], [230, 180, 40], [60, 140, 220], [220, 70, 70], [90, 190, 110]];

fn main() -> Result<(), Box<dyn Error>> {
    let out = PathBuf::from(std::env::args().nth(1).unwrap_or_else(|| "polygons.png".to_string()));
    let mut screen = Framebuffer::new(SCREEN);
    for polygon in polygons() {
        // `exact` declines nothing but a failed allocation.
        fill_auto(&polygon, &mut screen)?;
    }
    write_png(&out, &screen)?;
    println!("{}", out.display());
    Ok(())
}

/// A five-pointed star under each fill rule, a square with a square hole,
/// and a fan of triangles sharing a vertex off the pixel grid.
fn polygons() -> Vec<Polygon> {
    let star = |cx: f64, color: u8, rule: FillRule| {
        let points = (0..5).map(|i| {
            let a = std::f64::consts::TAU * f64::from(i * 2) / 5.0 - std::f64::consts::FRAC_PI_2;
            subpixels(cx + 45.0 * a.cos(), 60.0 + 45.0 * a.sin())
        });
        Polygon { contours: vec![points.collect()], color, rule }
    };
    let square = |x0: f64, y0: f64, side: f64| {
        [(x0, y0), (x0 + side, y0), (x0 + side, y0 + side), (x0, y0 + side)].map(|(x, y)| subpixels(x, y)).to_vec()
    };
    let mut hole = square(140.0, 35.0, 40.0);
    hole.reverse();
    let framed = Polygon { contours: vec![square(120.0, 15.0, 80.0), hole], color: 3, rule: FillRule::NonZero };
    let hub = subpixels(260.3, 150.7);
    let rim: Vec<Point> = (0..8)
        .map(|i| {
            let a = std::f64::consts::TAU * f64::from(i) / 8.0;
            subpixels(260.3 + 40.0 * a.cos(), 150.7 + 40.0 * a.sin())
        })
        .collect();
    let fan = (0..8).map(|i| Polygon::new(vec![hub, rim[i], rim[(i + 1) % 8]], if i % 2 == 0 { 4 } else { 2 }));
    // The even-odd star drawn over the non-zero one shows the centre the
    // two rules disagree on.
    let stars = [star(60.0, 2, FillRule::NonZero), star(60.0, 1, FillRule::EvenOdd)];
    stars.into_iter().chain([framed]).chain(fan).collect()
}

/// A point in pixels, to the nearest 1/256 pixel.
fn subpixels(x: f64, y: f64) -> Point {
    let one = f64::from(raster::SUBPIXEL_ONE);
    Point::new((x * one).round() as i32, (y * one).round() as i32)
}

fn write_png(path: &PathBuf, screen: &Framebuffer) -> Result<(), Box<dyn Error>> {
    let file = File::create(path).map_err(|e| format!("cannot create {}: {e}", path.display()))?;
    let mut encoder = png::Encoder::new(BufWriter::new(file), SCREEN.width as u32, SCREEN.height as u32);
    encoder.set_color(png::ColorType::Indexed);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_palette(PALETTE.as_flattened());
    let mut writer = encoder.write_header()?;
    writer.write_image_data(screen.pixels())?;
    writer.finish()?;
    Ok(())
}
