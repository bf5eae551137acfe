//! What an import is asked for: the flattening tolerance, the part of the
//! drawing that fills the screen, and whose palette the colours go to.

use std::fmt;
use std::str::FromStr;

use anyhow::{anyhow, bail, ensure, Result};

/// How an SVG becomes a scene.
#[derive(Clone, Debug, PartialEq)]
pub struct Options {
    /// The most a flattened curve or stroke outline may stray from the
    /// true one, in screen pixels, before snapping to the 1/256 grid.
    pub tolerance: f64,
    /// The part of the drawing that is fitted to the screen, in the SVG's
    /// user units; `None` for the SVG's own `viewBox` (or, without one,
    /// its width and height).
    pub view_box: Option<ViewBox>,
    /// Whose palette the colours take.
    pub palette: PaletteChoice,
}

impl Options {
    /// The tolerance when none is given, in screen pixels.
    pub const DEFAULT_TOLERANCE: f64 = 0.1;
    /// The finest tolerance taken: one step of the 1/256 grid the
    /// vertices snap to; a finer one would only add vertices.
    pub const FINEST_TOLERANCE: f64 = 1.0 / 256.0;

    /// The tolerance and the view box checked: an error saying what is
    /// wrong with them.
    pub(crate) fn check(&self) -> Result<()> {
        ensure!(
            self.tolerance.is_finite() && self.tolerance >= Self::FINEST_TOLERANCE,
            "the tolerance must be a number of pixels no finer than 1/256 (0.00390625), not {}",
            self.tolerance
        );
        if let Some(view_box) = &self.view_box {
            view_box.check()?;
        }
        Ok(())
    }
}

impl Default for Options {
    fn default() -> Self {
        Self { tolerance: Self::DEFAULT_TOLERANCE, view_box: None, palette: PaletteChoice::Own }
    }
}

/// Whose palette an imported scene's colours take.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PaletteChoice {
    /// The scene's own: each distinct colour (at 6 bits a channel) gets an
    /// entry from 1 up, 0 staying the black background; past 255 of them
    /// the nearest are merged.
    Own,
    /// The VGA default palette: each colour is drawn with its nearest
    /// entry, and the scene sets none.
    VgaDefault,
}

impl FromStr for PaletteChoice {
    type Err = anyhow::Error;

    /// `own` or `vga`.
    fn from_str(text: &str) -> Result<Self> {
        match text {
            "own" => Ok(PaletteChoice::Own),
            "vga" => Ok(PaletteChoice::VgaDefault),
            other => bail!("unknown palette `{other}`; the palettes are own, vga"),
        }
    }
}

impl fmt::Display for PaletteChoice {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            PaletteChoice::Own => "own",
            PaletteChoice::VgaDefault => "vga",
        })
    }
}

/// A rectangle of the drawing in the SVG's user units: its top left
/// corner, its width and its height.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ViewBox {
    pub x: f64,
    pub y: f64,
    pub width: f64,
    pub height: f64,
}

impl ViewBox {
    /// Finite, with a width and a height above zero; an error otherwise.
    fn check(&self) -> Result<()> {
        let ViewBox { x, y, width, height } = *self;
        ensure!(
            [x, y, width, height].iter().all(|v| v.is_finite()) && width > 0.0 && height > 0.0,
            "the view box {self} needs finite numbers and a width and height above 0"
        );
        Ok(())
    }
}

impl FromStr for ViewBox {
    type Err = anyhow::Error;

    /// `X,Y,W,H`.
    fn from_str(text: &str) -> Result<Self> {
        let numbers: Vec<f64> = text
            .split(',')
            .map(|word| word.trim().parse::<f64>())
            .collect::<Result<_, _>>()
            .map_err(|_| anyhow!("bad view box `{text}` (expected X,Y,W,H in the SVG's user units)"))?;
        let [x, y, width, height] = numbers[..] else {
            bail!("bad view box `{text}` (expected four numbers, X,Y,W,H)");
        };
        let view_box = ViewBox { x, y, width, height };
        view_box.check()?;
        Ok(view_box)
    }
}

impl fmt::Display for ViewBox {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{},{},{},{}", self.x, self.y, self.width, self.height)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_view_box_reads_four_numbers_and_refuses_an_empty_one() {
        assert_eq!(
            "-10, 5.5,100,50".parse::<ViewBox>().unwrap(),
            ViewBox { x: -10.0, y: 5.5, width: 100.0, height: 50.0 }
        );
        for (text, error) in [
            ("1,2,3", "expected four numbers"),
            ("1,2,3,4,5", "expected four numbers"),
            ("1,2,x,4", "expected X,Y,W,H"),
            ("0,0,0,10", "a width and height above 0"),
            ("0,0,10,-1", "a width and height above 0"),
            ("0,0,inf,10", "needs finite numbers"),
            ("NaN,0,10,10", "needs finite numbers"),
        ] {
            let message = format!("{:#}", text.parse::<ViewBox>().unwrap_err());
            assert!(message.contains(error), "{text}: {message}");
        }
    }

    #[test]
    fn the_palettes_are_named_own_and_vga() {
        for choice in [PaletteChoice::Own, PaletteChoice::VgaDefault] {
            assert_eq!(choice.to_string().parse::<PaletteChoice>().unwrap(), choice);
        }
        let error = "default".parse::<PaletteChoice>().unwrap_err().to_string();
        assert_eq!(error, "unknown palette `default`; the palettes are own, vga");
    }

    #[test]
    fn a_tolerance_finer_than_the_grid_or_not_a_number_is_refused() {
        let with = |tolerance| Options { tolerance, ..Options::default() }.check();
        assert!(with(Options::DEFAULT_TOLERANCE).is_ok());
        assert!(with(Options::FINEST_TOLERANCE).is_ok());
        for bad in [0.0, -1.0, 0.001, f64::NAN, f64::INFINITY] {
            let message = with(bad).unwrap_err().to_string();
            assert!(message.starts_with("the tolerance must be a number of pixels no finer than 1/256"), "{message}");
        }
        let view_box = Some(ViewBox { x: 0.0, y: 0.0, width: 0.0, height: 1.0 });
        assert!(Options { view_box, ..Options::default() }.check().is_err());
    }
}
