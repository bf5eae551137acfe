//! The show's palette: the VGA default below four colour ramps for
//! shading and textures.

use crate::palette::{ENTRIES, VGA_DEFAULT};

/// First palette index of the show's colour ramps.
pub const RAMP_BASE: u8 = 128;
/// Levels per ramp, darkest first.
pub const RAMP_LEVELS: u8 = 32;

/// The show's four colour ramps, at `RAMP_BASE + ramp * RAMP_LEVELS`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ramp {
    Red = 0,
    Green = 1,
    Blue = 2,
    Gold = 3,
}

impl Ramp {
    /// The palette index of `level` (clamped to `0..RAMP_LEVELS`).
    pub const fn color(self, level: i32) -> u8 {
        let level = if level < 0 {
            0
        } else if level >= RAMP_LEVELS as i32 {
            RAMP_LEVELS as i32 - 1
        } else {
            level
        };
        RAMP_BASE + self as u8 * RAMP_LEVELS + level as u8
    }

    /// Full-brightness colour, 6-bit red, green, blue.
    const fn top(self) -> [u8; 3] {
        match self {
            Ramp::Red => [63, 12, 8],
            Ramp::Green => [10, 63, 16],
            Ramp::Blue => [12, 28, 63],
            Ramp::Gold => [63, 52, 12],
        }
    }

    /// The ramp palette index `color` belongs to, if any: what the tests
    /// read a frame's colours back as.
    #[cfg(test)]
    pub(super) fn of(color: u8) -> Option<Ramp> {
        let ramps = [Ramp::Red, Ramp::Green, Ramp::Blue, Ramp::Gold];
        color.checked_sub(RAMP_BASE).map(|i| ramps[usize::from(i / RAMP_LEVELS)])
    }
}

/// The show's palette: the VGA default for entries 0-127 (every still page
/// uses only those) and four ramps of [`RAMP_LEVELS`] from black to full
/// colour in 128-255, for shading and textures.
pub const PALETTE: [[u8; 3]; ENTRIES] = {
    let mut palette = VGA_DEFAULT;
    let ramps = [Ramp::Red, Ramp::Green, Ramp::Blue, Ramp::Gold];
    let mut r = 0;
    while r < ramps.len() {
        let top = ramps[r].top();
        let mut level = 0;
        while level < RAMP_LEVELS as usize {
            let mut c = 0;
            while c < 3 {
                // Linear from black (level 0) to `top` (the last level).
                let value = top[c] as usize * level / (RAMP_LEVELS as usize - 1);
                palette[ramps[r].color(level as i32) as usize][c] = value as u8;
                c += 1;
            }
            level += 1;
        }
        r += 1;
    }
    palette
};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_palette_keeps_the_vga_default_below_the_ramps_and_ramps_climb() {
        assert_eq!(PALETTE[..usize::from(RAMP_BASE)], VGA_DEFAULT[..usize::from(RAMP_BASE)]);
        for ramp in [Ramp::Red, Ramp::Green, Ramp::Blue, Ramp::Gold] {
            assert_eq!(PALETTE[usize::from(ramp.color(0))], [0, 0, 0]);
            assert_eq!(PALETTE[usize::from(ramp.color(i32::MAX))], ramp.top());
            for level in 1..i32::from(RAMP_LEVELS) {
                let (below, here) =
                    (PALETTE[usize::from(ramp.color(level - 1))], PALETTE[usize::from(ramp.color(level))]);
                assert!((0..3).all(|c| below[c] <= here[c]), "{ramp:?} level {level}");
            }
        }
        assert_eq!(Ramp::Gold.color(-5), Ramp::Gold.color(0));
    }
}
