//! The polygons' colours as palette indices: in a palette of the scene's
//! own (each distinct colour at 6 bits a channel an entry, the nearest
//! merged past 255 of them), or the VGA default's nearest entries.

use scenes::palette::{Palette, MAX_LEVEL, VGA_DEFAULT};
use scenes::PaletteEntry;

use crate::paint::Rgb;

/// The entries a scene's own palette gives colours: every one but 0, the
/// background the scene clears to.
const OWN_ENTRIES: usize = 255;

/// Each polygon's colour index, the entries the scene sets and what is
/// worth saying about them.
pub(crate) struct Indexed {
    pub(crate) indices: Vec<u8>,
    pub(crate) palette: Vec<PaletteEntry>,
    pub(crate) notes: Vec<String>,
}

/// An 8-bit channel at the DAC's 6 bits, to the nearest level.
pub(crate) fn level(channel: u8) -> u8 {
    ((u32::from(channel) * u32::from(MAX_LEVEL) + 127) / 255) as u8
}

/// `colours` (one per polygon) in a palette of their own: entries 1, 2,
/// ... in the order the colours first appear, each a distinct colour at
/// 6 bits a channel; with more than 255 of them, the two nearest are
/// merged (weighted by their polygons) until 255 are left, and a note
/// says how far that moved a colour.
pub(crate) fn own(colours: &[Rgb]) -> Indexed {
    let levels: Vec<[u8; 3]> = colours.iter().map(|rgb| rgb.map(level)).collect();
    let mut distinct: Vec<[u8; 3]> = Vec::new();
    let mut weights: Vec<u64> = Vec::new();
    let mut of_polygon = Vec::with_capacity(levels.len());
    for colour in &levels {
        let at = match distinct.iter().position(|known| known == colour) {
            Some(at) => at,
            None => {
                distinct.push(*colour);
                weights.push(0);
                distinct.len() - 1
            }
        };
        weights[at] += 1;
        of_polygon.push(at);
    }
    let mut notes = Vec::new();
    let merged = merge_nearest(&distinct, &weights, OWN_ENTRIES);
    if distinct.len() > OWN_ENTRIES {
        let moved =
            distinct.iter().zip(&merged.of_colour).map(|(colour, &entry)| distance(*colour, merged.colours[entry]));
        notes.push(format!(
            "{} distinct colours at 6 bits a channel, more than the palette's {OWN_ENTRIES} entries beside the \
             background: the nearest merged until {OWN_ENTRIES} were left, moving a colour by at most {:.1} levels",
            distinct.len(),
            moved.fold(0.0, f64::max)
        ));
    }
    let palette: Vec<PaletteEntry> =
        (1..=u8::MAX).zip(&merged.colours).map(|(index, &rgb)| PaletteEntry { index, rgb }).collect();
    let indices: Vec<u8> = of_polygon.iter().map(|&at| palette[merged.of_colour[at]].index).collect();
    notes.extend(black_note(&indices, &palette_of(&palette)));
    Indexed { indices, palette, notes }
}

/// `colours` as the nearest entries of the VGA default palette (the
/// lowest index of equals), which the scene then leaves as it is.
pub(crate) fn vga_default(colours: &[Rgb]) -> Indexed {
    let indices: Vec<u8> = colours
        .iter()
        .map(|rgb| {
            let colour = rgb.map(level);
            let nearest = (0..VGA_DEFAULT.len()).min_by_key(|&index| square_distance(colour, VGA_DEFAULT[index]));
            nearest.map_or(0, |index| index as u8)
        })
        .collect();
    let notes = black_note(&indices, &VGA_DEFAULT).into_iter().collect();
    Indexed { indices, palette: Vec::new(), notes }
}

/// The DAC the scene's entries make over the default.
fn palette_of(entries: &[PaletteEntry]) -> Palette {
    let mut dac = VGA_DEFAULT;
    for entry in entries {
        dac[usize::from(entry.index)] = entry.rgb;
    }
    dac
}

/// A note if some polygons are black as the background (entry 0 of the
/// default palette, which `clear 0` fills with) is.
fn black_note(indices: &[u8], dac: &Palette) -> Option<String> {
    let black = indices.iter().filter(|&&index| dac[usize::from(index)] == VGA_DEFAULT[0]).count();
    (black > 0).then(|| {
        format!(
            "{black} of the {} polygons are black, the background's colour: they show only where they cover others",
            indices.len()
        )
    })
}

/// Colours merged into fewer.
struct Merged {
    /// The colours left, in the order of their first member.
    colours: Vec<[u8; 3]>,
    /// For each colour given, its place in `colours`.
    of_colour: Vec<usize>,
}

/// `colours` (each with a weight) merged, the nearest two at a time
/// (the first pair of equals), into at most `most`: each merged colour
/// is its members' weighted mean. Each colour keeps its nearest other,
/// refreshed only where a merge changed it.
fn merge_nearest(colours: &[[u8; 3]], weights: &[u64], most: usize) -> Merged {
    let count = colours.len();
    let mut mean: Vec<[u8; 3]> = colours.to_vec();
    let mut sums: Vec<[u64; 3]> = colours.iter().zip(weights).map(|(c, &w)| c.map(|v| u64::from(v) * w)).collect();
    let mut weight: Vec<u64> = weights.to_vec();
    let mut owner: Vec<usize> = (0..count).collect();
    let mut alive = vec![true; count];
    let nearest_to = |at: usize, mean: &[[u8; 3]], alive: &[bool]| -> (u32, usize) {
        (0..count)
            .filter(|&other| other != at && alive[other])
            .map(|other| (square_distance(mean[at], mean[other]), other))
            .min()
            .unwrap_or((u32::MAX, at))
    };
    let mut nearest: Vec<(u32, usize)> =
        if count > most { (0..count).map(|at| nearest_to(at, &mean, &alive)).collect() } else { Vec::new() };
    for _ in most..count {
        let Some(keep) = (0..count).filter(|&at| alive[at]).min_by_key(|&at| (nearest[at], at)) else { break };
        let gone = nearest[keep].1;
        let (keep, gone) = (keep.min(gone), keep.max(gone));
        alive[gone] = false;
        for channel in 0..3 {
            sums[keep][channel] += sums[gone][channel];
        }
        weight[keep] += weight[gone];
        mean[keep] = sums[keep].map(|sum| ((sum + weight[keep] / 2) / weight[keep]) as u8);
        for at in owner.iter_mut().filter(|at| **at == gone) {
            *at = keep;
        }
        nearest[keep] = nearest_to(keep, &mean, &alive);
        for at in (0..count).filter(|&at| alive[at] && at != keep) {
            let (_, other) = nearest[at];
            if other == keep || other == gone {
                nearest[at] = nearest_to(at, &mean, &alive);
            } else {
                nearest[at] = nearest[at].min((square_distance(mean[at], mean[keep]), keep));
            }
        }
    }
    let survivors: Vec<usize> = (0..count).filter(|&at| alive[at]).collect();
    let place = |at: usize| survivors.binary_search(&at).unwrap_or(0);
    Merged {
        colours: survivors.iter().map(|&at| mean[at]).collect(),
        of_colour: owner.iter().map(|&at| place(at)).collect(),
    }
}

fn square_distance(a: [u8; 3], b: [u8; 3]) -> u32 {
    a.iter().zip(b).map(|(&x, y)| (i32::from(x) - i32::from(y)).pow(2) as u32).sum()
}

fn distance(a: [u8; 3], b: [u8; 3]) -> f64 {
    f64::from(square_distance(a, b)).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_level_survives_the_trip_through_8_bits() {
        for v in 0..=MAX_LEVEL {
            let channel = ((u32::from(v) * 255 + 31) / 63) as u8;
            assert_eq!(level(channel), v, "{channel}");
        }
        assert_eq!((level(0), level(2), level(3), level(255)), (0, 0, 1, 63));
    }

    #[test]
    fn distinct_colours_get_entries_from_1_in_order_and_equal_ones_share() {
        let indexed = own(&[[255, 0, 0], [0, 0, 255], [254, 1, 0], [255, 0, 0]]);
        // 254 and 1 are 63 and 0 at 6 bits: the same entry as pure red.
        assert_eq!(indexed.indices, [1, 2, 1, 1]);
        let entry = |index, rgb| PaletteEntry { index, rgb };
        assert_eq!(indexed.palette, [entry(1, [63, 0, 0]), entry(2, [0, 0, 63])]);
        assert!(indexed.notes.is_empty(), "{:?}", indexed.notes);
    }

    #[test]
    fn past_255_colours_the_nearest_merge_and_a_note_says_so() {
        // 300 colours, each exactly a 6-bit colour and all distinct:
        // 64 reds at each of 5 greens (the last row short).
        let eight_bit = |level: u32| ((level * 255 + 31) / 63) as u8;
        let colours: Vec<Rgb> = (0..300).map(|i| [eight_bit(i % 64), eight_bit(i / 64 * 10), 0]).collect();
        let indexed = own(&colours);
        assert_eq!(indexed.palette.len(), 255);
        assert_eq!(indexed.palette.last().unwrap().index, 255);
        assert!(indexed.indices.iter().all(|&i| i >= 1));
        let note = &indexed.notes[0];
        assert!(note.starts_with("300 distinct colours at 6 bits a channel, more than the palette's 255 "), "{note}");
        // Neighbours one level apart merge first: no colour moves far.
        let mut farthest: f64 = 0.0;
        for (colour, &index) in colours.iter().zip(&indexed.indices) {
            let shown = indexed.palette[usize::from(index) - 1].rgb;
            farthest = farthest.max(distance(colour.map(level), shown));
        }
        assert!(farthest <= 2.0, "{farthest}");
        assert!(note.ends_with(&format!("moving a colour by at most {farthest:.1} levels")), "{note}");
    }

    #[test]
    fn merging_takes_the_nearest_pair_and_weighs_the_mean() {
        let colours = [[0, 0, 0], [10, 0, 0], [40, 0, 0], [43, 0, 0], [63, 63, 63]];
        let merged = merge_nearest(&colours, &[1, 1, 2, 1, 1], 4);
        // 40 and 43 are nearest; their mean weighs 40 twice: 41.
        assert_eq!(merged.colours, [[0, 0, 0], [10, 0, 0], [41, 0, 0], [63, 63, 63]]);
        assert_eq!(merged.of_colour, [0, 1, 2, 2, 3]);
        let merged = merge_nearest(&colours, &[1; 5], 2);
        assert_eq!(merged.colours, [[23, 0, 0], [63, 63, 63]]);
        assert_eq!(merged.of_colour, [0, 0, 0, 0, 1]);
    }

    #[test]
    fn the_vga_palette_takes_the_nearest_entry_and_sets_none() {
        // Pure red is entry 40's (63,0,0), not 4's (42,0,0); white is 15's
        // and 31's; 170 is 42 levels, entry 1's blue.
        let indexed = vga_default(&[[255, 0, 0], [0, 0, 0], [255, 255, 255], [0, 0, 170]]);
        assert_eq!(indexed.indices, [40, 0, 15, 1]);
        assert!(indexed.palette.is_empty());
        assert_eq!(
            indexed.notes,
            ["1 of the 4 polygons are black, the background's colour: they show only where they cover others"]
        );
    }
}
