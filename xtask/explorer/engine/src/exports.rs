//! The module's interface to the page's script: `extern "C"` functions over
//! integers, so the script needs no glue generator. Text goes both ways
//! through two buffers the module owns: the script asks for an input
//! buffer of a given length ([`ex_input`]), writes UTF-8 into it and calls
//! the function that reads it; a function that answers with text returns
//! its length and leaves it in the output buffer ([`ex_output`]). Text
//! answers are lines of `key<TAB>value`, or one item a line.
//!
//! Methods are numbered in `raster::MethodId::ALL`'s order, views 0
//! (picture) and 1 (difference), judges 0 (`exact`) and 1 (the method's
//! own convention).
//!
//! A panic cannot unwind out of WebAssembly: it traps, and the script
//! starts a fresh instance. The state lives in one `static` guarded by a
//! mutex (the page has one thread), so a trap mid-call is never seen by
//! a later call of the same instance.
// `no_mangle` is what exports a function from the module; the lint that
// forbids unsafe code counts it. Nothing here dereferences a pointer: the
// pointers handed out point into buffers owned by the state, which the
// script reads or writes before its next call.
#![allow(unsafe_code)]

use std::fmt::Write;
use std::sync::{Mutex, PoisonError};

use raster::{MethodId, Point};
use scenes::builtin;

use crate::family;
use crate::judge::Judge;
use crate::model::{Explorer, Origin};
use crate::view::{self, PaneReport, View};
use scenes::file::poly_line;

/// Everything the page has in the module.
#[derive(Default)]
struct State {
    explorer: Explorer,
    input: Vec<u8>,
    output: String,
    /// The two panes' pictures, RGBA.
    panes: [Vec<u8>; 2],
    /// The two panes' last reports.
    reports: [Option<PaneReport>; 2],
    /// The selected polygon's vertices as (contour, x, y) triples.
    vertices: Vec<i32>,
}

static STATE: Mutex<Option<State>> = Mutex::new(None);

fn with_state<R>(work: impl FnOnce(&mut State) -> R) -> R {
    let mut state = STATE.lock().unwrap_or_else(PoisonError::into_inner);
    work(state.get_or_insert_with(State::default))
}

/// Sets the output text and returns its length in bytes.
fn answer(state: &mut State, text: String) -> usize {
    state.output = text;
    state.output.len()
}

/// The input buffer as text; invalid UTF-8 becomes U+FFFD, which no parser
/// here accepts, so it ends as a message.
fn input_text(state: &State) -> String {
    String::from_utf8_lossy(&state.input).into_owned()
}

/// Loads `result` as the new scene (status 0), or leaves the scene as it
/// was and puts the error in the output (status -1).
fn load(state: &mut State, result: Result<Explorer, crate::model::InputError>) -> i32 {
    match result {
        Ok(explorer) => {
            state.explorer = explorer;
            0
        }
        Err(error) => {
            answer(state, error.to_string());
            -1
        }
    }
}

fn method(index: u32) -> MethodId {
    MethodId::ALL.get(index as usize).copied().unwrap_or(MethodId::Exact)
}

/// A buffer of `len` bytes for the script to write text into.
#[no_mangle]
pub extern "C" fn ex_input(len: usize) -> *mut u8 {
    with_state(|state| {
        state.input.clear();
        state.input.resize(len, 0);
        state.input.as_mut_ptr()
    })
}

/// Where the last text answer is.
#[no_mangle]
pub extern "C" fn ex_output() -> *const u8 {
    with_state(|state| state.output.as_ptr())
}

/// The last text answer's length in bytes (for the functions that answer
/// with a status, whose message is there when they fail).
#[no_mangle]
pub extern "C" fn ex_output_len() -> usize {
    with_state(|state| state.output.len())
}

/// Built-in scene names, one a line.
#[no_mangle]
pub extern "C" fn ex_builtins() -> usize {
    with_state(|state| answer(state, builtin::ALL.map(|page| page.name).join("\n")))
}

/// Method names, one a line, in `MethodId::ALL`'s order.
#[no_mangle]
pub extern "C" fn ex_methods() -> usize {
    with_state(|state| answer(state, MethodId::ALL.map(|id| id.name()).join("\n")))
}

/// What method `index` is, in words: `MethodInfo` as `key<TAB>value` lines.
#[no_mangle]
pub extern "C" fn ex_method_info(index: u32) -> usize {
    let info = method(index).method().info();
    let convention = &info.convention;
    let rules: Vec<&str> = info.rules.iter().map(|rule| rule.name()).collect();
    let sample = format!(
        "({}, {}) subpixels from the pixel's top-left corner: {}",
        convention.sample_x,
        convention.sample_y,
        match (convention.sample_x, convention.sample_y) {
            (0, 0) => "the integer grid point",
            (128, 128) => "the pixel centre",
            _ => "its own point",
        }
    );
    let text = [
        ("name", info.name.to_string()),
        ("source", info.source.to_string()),
        ("sample", sample),
        ("convention", convention.summary.to_string()),
        ("arithmetic", info.numeric.to_string()),
        ("handles", info.handles.name().to_string()),
        ("rules", rules.join(", ")),
        ("heap", info.heap.name().to_string()),
    ]
    .map(|(key, value)| format!("{key}\t{value}"))
    .join("\n");
    with_state(|state| answer(state, text))
}

/// Opens the built-in scene named in the input. 0, or -1 with a message.
#[no_mangle]
pub extern "C" fn ex_load_builtin() -> i32 {
    with_state(|state| {
        let name = input_text(state);
        load(state, Explorer::builtin(name.trim()))
    })
}

/// Opens the scene file in the input. 0, or -1 with a message (the line).
#[no_mangle]
pub extern "C" fn ex_load_text() -> i32 {
    with_state(|state| {
        let text = input_text(state);
        load(state, Explorer::from_text(&text))
    })
}

/// Applies the vertex edits in the input (`Explorer::edits`' format).
/// 0, or -1 with a message and nothing applied.
#[no_mangle]
pub extern "C" fn ex_apply_edits() -> i32 {
    with_state(|state| {
        let edits = input_text(state);
        match state.explorer.apply_edits(&edits) {
            Ok(()) => 0,
            Err(error) => {
                answer(state, error.to_string());
                -1
            }
        }
    })
}

/// The scene's origin: `builtin<TAB>NAME` or `file`.
#[no_mangle]
pub extern "C" fn ex_origin() -> usize {
    with_state(|state| {
        let text = match state.explorer.origin() {
            Origin::Builtin(page) => format!("builtin\t{}", page.name),
            Origin::File => "file".to_string(),
        };
        answer(state, text)
    })
}

/// The vertex edits of a built-in page (empty for a scene file).
#[no_mangle]
pub extern "C" fn ex_edits() -> usize {
    with_state(|state| {
        let edits = state.explorer.edits();
        answer(state, edits)
    })
}

/// The whole scene as a scene file.
#[no_mangle]
pub extern "C" fn ex_scene_text() -> usize {
    with_state(|state| {
        let text = state.explorer.scene_text();
        answer(state, text)
    })
}

#[no_mangle]
pub extern "C" fn ex_polygon_count() -> u32 {
    with_state(|state| state.explorer.polygon_count() as u32)
}

/// Selects polygon `index` (clamped); returns the selected index.
#[no_mangle]
pub extern "C" fn ex_select(index: u32) -> u32 {
    with_state(|state| {
        state.explorer.select(index as usize);
        state.explorer.selected() as u32
    })
}

/// The selected polygon's index.
#[no_mangle]
pub extern "C" fn ex_selected() -> u32 {
    with_state(|state| state.explorer.selected() as u32)
}

/// The topmost polygon whose exact fill covers pixel (x, y), or -1.
#[no_mangle]
pub extern "C" fn ex_polygon_at(x: i32, y: i32) -> i32 {
    with_state(|state| state.explorer.polygon_at(x, y).map_or(-1, |index| index as i32))
}

/// The selected polygon as a scene-file line, its fill rule, colour, class
/// and the lab family nearest to it, as `key<TAB>value` lines.
#[no_mangle]
pub extern "C" fn ex_selected_info() -> usize {
    with_state(|state| {
        let Some(polygon) = state.explorer.selected_polygon() else {
            return answer(state, String::new());
        };
        let nearest = family::nearest(polygon);
        let text = [
            ("index", state.explorer.selected().to_string()),
            ("line", poly_line(polygon)),
            ("rule", polygon.rule.name().to_string()),
            ("color", polygon.color.to_string()),
            ("contours", polygon.contours.len().to_string()),
            ("vertices", polygon.vertex_count().to_string()),
            ("class", raster::classify(polygon).name().to_string()),
            ("family", nearest.family.to_string()),
            ("family_reason", nearest.reason),
        ]
        .map(|(key, value)| format!("{key}\t{value}"))
        .join("\n");
        answer(state, text)
    })
}

/// The selected polygon's vertices as `(contour, x, y)` triples of `i32`
/// (subpixels); their count is [`ex_vertex_count`].
#[no_mangle]
pub extern "C" fn ex_vertices() -> *const i32 {
    with_state(|state| {
        state.vertices.clear();
        if let Some(polygon) = state.explorer.selected_polygon() {
            for (contour, points) in polygon.contours.iter().enumerate() {
                for point in points {
                    state.vertices.extend([contour as i32, point.x, point.y]);
                }
            }
        }
        state.vertices.as_ptr()
    })
}

#[no_mangle]
pub extern "C" fn ex_vertex_count() -> u32 {
    with_state(|state| state.explorer.selected_polygon().map_or(0, |polygon| polygon.vertex_count() as u32))
}

/// Moves vertex `vertex` of the selected polygon to (x, y) subpixels.
/// 0, or -1 when there is no such vertex.
#[no_mangle]
pub extern "C" fn ex_set_vertex(vertex: u32, x: i32, y: i32) -> i32 {
    with_state(|state| {
        let selected = state.explorer.selected();
        match state.explorer.set_vertex(selected, vertex as usize, Point::new(x, y)) {
            Ok(()) => 0,
            Err(_) => -1,
        }
    })
}

/// Renders pane `pane` (0 or 1) with method `method`, view `view` and judge
/// `judge`; returns its 320x200 RGBA picture ([`view::RGBA_BYTES`] bytes).
/// [`ex_report`] then describes it.
#[no_mangle]
pub extern "C" fn ex_render(pane: u32, method_index: u32, view_index: u32, judge_index: u32) -> *const u8 {
    let view = if view_index == 1 { View::Difference } else { View::Picture };
    let judge = if judge_index == 1 { Judge::OwnConvention } else { Judge::Exact };
    with_state(|state| {
        let pane = (pane as usize).min(1);
        let mut rgba = std::mem::take(&mut state.panes[pane]);
        state.reports[pane] = Some(view::render(&mut state.explorer, method(method_index), view, judge, &mut rgba));
        state.panes[pane] = rgba;
        state.panes[pane].as_ptr()
    })
}

/// Pane `pane`'s last report, as `key<TAB>value` lines: the judge used
/// (`exact` or `own`) and the reference's work for the scene against its
/// budget, polygons drawn and refused in the scene, then for the selected polygon (`selected_*`) and
/// the whole scene (`scene_*`) the pixels added and missed against the
/// judge, pixels overdrawn, stray spans and the (first) refusal in words.
#[no_mangle]
pub extern "C" fn ex_report(pane: u32) -> usize {
    with_state(|state| {
        let Some(report) = state.reports[(pane as usize).min(1)] else { return answer(state, String::new()) };
        let judge = if report.judge == Judge::Exact { "exact" } else { "own" };
        let mut text = format!(
            "judge\t{judge}\nreference_work\t{}\nreference_budget\t{}\npolygons\t{}\nrefused\t{}\n",
            report.reference_work,
            view::REFERENCE_BUDGET,
            report.drawn.polygons,
            report.drawn.refused
        );
        let parts = [("selected", report.selected), ("scene", Some(report.scene))];
        for (part, counts) in parts {
            let Some(counts) = counts else { continue };
            let refusal = counts.refusal.map_or("", |refusal| refusal.describe());
            // Writing to a String cannot fail.
            let _ = write!(
                text,
                "{part}_added\t{}\n{part}_missed\t{}\n{part}_overdrawn\t{}\n{part}_strays\t{}\n{part}_refusal\t{refusal}\n",
                counts.added, counts.missed, counts.overdrawn, counts.strays
            );
        }
        answer(state, text)
    })
}
