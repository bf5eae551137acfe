//! The `explorer` target: the explorer page's engine (`xtask/explorer/engine`) on
//! any state its address's fragment or a pasted scene can give it, the
//! calls the page's script makes through the engine's exports, in their
//! order: load a built-in page and apply vertex edits (`scene=` and
//! `edits=`), or load a scene text (`text=`, or a paste); select a
//! polygon (`poly=`); render both panes with their methods, view and judge
//! (`a=`, `b=`, `view=`, `judge=`); describe the selected polygon; find
//! the polygon under a click. Nothing panics, and:
//! - bad edits change nothing;
//! - a pane's picture has its size, no method strays outside the screen,
//!   and `exact` judged against itself differs in no pixel;
//! - the selected polygon's scene-file line reads back as the polygon;
//! - the state written back (`scene_text`, or the page and its `edits`)
//!   loads as the same scene;
//! - a click finds a polygon there is.
//!
//! Input: one byte of flags (bit 0 a built-in page rather than a text,
//! bit 1 the difference view, bit 2 the method's own convention as judge),
//! the two panes' method numbers, the selected polygon (`u32`), the click
//! (two `i16`), the built-in page's number, then the rest as the text (the
//! edits for a page), as the engine reads its input buffer (invalid UTF-8
//! replaced).

use arbitrary::Unstructured;
use explorer::family;
use explorer::judge::Judge;
use explorer::model::Explorer;
use explorer::view::{self, View, RGBA_BYTES};
use raster::{classify, MethodId};
use scenes::builtin;
use scenes::file;

/// The flags.
const BUILTIN: u8 = 1;
const DIFFERENCE: u8 = 2;
const OWN_CONVENTION: u8 = 4;

/// What the page hands the engine.
#[derive(Debug)]
struct PageState {
    flags: u8,
    methods: [MethodId; 2],
    poly: u32,
    click: (i32, i32),
    page: &'static builtin::BuiltinPage,
    text: String,
}

fn decode(data: &[u8]) -> PageState {
    let mut bytes = Unstructured::new(data);
    let mut next = || -> u8 { bytes.arbitrary().unwrap_or_default() };
    let flags = next();
    let methods = [next(), next()].map(|n| MethodId::ALL[usize::from(n) % MethodId::ALL.len()]);
    let poly = u32::from_le_bytes([next(), next(), next(), next()]);
    let click = (i32::from(i16::from_le_bytes([next(), next()])), i32::from(i16::from_le_bytes([next(), next()])));
    let page = &builtin::ALL[usize::from(next()) % builtin::ALL.len()];
    let text = String::from_utf8_lossy(bytes.take_rest()).into_owned();
    PageState { flags, methods, poly, click, page, text }
}

/// The bytes [`decode`] reads as `page` with `edits`, or as `text`.
fn encode(page: Option<usize>, text: &str) -> Vec<u8> {
    let flags = u8::from(page.is_some()) * BUILTIN;
    let mut bytes = vec![flags, 0, MethodId::ALL.len() as u8 - 1, 0, 0, 0, 0, 160, 0, 100, 0];
    bytes.push(page.unwrap_or(0) as u8);
    bytes.extend(text.as_bytes());
    bytes
}

pub fn check(data: &[u8]) {
    let state = decode(data);
    let mut explorer = if state.flags & BUILTIN != 0 {
        let mut explorer = Explorer::with_builtin(state.page);
        if explorer.apply_edits(&state.text).is_err() {
            assert_eq!(explorer.scene(), Explorer::with_builtin(state.page).scene(), "a bad edit changed the scene");
        }
        explorer
    } else {
        match Explorer::from_text(&state.text) {
            Ok(explorer) => explorer,
            Err(_) => return,
        }
    };
    explorer.select(state.poly as usize);
    let view = if state.flags & DIFFERENCE != 0 { View::Difference } else { View::Picture };
    let judge = if state.flags & OWN_CONVENTION != 0 { Judge::OwnConvention } else { Judge::Exact };
    let mut rgba = Vec::new();
    for method in state.methods {
        let report = view::render(&mut explorer, method, view, judge, &mut rgba);
        assert_eq!(rgba.len(), RGBA_BYTES);
        assert_eq!(report.scene.strays, 0, "{method} strayed outside the screen");
        if method == MethodId::Exact && report.judge == Judge::Exact {
            assert_eq!((report.scene.added, report.scene.missed), (0, 0), "exact differs from itself");
        }
    }
    if let Some(polygon) = explorer.selected_polygon() {
        let line = file::poly_line(polygon);
        let spec = line.strip_prefix("poly").unwrap_or(&line);
        assert_eq!(file::parse_poly(spec).as_ref(), Ok(polygon), "{line}");
        family::nearest(polygon);
        classify(polygon);
    }
    if let Some(index) = explorer.polygon_at(state.click.0, state.click.1) {
        assert!(index < explorer.polygon_count());
    }
    let again = Explorer::from_text(&explorer.scene_text()).expect("a scene the explorer holds, written out, loads");
    assert_eq!(again.scene().ops, explorer.scene().ops);
    if state.flags & BUILTIN != 0 {
        let mut again = Explorer::with_builtin(state.page);
        again.apply_edits(&explorer.edits()).expect("the explorer's own edits apply");
        assert_eq!(again.scene(), explorer.scene());
    }
}

/// Each built-in page, as it is and with an edit, and as a pasted text.
pub fn seeds() -> Vec<(String, Vec<u8>)> {
    let mut seeds = Vec::new();
    for (index, page) in builtin::ALL.iter().enumerate() {
        seeds.push((format!("{}-as-built", page.name), encode(Some(index), "")));
        seeds.push((format!("{}-edited", page.name), encode(Some(index), "0.1.-5.70000,1.0.2560.-256")));
        seeds.push((format!("{}-pasted", page.name), encode(None, &file::write(&page.scene()))));
    }
    seeds
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seeds_decode_to_the_page_or_the_text_they_were_made_from() {
        let state = decode(&encode(Some(2), "1.0.5.5"));
        assert_eq!((state.flags, state.page.name, state.text.as_str()), (BUILTIN, builtin::ALL[2].name, "1.0.5.5"));
        assert_eq!(state.methods, [MethodId::ALL[0], MethodId::Exact]);
        assert_eq!(state.click, (160, 100));
        let state = decode(&encode(None, "clear 3\n"));
        assert_eq!((state.flags, state.text.as_str()), (0, "clear 3\n"));
    }
}
