//! The labels over a frame, in the 8x8 bitmap font of the `font8x8` crate
//! (the public-domain IBM PC-style font, its `BASIC_LEGACY` table).
//!
//! The top line names the entry, and for an animation the frame counter
//! on the right; the bottom line names the method, and the cycles its draw
//! took on the right. Text is white on top, yellow below, every glyph
//! pixel ringed by black on all eight sides so it reads on any colour. The
//! lines are formatted into fixed buffers on the stack through
//! [`core::fmt::Write`], cut at the screen's width: nothing is allocated.

use core::fmt::{self, Write};

use font8x8::legacy::BASIC_LEGACY;

use super::entries::Entry;
use raster::SpanSink;

/// A glyph's width and height in pixels.
const GLYPH: i32 = 8;
/// Characters that fit in a line.
const COLUMNS: usize = (raster::SCREEN.width / GLYPH) as usize;
/// Where the glyphs' top rows are: one pixel in from the screen's top and
/// bottom edges, leaving a row for the outline.
const TOP_ROW: i32 = 1;
const BOTTOM_ROW: i32 = raster::SCREEN.height - 1 - GLYPH;
/// Left edge of left-aligned text, and right margin of right-aligned text.
const MARGIN: i32 = 1;
const TOP_COLOR: u8 = 15;
const BOTTOM_COLOR: u8 = 14;
const OUTLINE_COLOR: u8 = 0;

/// Draws the entry's name and frame counter at the top of `target`, the
/// method's name and `cycles` at the bottom. `frame` counts from 0.
pub(super) fn draw_labels(target: &mut dyn SpanSink, entry: &Entry, frame: u32, method: &str, cycles: u64) {
    let mut counter = Line::new();
    if entry.is_animated() {
        // Writing into a `Line` never fails: it cuts instead.
        let _ = write!(counter, "{}/{}", frame.saturating_add(1), entry.frames);
    }
    draw_line(target, TOP_ROW, entry.name, &counter, TOP_COLOR);
    let mut cost = Line::new();
    let _ = write!(cost, "{cycles} cyc");
    draw_line(target, BOTTOM_ROW, method, &cost, BOTTOM_COLOR);
}

/// Draws `top` at the top of `target`, `bottom_left` and `bottom_right` at
/// its bottom, as [`draw_labels`] draws an entry's: a caption in the show's
/// letters for a picture that is no entry of the show.
pub(super) fn draw_caption(target: &mut dyn SpanSink, top: &str, bottom_left: &str, bottom_right: &str) {
    draw_line(target, TOP_ROW, top, &Line::new(), TOP_COLOR);
    let mut right = Line::new();
    let _ = right.write_str(bottom_right);
    draw_line(target, BOTTOM_ROW, bottom_left, &right, BOTTOM_COLOR);
}

/// `left` from the left margin and `right` up to the right margin on the
/// line whose glyphs start at row `y`; `left` is cut short to leave a blank
/// column before `right`.
fn draw_line(target: &mut dyn SpanSink, y: i32, left: &str, right: &Line, color: u8) {
    let mut line = Line::new();
    let _ = line.write_str(left);
    let room = if right.len == 0 { COLUMNS } else { COLUMNS.saturating_sub(right.len + 1) };
    line.len = line.len.min(room);
    draw_text(target, MARGIN, y, line.text(), color);
    let right_x = raster::SCREEN.width - MARGIN - GLYPH * right.len as i32;
    draw_text(target, right_x, y, right.text(), color);
}

/// Up to [`COLUMNS`] characters, ASCII only (anything else becomes `?`),
/// filled by [`core::fmt::Write`]; what does not fit is dropped.
struct Line {
    bytes: [u8; COLUMNS],
    len: usize,
}

impl Line {
    const fn new() -> Self {
        Self { bytes: [0; COLUMNS], len: 0 }
    }

    fn text(&self) -> &[u8] {
        &self.bytes[..self.len]
    }
}

impl Write for Line {
    fn write_str(&mut self, s: &str) -> fmt::Result {
        for (slot, c) in self.bytes[self.len..].iter_mut().zip(s.chars()) {
            *slot = if c.is_ascii() { c as u8 } else { b'?' };
            self.len += 1;
        }
        Ok(())
    }
}

/// Draws ASCII `text` with its first glyph's top-left corner at (`x`, `y`):
/// first the black outline of every glyph, then the glyphs in `color`, so
/// that one glyph's outline never cuts into its neighbour.
fn draw_text(target: &mut dyn SpanSink, x: i32, y: i32, text: &[u8], color: u8) {
    for (px, py) in lit_pixels(x, y, text) {
        for dy in -1..=1 {
            put(target, px - 1, py + dy, px + 2, OUTLINE_COLOR);
        }
    }
    for (px, py) in lit_pixels(x, y, text) {
        put(target, px, py, px + 1, color);
    }
}

/// The pixels `text`'s glyphs light when drawn from (`x`, `y`). A glyph row
/// is a byte whose bit 0 is the leftmost pixel.
fn lit_pixels(x: i32, y: i32, text: &[u8]) -> impl Iterator<Item = (i32, i32)> + '_ {
    (x..).step_by(GLYPH as usize).zip(text).flat_map(move |(gx, &c)| {
        let glyph = BASIC_LEGACY[usize::from(c) % BASIC_LEGACY.len()];
        (0..GLYPH).zip(glyph).flat_map(move |(row, bits)| {
            (0..GLYPH).filter(move |col| bits >> col & 1 == 1).map(move |col| (gx + col, y + row))
        })
    })
}

/// Pixels `x_start..x_end` of row `y` in `color`, cut to the target.
fn put(target: &mut dyn SpanSink, x_start: i32, y: i32, x_end: i32, color: u8) {
    let size = target.size();
    let (x0, x1) = (x_start.max(0), x_end.min(size.width));
    if (0..size.height).contains(&y) && x0 < x1 {
        target.span(y, x0, x1, color);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::show::entries::{entry, ENTRIES_IN_ORDER};
    use raster::stores;
    use raster::{Framebuffer, SCREEN};

    const BACKGROUND: u8 = 3;

    fn screen() -> Framebuffer {
        let mut target = Framebuffer::new(SCREEN);
        stores::clear(&mut target, BACKGROUND);
        target
    }

    /// The rows a label may touch: its glyphs and their outline.
    fn in_label_rows(y: i32) -> bool {
        (TOP_ROW - 1..=TOP_ROW + GLYPH).contains(&y) || (BOTTOM_ROW - 1..=BOTTOM_ROW + GLYPH).contains(&y)
    }

    #[test]
    fn a_glyph_lights_its_pixels_and_is_outlined() {
        const A: [&str; 8] =
            ["..##....", ".####...", "##..##..", "##..##..", "######..", "##..##..", "##..##..", "........"];
        let mut target = screen();
        draw_text(&mut target, 10, 20, b"A", 15);
        for (row, pattern) in (0..).zip(A) {
            for (col, cell) in (0..).zip(pattern.bytes()) {
                let pixel = target.get(10 + col, 20 + row).unwrap();
                assert_eq!(pixel == 15, cell == b'#', "({col}, {row}) is {pixel}");
            }
        }
        // Black between the legs and beside them; untouched further out.
        assert_eq!(target.get(12, 22), Some(OUTLINE_COLOR));
        assert_eq!(target.get(9, 22), Some(OUTLINE_COLOR));
        assert_eq!(target.get(8, 22), Some(BACKGROUND));
        assert_eq!(target.get(12, 18), Some(BACKGROUND));
    }

    #[test]
    fn labels_stay_in_their_rows() {
        let race = entry("race").unwrap();
        let mut target = screen();
        draw_labels(&mut target, race, 41, "lamothe_fixed", u64::MAX);
        let mut touched = 0;
        for y in 0..SCREEN.height {
            for x in 0..SCREEN.width {
                if target.get(x, y) != Some(BACKGROUND) {
                    assert!(in_label_rows(y), "({x}, {y})");
                    touched += 1;
                }
            }
        }
        assert!(touched > 0);
        assert_eq!(target.stray_spans(), 0);
    }

    #[test]
    fn long_text_is_cut_not_a_panic() {
        const NAME: &str =
            "a name far longer than the forty characters of a line of mode 13h text, with a \u{e9} in it";
        const LONG: Entry = Entry { name: NAME, ..ENTRIES_IN_ORDER[0] };
        let animated = Entry { frames: u32::MAX, ..LONG };
        for entry in [&LONG, &animated] {
            for frame in [0, u32::MAX] {
                let mut target = screen();
                draw_labels(&mut target, entry, frame, LONG.name, u64::MAX);
                assert_eq!(target.stray_spans(), 0);
                // The counter keeps its place at the right edge.
                if entry.is_animated() {
                    assert_ne!(target.get(SCREEN.width - 4, TOP_ROW + 3), Some(BACKGROUND));
                }
            }
        }
    }

    #[test]
    fn lines_format_cut_and_replace() {
        let mut line = Line::new();
        write!(line, "{} cyc", 1234567u64).unwrap();
        assert_eq!(line.text(), b"1234567 cyc");
        write!(line, " \u{e9}{}", "x".repeat(100)).unwrap();
        assert_eq!(line.len, COLUMNS);
        assert_eq!(&line.text()[..14], b"1234567 cyc ?x");
    }

    #[test]
    fn still_entries_have_no_frame_counter() {
        let still = entry("wgt-triangle").unwrap();
        let animated = entry("lamothe-rotate").unwrap();
        let right_edge = |entry: &Entry| {
            let mut target = screen();
            draw_labels(&mut target, entry, 0, "wgt", 7);
            (SCREEN.width - 40..SCREEN.width).filter(|&x| target.get(x, TOP_ROW + 3) != Some(BACKGROUND)).count()
        };
        assert_eq!(right_edge(still), 0);
        assert!(right_edge(animated) > 0);
        let mut target = screen();
        draw_labels(&mut target, still, 0, "wgt", 7);
        assert!(target.pixels().contains(&TOP_COLOR) && target.pixels().contains(&BOTTOM_COLOR));
    }
}
