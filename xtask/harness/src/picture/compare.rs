//! Golden-image comparison that explains a mismatch with pictures, never
//! with pixel values: expected, actual and diff PNGs written side by side.

use std::ops::Range;
use std::path::PathBuf;

use anyhow::{bail, Result};
use scenes::palette::ENTRIES;

use super::{Image, Pixels, Rgb};
use crate::workspace;

/// Colour of a differing pixel in a diff image.
const DIFF_MARK: Rgb = [255, 0, 255];

/// Where mismatches are written: `target/harness-failures/`.
pub fn failures_dir() -> PathBuf {
    workspace::target_dir().join("harness-failures")
}

/// Succeeds when the images are equal pixel for pixel: two indexed images
/// by their indices (the raw framebuffer bytes), otherwise by colour.
/// Otherwise writes `<name>.expected.png`, `<name>.actual.png` and
/// `<name>.diff.png` (differing pixels magenta over a darkened copy of
/// the actual image) into [`failures_dir`] and fails naming them and
/// counting the differing pixels.
pub fn compare_images(name: &str, expected: &Image, actual: &Image) -> Result<()> {
    compare_image_rows(name, expected, actual, 0..expected.height())
}

/// [`compare_images`] over rows `rows` only (cut at the image's height):
/// for a picture part of which is known to change, such as a label with
/// a measurement in it. The PNGs are whole; the diff marks differences in
/// those rows only.
pub fn compare_image_rows(name: &str, expected: &Image, actual: &Image, rows: Range<u32>) -> Result<()> {
    let same_size = same_size(expected, actual);
    let differing = if same_size { differing_pixels(expected, actual, rows.clone()) } else { Vec::new() };
    if same_size && differing.is_empty() {
        return Ok(());
    }
    let file_stem: String =
        name.chars().map(|c| if c.is_ascii_alphanumeric() || "-_.".contains(c) { c } else { '_' }).collect();
    let path = |what: &str| failures_dir().join(format!("{file_stem}.{what}.png"));
    let (expected_path, actual_path) = (path("expected"), path("actual"));
    expected.write_png(&expected_path)?;
    actual.write_png(&actual_path)?;
    if !same_size {
        bail!(
            "{name}: expected a {}x{} image, got {}x{}; wrote {} and {}",
            expected.width(),
            expected.height(),
            actual.width(),
            actual.height(),
            expected_path.display(),
            actual_path.display()
        );
    }
    let diff_path = path("diff");
    diff_image(actual, &differing)?.write_png(&diff_path)?;
    let rows = rows.start.min(expected.height())..rows.end.min(expected.height());
    let compared = rows.len() * expected.width() as usize;
    let which_rows = if compared == expected.pixel_count() {
        String::new()
    } else {
        format!(" in rows {}..{}", rows.start, rows.end)
    };
    let first = differing[0] as u32;
    bail!(
        "{name}: {} of {compared} pixels{which_rows} differ (first at x={}, y={}); wrote {}, {} and {}",
        differing.len(),
        first % expected.width(),
        first / expected.width(),
        expected_path.display(),
        actual_path.display(),
        diff_path.display()
    )
}

/// Whether the images have the same size and are equal pixel for pixel
/// (as [`compare_images`] compares them) in rows `rows`. Writes nothing:
/// for polling a picture that is expected to change, and stops at the
/// first differing pixel (a poll tries many candidates that differ early).
pub fn images_match_in_rows(expected: &Image, actual: &Image, rows: Range<u32>) -> bool {
    same_size(expected, actual) && pixels_in_rows(expected, rows).all(|i| same_pixel(expected, actual, i))
}

/// How many pixels differ (as [`compare_images`] compares them): every
/// pixel of `expected` if the sizes differ. Writes nothing.
pub fn differing_pixel_count(expected: &Image, actual: &Image) -> usize {
    if !same_size(expected, actual) {
        return expected.pixel_count();
    }
    differing_pixels(expected, actual, 0..expected.height()).len()
}

/// How many DAC entries differ between two palettes (6-bit levels).
pub fn differing_palette_entries(expected: &[[u8; 3]; ENTRIES], actual: &[[u8; 3]; ENTRIES]) -> usize {
    expected.iter().zip(actual).filter(|(expected, actual)| expected != actual).count()
}

fn same_size(expected: &Image, actual: &Image) -> bool {
    (expected.width(), expected.height()) == (actual.width(), actual.height())
}

/// Row-major indices of the pixels in rows `rows` (cut at the height) that
/// differ between two images of the same size.
fn differing_pixels(expected: &Image, actual: &Image, rows: Range<u32>) -> Vec<usize> {
    pixels_in_rows(expected, rows).filter(|&i| !same_pixel(expected, actual, i)).collect()
}

/// Row-major indices of the pixels of `image` in rows `rows`, cut at its
/// height.
fn pixels_in_rows(image: &Image, rows: Range<u32>) -> Range<usize> {
    let width = image.width() as usize;
    let rows = rows.start.min(image.height()) as usize..rows.end.min(image.height()) as usize;
    rows.start * width..rows.end.max(rows.start) * width
}

/// Succeeds when two DAC palettes (6-bit levels) are equal entry for
/// entry; otherwise fails counting the differing entries and naming the
/// first. A palette has no picture to write: its values are the message.
pub fn compare_palettes(name: &str, expected: &[[u8; 3]; ENTRIES], actual: &[[u8; 3]; ENTRIES]) -> Result<()> {
    if let Some(first) = (0..ENTRIES).find(|&i| expected[i] != actual[i]) {
        bail!(
            "{name}: {} of {ENTRIES} DAC entries differ; entry {first} reads {:?}, expected {:?}",
            differing_palette_entries(expected, actual),
            actual[first],
            expected[first]
        );
    }
    Ok(())
}

fn same_pixel(expected: &Image, actual: &Image, i: usize) -> bool {
    match (expected.pixels(), actual.pixels()) {
        (Pixels::Indexed { indices: a, .. }, Pixels::Indexed { indices: b, .. }) => a[i] == b[i],
        _ => expected.color(i) == actual.color(i),
    }
}

fn diff_image(actual: &Image, differing: &[usize]) -> Result<Image> {
    let mut colors: Vec<Rgb> = (0..actual.pixel_count()).map(|i| actual.color(i).map(|c| c / 4)).collect();
    for &i in differing {
        colors[i] = DIFF_MARK;
    }
    Image::rgb(actual.width(), actual.height(), colors)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grey(levels: &[u8]) -> Image {
        Image::rgb(levels.len() as u32, 1, levels.iter().map(|&v| [v; 3]).collect()).unwrap()
    }

    #[test]
    fn equal_images_pass_and_write_nothing() {
        compare_images("unit-equal", &grey(&[1, 2, 3]), &grey(&[1, 2, 3])).unwrap();
        assert!(!failures_dir().join("unit-equal.diff.png").exists());
    }

    #[test]
    fn indexed_images_compare_by_index_even_when_colours_agree() {
        let palette = vec![[9, 9, 9], [9, 9, 9]];
        let a = Image::indexed(2, 1, vec![0, 1], palette.clone()).unwrap();
        let b = Image::indexed(2, 1, vec![0, 0], palette).unwrap();
        let error = compare_images("unit/indexed", &a, &b).unwrap_err().to_string();
        assert!(error.starts_with("unit/indexed: 1 of 2 pixels differ (first at x=1, y=0); wrote "), "{error}");
        let diff = Image::read_png(&failures_dir().join("unit_indexed.diff.png")).unwrap();
        assert_eq!(diff, Image::rgb(2, 1, vec![[2, 2, 2], DIFF_MARK]).unwrap());
        for what in ["expected", "actual", "diff"] {
            let path = failures_dir().join(format!("unit_indexed.{what}.png"));
            assert!(error.contains(&path.display().to_string()), "{error}");
            std::fs::remove_file(path).unwrap();
        }
    }

    #[test]
    fn differing_pixels_are_counted_and_a_size_mismatch_counts_them_all() {
        assert_eq!(differing_pixel_count(&grey(&[1, 2, 3]), &grey(&[1, 2, 3])), 0);
        assert_eq!(differing_pixel_count(&grey(&[1, 2, 3]), &grey(&[1, 0, 0])), 2);
        assert_eq!(differing_pixel_count(&grey(&[1, 2, 3]), &grey(&[1, 2])), 3);
    }

    #[test]
    fn palettes_compare_entry_by_entry() {
        let expected = [[1, 2, 3]; ENTRIES];
        compare_palettes("unit-dac", &expected, &expected).unwrap();
        let mut actual = expected;
        actual[7] = [0, 2, 3];
        actual[9] = [0; 3];
        let error = compare_palettes("unit-dac", &expected, &actual).unwrap_err().to_string();
        assert_eq!(error, "unit-dac: 2 of 256 DAC entries differ; entry 7 reads [0, 2, 3], expected [1, 2, 3]");
    }

    #[test]
    fn rows_outside_the_range_are_not_compared() {
        let a = Image::rgb(2, 3, vec![[0; 3], [1; 3], [2; 3], [3; 3], [4; 3], [5; 3]]).unwrap();
        let mut colors = vec![[9; 3], [1; 3], [2; 3], [3; 3], [9; 3], [5; 3]];
        let b = Image::rgb(2, 3, colors.clone()).unwrap();
        assert!(images_match_in_rows(&a, &b, 1..2));
        compare_image_rows("unit-rows", &a, &b, 1..2).unwrap();
        assert!(!images_match_in_rows(&a, &b, 1..3));
        assert!(!images_match_in_rows(&a, &b, 0..1));
        colors[3] = [0; 3];
        let c = Image::rgb(2, 3, colors).unwrap();
        let error = compare_image_rows("unit-rows", &a, &c, 1..9).unwrap_err().to_string();
        assert!(
            error.starts_with("unit-rows: 2 of 4 pixels in rows 1..3 differ (first at x=1, y=1); wrote "),
            "{error}"
        );
        for what in ["expected", "actual", "diff"] {
            std::fs::remove_file(failures_dir().join(format!("unit-rows.{what}.png"))).unwrap();
        }
    }

    #[test]
    fn different_sizes_are_reported_as_such() {
        let error = compare_images("unit-size", &grey(&[1, 2]), &grey(&[1])).unwrap_err().to_string();
        assert!(error.starts_with("unit-size: expected a 2x1 image, got 1x1"), "{error}");
        for what in ["expected", "actual"] {
            std::fs::remove_file(failures_dir().join(format!("unit-size.{what}.png"))).unwrap();
        }
    }
}
