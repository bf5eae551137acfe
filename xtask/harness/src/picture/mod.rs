//! Images in memory and as PNG files. A framebuffer is kept indexed (one
//! palette index per pixel), so its PNG (colour type 3) keeps the raw bytes
//! the kernel wrote, while its palette (`PLTE`) makes it show right.

pub mod compare;
pub mod ppm;
pub mod render;

use std::fs::File;
use std::io::{BufReader, BufWriter};
use std::path::Path;

use anyhow::{bail, ensure, Context, Result};
use scenes::palette::{to_rgb8, ENTRIES};

/// An 8-bit red, green, blue colour.
pub type Rgb = [u8; 3];

/// A width x height picture, rows top to bottom.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Image {
    width: u32,
    height: u32,
    pixels: Pixels,
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Pixels {
    /// One palette index per pixel, and the palette in 8-bit colours.
    Indexed { indices: Vec<u8>, palette: Vec<Rgb> },
    /// One colour per pixel.
    Rgb(Vec<Rgb>),
}

impl Image {
    /// An image of palette indices, or an error if the sizes disagree.
    pub fn indexed(width: u32, height: u32, indices: Vec<u8>, palette: Vec<Rgb>) -> Result<Self> {
        ensure!(
            !palette.is_empty() && palette.len() <= ENTRIES,
            "a palette has 1 to {ENTRIES} colours, not {}",
            palette.len()
        );
        Self::new(width, height, Pixels::Indexed { indices, palette })
    }

    /// An image of palette indices whose palette is a VGA DAC's (6-bit
    /// levels), widened with `c6_to_8` exactly as QEMU shows it.
    pub fn from_dac(width: u32, height: u32, indices: Vec<u8>, dac: &[[u8; 3]; ENTRIES]) -> Result<Self> {
        let palette = to_rgb8(dac).as_chunks::<3>().0.to_vec();
        Self::indexed(width, height, indices, palette)
    }

    /// An image of colours, or an error if the sizes disagree.
    pub fn rgb(width: u32, height: u32, colors: Vec<Rgb>) -> Result<Self> {
        Self::new(width, height, Pixels::Rgb(colors))
    }

    fn new(width: u32, height: u32, pixels: Pixels) -> Result<Self> {
        let count = match &pixels {
            Pixels::Indexed { indices, .. } => indices.len(),
            Pixels::Rgb(colors) => colors.len(),
        };
        ensure!(
            count as u64 == u64::from(width) * u64::from(height),
            "{count} pixels do not make a {width}x{height} image"
        );
        Ok(Self { width, height, pixels })
    }

    pub fn width(&self) -> u32 {
        self.width
    }

    pub fn height(&self) -> u32 {
        self.height
    }

    pub fn pixels(&self) -> &Pixels {
        &self.pixels
    }

    pub fn pixel_count(&self) -> usize {
        self.width as usize * self.height as usize
    }

    /// The colour of the `i`-th pixel (row-major). An index past the end of
    /// the palette shows black, as PNG viewers show it.
    pub fn color(&self, i: usize) -> Rgb {
        match &self.pixels {
            Pixels::Indexed { indices, palette } => palette.get(usize::from(indices[i])).copied().unwrap_or_default(),
            Pixels::Rgb(colors) => colors[i],
        }
    }

    /// The same picture with every pixel a `factor` x `factor` block of its
    /// colour: what a display that doubles pixels shows.
    pub fn scaled(&self, factor: u32) -> Self {
        let (width, height) = (self.width * factor, self.height * factor);
        let colors = (0..height)
            .flat_map(|y| (0..width).map(move |x| ((y / factor) * self.width + x / factor) as usize))
            .map(|i| self.color(i))
            .collect();
        Self { width, height, pixels: Pixels::Rgb(colors) }
    }

    /// Writes a PNG: colour type 3 with the palette as `PLTE` for an indexed
    /// image, colour type 2 otherwise; 8 bits a sample.
    pub fn write_png(&self, path: &Path) -> Result<()> {
        let write = || -> Result<()> {
            if let Some(dir) = path.parent() {
                std::fs::create_dir_all(dir)?;
            }
            let mut encoder = png::Encoder::new(BufWriter::new(File::create(path)?), self.width, self.height);
            encoder.set_depth(png::BitDepth::Eight);
            let data = match &self.pixels {
                Pixels::Indexed { indices, palette } => {
                    encoder.set_color(png::ColorType::Indexed);
                    encoder.set_palette(palette.concat());
                    indices.clone()
                }
                Pixels::Rgb(colors) => {
                    encoder.set_color(png::ColorType::Rgb);
                    colors.concat()
                }
            };
            let mut writer = encoder.write_header()?;
            writer.write_image_data(&data)?;
            writer.finish()?;
            Ok(())
        };
        write().with_context(|| format!("failed to write PNG {}", path.display()))
    }

    /// Reads an 8-bit indexed or RGB PNG as it is stored: indices stay
    /// indices.
    pub fn read_png(path: &Path) -> Result<Self> {
        let read = || -> Result<Self> {
            let mut reader = png::Decoder::new(BufReader::new(File::open(path)?)).read_info()?;
            let info = reader.info();
            let (width, height, color_type, depth) = (info.width, info.height, info.color_type, info.bit_depth);
            let palette: Option<Vec<Rgb>> = info.palette.as_ref().map(|plte| plte.as_chunks::<3>().0.to_vec());
            ensure!(depth == png::BitDepth::Eight, "bit depth {depth:?}; only 8 is read");
            let mut data = vec![0; reader.output_buffer_size().context("image too large")?];
            let frame = reader.next_frame(&mut data)?;
            data.truncate(frame.buffer_size());
            match color_type {
                png::ColorType::Indexed => {
                    Self::indexed(width, height, data, palette.context("indexed PNG without PLTE")?)
                }
                png::ColorType::Rgb => Self::rgb(width, height, data.as_chunks::<3>().0.to_vec()),
                other => bail!("colour type {other:?}; only indexed and RGB are read"),
            }
        };
        read().with_context(|| format!("failed to read PNG {}", path.display()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use scenes::palette::VGA_DEFAULT;

    fn temp_png(name: &str) -> std::path::PathBuf {
        std::env::temp_dir().join(format!("harness-picture-{}-{name}.png", std::process::id()))
    }

    #[test]
    fn indexed_png_round_trips_with_raw_indices_and_the_dac_palette() {
        let indices: Vec<u8> = (0..=255).cycle().take(320 * 200).collect();
        let image = Image::from_dac(320, 200, indices, &VGA_DEFAULT).unwrap();
        let path = temp_png("indexed");
        image.write_png(&path).unwrap();
        let back = Image::read_png(&path).unwrap();
        std::fs::remove_file(&path).unwrap();
        assert_eq!(back, image);
        let Pixels::Indexed { palette, .. } = back.pixels() else { panic!("not indexed") };
        // Entry 9 is light blue, (21, 21, 63) in 6 bits.
        assert_eq!(palette[9], [87, 87, 255]);
    }

    #[test]
    fn rgb_png_round_trips() {
        let colors: Vec<Rgb> = (0..6u8).map(|i| [i, 255 - i, i * 7]).collect();
        let image = Image::rgb(3, 2, colors).unwrap();
        let path = temp_png("rgb");
        image.write_png(&path).unwrap();
        let back = Image::read_png(&path).unwrap();
        std::fs::remove_file(&path).unwrap();
        assert_eq!(back, image);
    }

    #[test]
    fn scaling_doubles_every_pixel_into_a_block() {
        let image = Image::indexed(2, 1, vec![0, 1], vec![[1, 1, 1], [2, 2, 2]]).unwrap();
        let a = [1, 1, 1];
        let b = [2, 2, 2];
        assert_eq!(image.scaled(2), Image::rgb(4, 2, vec![a, a, b, b, a, a, b, b]).unwrap());
    }

    #[test]
    fn sizes_must_agree() {
        assert!(Image::rgb(2, 2, vec![[0; 3]; 3]).is_err());
        assert!(Image::indexed(1, 1, vec![0], Vec::new()).is_err());
    }
}
