//! A paint (a colour, a gradient or a pattern) with its opacity as one
//! flat, opaque colour, and a note for whatever was not one: a polygon
//! has one colour index and the screen no transparency.

use usvg::{Group, Node, Paint};

use crate::notes::Notes;

/// 8-bit red, green and blue, as SVG gives them.
pub(crate) type Rgb = [u8; 3];

/// The colour to fill with for `paint` at `opacity` (the paint's own
/// times its groups'), noting in `notes` what was made flat or opaque
/// under `element`'s name (which says fill or stroke); `None` for a paint
/// at opacity 0, which is not drawn (and noted).
pub(crate) fn flat_colour(paint: &Paint, opacity: f32, element: &str, notes: &mut Notes) -> Option<Rgb> {
    if opacity <= 0.0 {
        notes.add("opacity 0, not drawn", element.to_string());
        return None;
    }
    if opacity < 1.0 {
        notes.add("opacity below 1, drawn opaque", format!("{element} at {opacity:.2}"));
    }
    let (kind, id, count) = match paint {
        Paint::Color(color) => return Some(rgb(*color)),
        Paint::LinearGradient(gradient) => ("linear gradient", gradient.id(), gradient.stops().len()),
        Paint::RadialGradient(gradient) => ("radial gradient", gradient.id(), gradient.stops().len()),
        Paint::Pattern(pattern) => ("pattern", pattern.id(), painted(pattern.root()).len()),
    };
    let server = if id.is_empty() { kind.to_string() } else { format!("{kind} #{id}") };
    match (paint, mean_of(paint)) {
        (Paint::Pattern(_), Some(colour)) => notes.add(
            "patterns drawn flat in the mean of the colours they paint",
            format!("{element}: {server}, {count} colours, as {}", hex(colour)),
        ),
        (_, Some(colour)) => notes.add(
            "gradients drawn flat in the mean of their stops' colours",
            format!("{element}: {server}, {count} stops, as {}", hex(colour)),
        ),
        (_, None) => notes.add("paints of no colour, drawn black", format!("{element}: {server}")),
    }
    Some(mean_of(paint).unwrap_or([0; 3]))
}

/// A colour as `#rrggbb`.
pub(crate) fn hex([r, g, b]: Rgb) -> String {
    format!("#{r:02x}{g:02x}{b:02x}")
}

fn rgb(color: usvg::Color) -> Rgb {
    [color.red, color.green, color.blue]
}

/// The paint's colour, or the mean of its gradient's stops' colours, or
/// of the colours its pattern paints; `None` when there are none.
fn mean_of(paint: &Paint) -> Option<Rgb> {
    match paint {
        Paint::Color(color) => Some(rgb(*color)),
        Paint::LinearGradient(gradient) => mean(gradient.stops().iter().map(|stop| rgb(stop.color()))),
        Paint::RadialGradient(gradient) => mean(gradient.stops().iter().map(|stop| rgb(stop.color()))),
        Paint::Pattern(pattern) => mean(painted(pattern.root()).into_iter()),
    }
}

/// The colours the paths in `group` paint with, fills and strokes, each
/// paint as its [`mean_of`].
fn painted(group: &Group) -> Vec<Rgb> {
    let mut colours = Vec::new();
    for node in group.children() {
        match node {
            Node::Group(group) => colours.extend(painted(group)),
            Node::Path(path) => {
                let paints = [path.fill().map(|fill| fill.paint()), path.stroke().map(|stroke| stroke.paint())];
                colours.extend(paints.into_iter().flatten().filter_map(mean_of));
            }
            Node::Image(_) | Node::Text(_) => {}
        }
    }
    colours
}

/// Each channel's mean, rounded; `None` for no colours.
fn mean(colours: impl Iterator<Item = Rgb>) -> Option<Rgb> {
    let mut sums = [0u64; 3];
    let mut count = 0u64;
    for colour in colours {
        for (sum, channel) in sums.iter_mut().zip(colour) {
            *sum += u64::from(channel);
        }
        count += 1;
    }
    (count > 0).then(|| sums.map(|sum| ((sum + count / 2) / count) as u8))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_mean_rounds_each_channel() {
        assert_eq!(mean([[255, 0, 10], [0, 0, 11]].into_iter()), Some([128, 0, 11]));
        assert_eq!(mean([[1, 2, 3]; 3].into_iter()), Some([1, 2, 3]));
        assert_eq!(mean(std::iter::empty()), None);
        assert_eq!(hex([255, 8, 160]), "#ff08a0");
    }

    #[test]
    fn opacity_is_noted_and_zero_is_not_drawn() {
        let mut notes = Notes::default();
        let red = Paint::Color(usvg::Color::new_rgb(255, 0, 0));
        assert_eq!(flat_colour(&red, 1.0, "shape #a (fill)", &mut notes), Some([255, 0, 0]));
        assert!(notes.lines().is_empty());
        assert_eq!(flat_colour(&red, 0.25, "shape #b (stroke)", &mut notes), Some([255, 0, 0]));
        assert_eq!(flat_colour(&red, 0.0, "shape #c (fill)", &mut notes), None);
        assert_eq!(
            notes.lines(),
            ["opacity below 1, drawn opaque: shape #b (stroke) at 0.25", "opacity 0, not drawn: shape #c (fill)"]
        );
    }
}
