//! Binary PPM (`P6`), the format QEMU's `screendump` writes.

use anyhow::{bail, ensure, Context, Result};

use super::Image;

/// Parses a `P6` file with 8-bit samples (maxval 1..=255, scaled to 255 as
/// netpbm specifies). Header fields are separated by whitespace and may be
/// interleaved with `#` comments; one whitespace byte ends the header.
pub fn parse_ppm(bytes: &[u8]) -> Result<Image> {
    let mut at = 0;
    let mut fields = [0u32; 3];
    ensure!(bytes.starts_with(b"P6"), "not a binary PPM: it does not start with `P6`");
    at += 2;
    for (field, name) in fields.iter_mut().zip(["width", "height", "maxval"]) {
        loop {
            match bytes.get(at) {
                Some(b) if b.is_ascii_whitespace() => at += 1,
                Some(b'#') => at += bytes[at..].iter().position(|&b| b == b'\n').context("PPM comment never ends")?,
                _ => break,
            }
        }
        let digits = bytes[at..].iter().take_while(|b| b.is_ascii_digit()).count();
        ensure!(digits > 0, "PPM header: expected the {name} at byte {at}");
        *field = std::str::from_utf8(&bytes[at..at + digits])?
            .parse()
            .with_context(|| format!("PPM {name} out of range"))?;
        at += digits;
    }
    let [width, height, maxval] = fields;
    match bytes.get(at) {
        Some(b) if b.is_ascii_whitespace() => at += 1,
        _ => bail!("PPM header: no whitespace after the maxval"),
    }
    ensure!((1..=255).contains(&maxval), "PPM maxval {maxval}: only 8-bit samples are read");
    let data = &bytes[at..];
    let expected = width as usize * height as usize * 3;
    ensure!(data.len() == expected, "PPM {width}x{height} needs {expected} bytes of samples, has {}", data.len());
    let scale = |v: u8| (u32::from(v) * 255 / maxval) as u8;
    Image::rgb(width, height, data.as_chunks::<3>().0.iter().map(|rgb| rgb.map(scale)).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn qemu_style_ppm_is_read() {
        let mut bytes = b"P6\n2 1\n255\n".to_vec();
        bytes.extend([1, 2, 3, 250, 251, 252]);
        assert_eq!(parse_ppm(&bytes).unwrap(), Image::rgb(2, 1, vec![[1, 2, 3], [250, 251, 252]]).unwrap());
    }

    #[test]
    fn comments_and_odd_whitespace_are_allowed_and_samples_may_be_binary_whitespace() {
        let mut bytes = b"P6 # made by hand\n 1\t# width\n1 15\r".to_vec();
        bytes.extend([b'\n', 15, 0]);
        assert_eq!(parse_ppm(&bytes).unwrap(), Image::rgb(1, 1, vec![[170, 255, 0]]).unwrap());
    }

    #[test]
    fn bad_files_are_refused_with_a_reason() {
        let error = |bytes: &[u8]| parse_ppm(bytes).unwrap_err().to_string();
        assert!(error(b"P3\n1 1\n255\n000").contains("P6"));
        assert!(error(b"P6\n1\n").contains("height"));
        assert!(error(b"P6\n1 1 65535\n\0\0\0\0\0\0").contains("8-bit"));
        assert!(error(b"P6\n2 2\n255\n\0\0\0").contains("needs 12 bytes"));
    }
}
