//! The plain-text scene format (documented in `docs/scenes.md#scene-files`):
//!
//! ```text
//! # a comment; blank lines are ignored
//! clear 3
//! poly color=6 10,10 100.5,10 60,80.25
//! poly color=5 rule=nonzero 0,0 320,0 320,200 0,200 | 50,50 50,150 270,150 270,50
//! palette 16 63,32,0 0,0,21
//! ```
//!
//! `poly` takes `color=` (0-255, required), `rule=evenodd|nonzero`
//! (default evenodd) and vertices `x,y` in pixels, decimals allowed; `|`
//! starts another contour of the same polygon. Coordinates are snapped to
//! 1/256 pixel, rounding to nearest (halves up). `palette I r,g,b ...`
//! sets DAC entries I, I+1, ... (6-bit levels, 0-63) over the VGA default
//! palette, for the whole scene wherever the line stands.

use alloc::string::String;
use alloc::vec::Vec;
use core::fmt::{self, Write};

use raster::{FillRule, Point, Polygon, SUBPIXEL_BITS, SUBPIXEL_ONE};

use crate::palette::{ENTRIES, MAX_LEVEL};
use crate::scene::{Op, PaletteEntry, Scene, FILE_METHOD};

/// What is wrong with one line.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum LineError {
    UnknownKeyword(String),
    MissingColor,
    BadColor(String),
    BadRule(String),
    BadVertex(String),
    CoordinateOutOfRange(String),
    UnknownOption(String),
    EmptyContour,
    Extra(String),
    BadPaletteIndex(String),
    BadLevels(String),
    /// `palette` with no index or no colour after it.
    MissingLevels,
    /// A `palette` line's colours run past the last entry.
    PaletteTooLong,
    /// A control character other than a tab between the words, which the
    /// protocol's command line would not carry.
    ControlCharacter(char),
}

impl fmt::Display for LineError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            LineError::UnknownKeyword(w) => {
                write!(f, "unknown keyword `{w}` (expected `clear`, `poly` or `palette`)")
            }
            LineError::MissingColor => write!(f, "`poly` needs `color=N`"),
            LineError::BadColor(w) => write!(f, "bad colour `{w}` (expected 0-255)"),
            LineError::BadRule(w) => write!(f, "bad rule `{w}` (expected evenodd or nonzero)"),
            LineError::BadVertex(w) => write!(f, "bad vertex `{w}` (expected x,y)"),
            LineError::CoordinateOutOfRange(w) => {
                write!(f, "coordinate `{w}` out of range (|v| < 8388608 pixels)")
            }
            LineError::UnknownOption(w) => write!(f, "unknown option `{w}`"),
            LineError::EmptyContour => write!(f, "empty contour around `|`"),
            LineError::Extra(w) => write!(f, "unexpected `{w}`"),
            LineError::BadPaletteIndex(w) => write!(f, "bad palette index `{w}` (expected 0-255)"),
            LineError::BadLevels(w) => write!(f, "bad palette colour `{w}` (expected r,g,b, each 0-63)"),
            LineError::MissingLevels => write!(f, "`palette` needs an index and at least one r,g,b"),
            LineError::PaletteTooLong => write!(f, "palette colours run past entry 255"),
            LineError::ControlCharacter(c) => {
                write!(f, "control character U+{:04X} (words are separated by spaces and tabs)", u32::from(*c))
            }
        }
    }
}

/// The error a [`LineError`] text around a word is, made from the word.
type OfWord = fn(String) -> LineError;

/// The texts [`LineError`]'s `Display` writes around a word: what comes
/// before it, what after, and the error of that word.
const AROUND_A_WORD: [(&str, &str, OfWord); 9] = [
    ("unknown keyword `", "` (expected `clear`, `poly` or `palette`)", LineError::UnknownKeyword),
    ("bad colour `", "` (expected 0-255)", LineError::BadColor),
    ("bad rule `", "` (expected evenodd or nonzero)", LineError::BadRule),
    ("bad vertex `", "` (expected x,y)", LineError::BadVertex),
    ("coordinate `", "` out of range (|v| < 8388608 pixels)", LineError::CoordinateOutOfRange),
    ("unknown option `", "`", LineError::UnknownOption),
    ("unexpected `", "`", LineError::Extra),
    ("bad palette index `", "` (expected 0-255)", LineError::BadPaletteIndex),
    ("bad palette colour `", "` (expected r,g,b, each 0-63)", LineError::BadLevels),
];

impl LineError {
    /// Reads back the text `Display` writes (the kernel answers a `POLY`
    /// whose polygon does not parse with it); `None` for any other text.
    pub fn parse(text: &str) -> Option<Self> {
        let error = match text {
            "`poly` needs `color=N`" => LineError::MissingColor,
            "empty contour around `|`" => LineError::EmptyContour,
            "`palette` needs an index and at least one r,g,b" => LineError::MissingLevels,
            "palette colours run past entry 255" => LineError::PaletteTooLong,
            _ => match text.strip_prefix("control character U+") {
                Some(rest) => {
                    let code = rest.strip_suffix(" (words are separated by spaces and tabs)")?;
                    LineError::ControlCharacter(char::from_u32(u32::from_str_radix(code, 16).ok()?)?)
                }
                None => AROUND_A_WORD.iter().find_map(|(before, after, error)| {
                    let word = text.strip_prefix(before)?.strip_suffix(after)?;
                    Some(error(String::from(word)))
                })?,
            },
        };
        writes(&error, text).then_some(error)
    }
}

/// Whether `value`'s `Display` writes exactly `text`: how an error read
/// back from its text is held to the text it was read from.
pub(crate) fn writes(value: &impl fmt::Display, text: &str) -> bool {
    let mut written = String::new();
    write!(written, "{value}").is_ok() && written == text
}

/// A [`LineError`] with its 1-based line number.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SceneFileError {
    pub line: usize,
    pub error: LineError,
}

impl fmt::Display for SceneFileError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "line {}: {}", self.line, self.error)
    }
}

/// Parses a whole scene file.
pub fn parse(name: &str, text: &str) -> Result<Scene, SceneFileError> {
    let mut scene = Scene::new(String::from(name), Vec::new(), FILE_METHOD);
    for (i, line) in text.lines().enumerate() {
        match parse_line(line).map_err(|error| SceneFileError { line: i + 1, error })? {
            Some(Statement::Op(op)) => scene.ops.push(op),
            Some(Statement::Palette(entries)) => scene.palette.extend(entries),
            None => {}
        }
    }
    Ok(scene)
}

/// What one line of a scene file says.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Statement {
    /// A drawing step: `clear` or `poly`.
    Op(Op),
    /// DAC entries the scene sets: `palette`.
    Palette(Vec<PaletteEntry>),
}

/// Parses one line: `Ok(None)` for blank lines and comments.
pub fn parse_line(line: &str) -> Result<Option<Statement>, LineError> {
    let line = words_of(line.split('#').next().unwrap_or(""))?;
    let mut words = line.split_ascii_whitespace();
    let Some(keyword) = words.next() else { return Ok(None) };
    let statement = match keyword {
        "clear" => {
            let color = words.next().ok_or(LineError::MissingColor)?;
            let color = color.parse::<u8>().map_err(|_| LineError::BadColor(String::from(color)))?;
            match words.next() {
                Some(extra) => return Err(LineError::Extra(String::from(extra))),
                None => Statement::Op(Op::Clear(color)),
            }
        }
        "poly" => Statement::Op(Op::Fill(parse_poly_words(words)?)),
        "palette" => Statement::Palette(parse_palette_words(words)?),
        other => return Err(LineError::UnknownKeyword(String::from(other))),
    };
    Ok(Some(statement))
}

/// Parses a `palette` line without its keyword: `I r,g,b [r,g,b ...]`.
fn parse_palette_words<'a>(mut words: impl Iterator<Item = &'a str>) -> Result<Vec<PaletteEntry>, LineError> {
    let first = words.next().ok_or(LineError::MissingLevels)?;
    let first = first.parse::<u8>().map_err(|_| LineError::BadPaletteIndex(String::from(first)))?;
    let mut entries = Vec::new();
    for (index, word) in (usize::from(first)..).zip(words) {
        let bad = || LineError::BadLevels(String::from(word));
        let mut levels = word.split(',').map(|level| level.parse::<u8>().ok().filter(|&level| level <= MAX_LEVEL));
        let rgb = [levels.next(), levels.next(), levels.next()].map(Option::flatten);
        let ([Some(r), Some(g), Some(b)], None) = (rgb, levels.next()) else { return Err(bad()) };
        let index = u8::try_from(index).map_err(|_| LineError::PaletteTooLong)?;
        entries.push(PaletteEntry { index, rgb: [r, g, b] });
    }
    if entries.is_empty() {
        return Err(LineError::MissingLevels);
    }
    Ok(entries)
}

/// Parses a `poly` line without its keyword (the protocol's `POLY`
/// command carries one): `color=C [rule=R] x,y ...`.
pub fn parse_poly(spec: &str) -> Result<Polygon, LineError> {
    parse_poly_words(words_of(spec)?.split_ascii_whitespace())
}

/// `text` without the whitespace at its ends, refused if a control
/// character other than a tab is left between its words: the protocol's
/// `POLY` line, which carries a `poly` line's text to the kernel, takes
/// only printable ASCII and tabs.
fn words_of(text: &str) -> Result<&str, LineError> {
    let text = text.trim_matches(|c: char| c.is_ascii_whitespace());
    match text.chars().find(|&c| c.is_control() && c != '\t') {
        Some(c) => Err(LineError::ControlCharacter(c)),
        None => Ok(text),
    }
}

fn parse_poly_words<'a>(words: impl Iterator<Item = &'a str>) -> Result<Polygon, LineError> {
    let mut color = None;
    let mut rule = FillRule::EvenOdd;
    let mut contours: Vec<Vec<Point>> = alloc::vec![Vec::new()];
    for word in words {
        if let Some(value) = word.strip_prefix("color=") {
            color = Some(value.parse::<u8>().map_err(|_| LineError::BadColor(String::from(value)))?);
        } else if let Some(value) = word.strip_prefix("rule=") {
            rule = FillRule::from_name(value).ok_or_else(|| LineError::BadRule(String::from(value)))?;
        } else if word == "|" {
            contours.push(Vec::new());
        } else if word.contains('=') {
            return Err(LineError::UnknownOption(String::from(word)));
        } else {
            let (x, y) = word.split_once(',').ok_or_else(|| LineError::BadVertex(String::from(word)))?;
            let point = Point::new(parse_coordinate(x)?, parse_coordinate(y)?);
            if let Some(contour) = contours.last_mut() {
                contour.push(point);
            }
        }
    }
    if contours.len() > 1 && contours.iter().any(Vec::is_empty) {
        return Err(LineError::EmptyContour);
    }
    let color = color.ok_or(LineError::MissingColor)?;
    Ok(Polygon { contours, color, rule })
}

/// `subpixels / 256` pixels as the shortest exact decimal ("-3.25", "12").
fn pixels(subpixels: i32) -> String {
    let magnitude = i64::from(subpixels).unsigned_abs();
    let whole = magnitude >> SUBPIXEL_BITS;
    let fraction = magnitude & (SUBPIXEL_ONE as u64 - 1);
    let sign = if subpixels < 0 { "-" } else { "" };
    if fraction == 0 {
        return alloc::format!("{sign}{whole}");
    }
    // fraction / 256 = fraction * 5^8 / 10^8.
    let digits = alloc::format!("{:08}", fraction * 390_625);
    alloc::format!("{sign}{whole}.{}", digits.trim_end_matches('0'))
}

/// `polygon` as one scene-file `poly` line that [`parse_line`] reads back
/// to the very same polygon: every subpixel value has a finite decimal form
/// (1/256 is 0.00390625), written out in full and no longer.
pub fn poly_line(polygon: &Polygon) -> String {
    let mut line = alloc::format!("poly color={} rule={}", polygon.color, polygon.rule.name());
    for (i, contour) in polygon.contours.iter().enumerate() {
        if i > 0 {
            line.push_str(" |");
        }
        for point in contour {
            // Writing to a String cannot fail.
            let _ = write!(line, " {},{}", pixels(point.x), pixels(point.y));
        }
    }
    line
}

/// Colours on one `palette` line that [`write`] writes.
const LEVELS_PER_LINE: usize = 8;

/// The palette of `scene` as `palette` lines: runs of consecutive
/// indices, at most [`LEVELS_PER_LINE`] colours a line, in the scene's
/// order (so a later entry for an index still wins).
fn palette_lines(entries: &[PaletteEntry], text: &mut String) {
    let mut rest = entries;
    while let Some(first) = rest.first() {
        let run = rest
            .iter()
            .zip(usize::from(first.index)..ENTRIES)
            .take(LEVELS_PER_LINE)
            .take_while(|(entry, index)| usize::from(entry.index) == *index)
            .count();
        // Writing to a String cannot fail.
        let _ = write!(text, "palette {}", first.index);
        for entry in &rest[..run] {
            let [r, g, b] = entry.rgb;
            let _ = write!(text, " {r},{g},{b}");
        }
        text.push('\n');
        rest = &rest[run..];
    }
}

/// `scene` as a scene file, its palette first, then one line per
/// operation, that [`parse`] reads back to the very same palette and
/// operations.
pub fn write(scene: &Scene) -> String {
    let mut text = String::new();
    palette_lines(&scene.palette, &mut text);
    for op in &scene.ops {
        match op {
            Op::Clear(color) => {
                // Writing to a String cannot fail.
                let _ = write!(text, "clear {color}");
            }
            Op::Fill(polygon) => text.push_str(&poly_line(polygon)),
        }
        text.push('\n');
    }
    text
}

/// A decimal number of pixels to subpixels, rounded to nearest, halves up.
fn parse_coordinate(text: &str) -> Result<i32, LineError> {
    let bad = || LineError::BadVertex(String::from(text));
    let (negative, digits) = match text.strip_prefix('-') {
        Some(rest) => (true, rest),
        None => (false, text.strip_prefix('+').unwrap_or(text)),
    };
    let (whole, fraction) = digits.split_once('.').unwrap_or((digits, ""));
    if whole.is_empty() && fraction.is_empty() {
        return Err(bad());
    }
    if !whole.bytes().chain(fraction.bytes()).all(|b| b.is_ascii_digit()) {
        return Err(bad());
    }
    // Exact: mantissa / 10^k pixels, at most 30 significant digits.
    let all_digits = whole.trim_start_matches('0').len() + fraction.len();
    if all_digits > 30 {
        return Err(LineError::CoordinateOutOfRange(String::from(text)));
    }
    let mut mantissa: i128 = 0;
    for b in whole.bytes().chain(fraction.bytes()) {
        mantissa = mantissa * 10 + i128::from(b - b'0');
    }
    if negative {
        mantissa = -mantissa;
    }
    let scale = 10i128.pow(fraction.len() as u32);
    // floor((m * 256 * 2 + scale) / (2 * scale)) rounds to nearest, halves up.
    let doubled = mantissa * (2 << SUBPIXEL_BITS) + scale;
    let value = doubled.div_euclid(2 * scale);
    i32::try_from(value).map_err(|_| LineError::CoordinateOutOfRange(String::from(text)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::palette::VGA_DEFAULT;

    #[test]
    fn every_line_error_reads_back_from_its_text() {
        let word = || String::from("x`y");
        let errors = [
            LineError::UnknownKeyword(word()),
            LineError::MissingColor,
            LineError::BadColor(String::from("999")),
            LineError::BadRule(word()),
            LineError::BadVertex(word()),
            LineError::CoordinateOutOfRange(word()),
            LineError::UnknownOption(word()),
            LineError::EmptyContour,
            LineError::Extra(word()),
            LineError::ControlCharacter('\u{1b}'),
            LineError::BadPaletteIndex(word()),
            LineError::BadLevels(word()),
            LineError::MissingLevels,
            LineError::PaletteTooLong,
        ];
        for error in errors {
            let text = alloc::format!("{error}");
            assert_eq!(LineError::parse(&text), Some(error), "{text}");
        }
        for garbage in ["", "bad colour `999`", "control character U+1B (words are separated by spaces and tabs)"] {
            assert_eq!(LineError::parse(garbage), None, "{garbage}");
        }
    }

    #[test]
    fn parses_clear_poly_comments_and_contours() {
        let text = "# scene\n\nclear 3\npoly color=6 rule=nonzero 0,0 10.5,0 5,-2.25 | 1,1 2,1 2,2 # hole\n";
        let scene = parse("t", text).unwrap();
        assert_eq!(scene.ops[0], Op::Clear(3));
        let Op::Fill(p) = &scene.ops[1] else { panic!() };
        assert_eq!(p.color, 6);
        assert_eq!(p.rule, FillRule::NonZero);
        assert_eq!(p.contours[0], [Point::new(0, 0), Point::new(2688, 0), Point::new(1280, -576)]);
        assert_eq!(p.contours[1].len(), 3);
    }

    #[test]
    fn palette_lines_set_entries_from_their_index_for_the_whole_scene() {
        let text = "clear 16\npalette 16 63,32,0 0,0,21 # orange, navy\npoly color=17 0,0 9,0 0,9\npalette 16 1,2,3\n";
        let scene = parse("t", text).unwrap();
        let entry = |index, rgb| PaletteEntry { index, rgb };
        assert_eq!(scene.palette, [entry(16, [63, 32, 0]), entry(17, [0, 0, 21]), entry(16, [1, 2, 3])]);
        let dac = scene.dac();
        assert_eq!((dac[15], dac[16], dac[17], dac[18]), ([63, 63, 63], [1, 2, 3], [0, 0, 21], VGA_DEFAULT[18]));
        assert_eq!(parse_line("palette 255 0,0,0").unwrap(), Some(Statement::Palette(alloc::vec![entry(255, [0; 3])])));
        assert_eq!(parse_line("palette 255 0,0,0 1,1,1"), Err(LineError::PaletteTooLong));
        assert_eq!(parse_line("palette 256 0,0,0"), Err(LineError::BadPaletteIndex(String::from("256"))));
        assert_eq!(parse_line("palette 3"), Err(LineError::MissingLevels));
        assert_eq!(parse_line("palette"), Err(LineError::MissingLevels));
        for bad in ["64,0,0", "1,2", "1,2,3,4", "a,b,c", "1,,3", "-1,0,0"] {
            let line = alloc::format!("palette 3 {bad}");
            assert_eq!(parse_line(&line), Err(LineError::BadLevels(String::from(bad))), "{line}");
        }
    }

    #[test]
    fn a_palette_is_written_in_runs_that_read_back_in_order() {
        let entry = |index: u8, rgb| PaletteEntry { index, rgb };
        let mut scene = Scene::new(String::from("t"), alloc::vec![Op::Clear(3)], FILE_METHOD);
        scene.palette = (250..=255).map(|i| entry(i, [i - 250; 3])).collect();
        scene.palette.extend((0..10).map(|i| entry(i, [i, 63 - i, 7])));
        scene.palette.push(entry(3, [9, 9, 9]));
        let text = write(&scene);
        assert_eq!(text.lines().filter(|line| line.starts_with("palette")).count(), 4, "{text}");
        assert!(text.starts_with("palette 250 0,0,0 1,1,1 2,2,2 3,3,3 4,4,4 5,5,5\npalette 0 0,63,7 "), "{text}");
        let again = parse("t", &text).unwrap();
        assert_eq!((again.palette, again.ops), (scene.palette, scene.ops));
    }

    #[test]
    fn coordinates_round_to_nearest_subpixel_halves_up() {
        assert_eq!(parse_coordinate("0.001953125"), Ok(1)); // exactly 0.5/256
        assert_eq!(parse_coordinate("-0.001953125"), Ok(0));
        assert_eq!(parse_coordinate("0.0019"), Ok(0));
        assert_eq!(parse_coordinate(".5"), Ok(128));
        assert_eq!(parse_coordinate("8388607.99"), Ok(i32::MAX - 2));
        assert!(matches!(parse_coordinate("8388608"), Err(LineError::CoordinateOutOfRange(_))));
        assert!(matches!(parse_coordinate("1e3"), Err(LineError::BadVertex(_))));
        assert!(matches!(parse_coordinate("."), Err(LineError::BadVertex(_))));
    }

    #[test]
    fn errors_name_the_line() {
        let err = parse("t", "clear 1\npoly 1,1 2,2 3,1\n").unwrap_err();
        assert_eq!(err.line, 2);
        assert_eq!(err.error, LineError::MissingColor);
        assert_eq!(alloc::format!("{err}"), "line 2: `poly` needs `color=N`");
        assert!(matches!(parse_line("fill 3"), Err(LineError::UnknownKeyword(_))));
        assert!(matches!(parse_line("poly color=300 1,1"), Err(LineError::BadColor(_))));
        assert!(matches!(parse_line("poly color=1 rule=odd 1,1"), Err(LineError::BadRule(_))));
        assert!(matches!(parse_line("poly color=1 1;1"), Err(LineError::BadVertex(_))));
        assert!(matches!(parse_line("poly color=1 1,1 | | 2,2"), Err(LineError::EmptyContour)));
        assert!(matches!(parse_line("clear 1 2"), Err(LineError::Extra(_))));
    }

    #[test]
    fn a_control_character_between_words_is_refused_as_the_kernel_would_refuse_the_line() {
        // Found by the scene_file fuzz target: a form feed is ASCII
        // whitespace, so this line parsed, but the `POLY` command carrying
        // its text is not printable ASCII and the kernel refused it.
        let line = "poly color=3 rule=evenodd 0,0 320,0\x0c50,20";
        assert_eq!(parse_line(line), Err(LineError::ControlCharacter('\x0c')));
        assert_eq!(parse_poly("color=3 0,0\r320,0 50,20"), Err(LineError::ControlCharacter('\r')));
        assert_eq!(parse_line("poly color=3 0,0 320,0 50,20 # a \x0c in a comment\r").map(|op| op.is_some()), Ok(true));
        assert_eq!(parse_line("\tpoly\tcolor=3 0,0 320,0 50,20\x0c").map(|op| op.is_some()), Ok(true));
        let error = parse("t", "clear 1\npoly color=3 0,0\x0b320,0 50,20\n").unwrap_err();
        assert_eq!(
            alloc::format!("{error}"),
            "line 2: control character U+000B (words are separated by spaces and tabs)"
        );
    }

    #[test]
    fn decimals_are_exact_and_shortest() {
        assert_eq!(pixels(0), "0");
        assert_eq!(pixels(256), "1");
        assert_eq!(pixels(-832), "-3.25");
        assert_eq!(pixels(1), "0.00390625");
        assert_eq!(pixels(-1), "-0.00390625");
        assert_eq!(pixels(i32::MAX), "8388607.99609375");
        assert_eq!(pixels(i32::MIN), "-8388608");
    }

    #[test]
    fn a_written_scene_parses_back_to_the_same_operations() {
        let text = "clear 9\npoly color=5 rule=nonzero 0,0 10.5,0 5,7.25 | 1,1 2,1 2,2\nclear 0\n";
        let scene = parse("t", text).unwrap();
        assert_eq!(write(&scene), text);
    }

    #[test]
    fn a_copied_line_parses_back_to_the_same_polygon() {
        let values = [i32::MIN, i32::MIN + 1, -257, -256, -255, -128, -1, 0, 1, 127, 128, 255, 70_000, i32::MAX];
        let contour: Vec<Point> = values.iter().zip(values.iter().rev()).map(|(&x, &y)| Point::new(x, y)).collect();
        let polygon = Polygon {
            contours: alloc::vec![contour, alloc::vec![Point::new(5, 6), Point::new(-7, 8), Point::new(9, -10)]],
            color: 200,
            rule: FillRule::NonZero,
        };
        let line = poly_line(&polygon);
        assert!(line.starts_with("poly color=200 rule=nonzero -8388608,8388607.99609375 "), "{line}");
        let back = parse_poly(line.strip_prefix("poly").unwrap()).unwrap();
        assert_eq!(back, polygon);
    }
}
