//! Every [`MethodId`] held to something outside its own two matches: the
//! kernel and the host both draw through `MethodId::fill`, so an arm that
//! sent an id to another method's filler would draw the same wrong pixels
//! on both sides, and no test comparing them could see it. Here each id's
//! `fill` (statically dispatched) and its `method()` (the `&dyn Method`),
//! two separate matches in `method_id.rs`, must draw the very spans, and
//! decline the very polygons, of the method's own type, paired with the id
//! in a table of this file's own ([`pairs`]), on a corpus of polygons of
//! every kind; and the corpus must tell every method from every other, or
//! an arm sending an id to the wrong one of two methods it cannot tell
//! apart would pass.

mod exact_support;

use exact_support::{generate, generate_any, Kind, Seeded, TARGET};
use raster::methods::{AbrashAet, AbrashFloat, AbrashInt, Exact, Lamothe, LamotheFixed, Pendleton, Wgt};
use raster::{Method, MethodId, Polygon, Refusal, Size, SpanSink};

/// Each id and the type it names, written out here rather than taken
/// from the code under test.
fn pairs() -> [(MethodId, &'static dyn Method); 8] {
    [
        (MethodId::AbrashFloat, &AbrashFloat),
        (MethodId::AbrashInt, &AbrashInt),
        (MethodId::AbrashAet, &AbrashAet),
        (MethodId::Pendleton, &Pendleton),
        (MethodId::Lamothe, &Lamothe),
        (MethodId::LamotheFixed, &LamotheFixed),
        (MethodId::Wgt, &Wgt),
        (MethodId::Exact, &Exact),
    ]
}

/// Polygons near and across the target of every kind the exact tests
/// generate, and some with vertices anywhere in `i32` (which the classic
/// methods decline, each by its own range).
const NEARBY: usize = 400;
const HUGE: usize = 40;
const SEED: u64 = 0x1d50_fa11;

fn corpus() -> Vec<Polygon> {
    let mut draws = Seeded::new(SEED);
    let mut corpus: Vec<Polygon> = (0..NEARBY).map(|_| generate_any(&mut draws).1).collect();
    corpus.extend((0..HUGE).map(|_| generate(&mut draws, Kind::Huge)));
    corpus
}

/// Every span a fill emits, in order.
struct Recorder {
    size: Size,
    spans: Vec<(i32, i32, i32, u8)>,
}

impl Recorder {
    fn new() -> Self {
        Self { size: TARGET, spans: Vec::new() }
    }
}

impl SpanSink for Recorder {
    fn size(&self) -> Size {
        self.size
    }

    fn span(&mut self, y: i32, x_start: i32, x_end: i32, color: u8) {
        self.spans.push((y, x_start, x_end, color));
    }
}

/// What a fill did: declined or not, and the spans it emitted.
type Outcome = (Result<(), Refusal>, Vec<(i32, i32, i32, u8)>);

fn outcome(fill: impl FnOnce(&mut Recorder) -> Result<(), Refusal>) -> Outcome {
    let mut recorder = Recorder::new();
    let result = fill(&mut recorder);
    (result, recorder.spans)
}

/// The method's own type, through the one interface.
fn by_type(method: &dyn Method, polygon: &Polygon) -> Outcome {
    outcome(|sink| method.fill(polygon, sink))
}

#[test]
fn the_table_pairs_every_id_once_in_order_with_a_type_of_its_name() {
    let ids = pairs().map(|(id, _)| id);
    assert_eq!(ids, MethodId::ALL, "a method was added or reordered: pair it with its type in `pairs`");
    for (id, method) in pairs() {
        assert_eq!(id.name(), method.info().name, "{id:?}'s name is not its type's");
        assert_eq!(id.to_string().parse(), Ok(id));
    }
}

#[test]
fn every_id_fills_and_declines_as_its_own_type() {
    let mut wrong = Vec::new();
    for (index, polygon) in corpus().iter().enumerate() {
        for (id, method) in pairs() {
            let own = by_type(method, polygon);
            let static_fill = outcome(|sink| id.fill(polygon, sink));
            let dyn_fill = outcome(|sink| id.method().fill(polygon, sink));
            if static_fill != own {
                wrong.push(format!("polygon {index}: {id:?}.fill is not {}'s fill", method.info().name));
            }
            if dyn_fill != own {
                wrong.push(format!("polygon {index}: {id:?}.method() is not {}", method.info().name));
            }
        }
    }
    assert!(wrong.is_empty(), "{} fills differ, the first:\n{}", wrong.len(), wrong[..wrong.len().min(16)].join("\n"));
}

#[test]
fn the_corpus_tells_every_method_from_every_other() {
    let corpus = corpus();
    let drawn: Vec<Vec<Outcome>> =
        pairs().iter().map(|(_, method)| corpus.iter().map(|polygon| by_type(*method, polygon)).collect()).collect();
    let names = pairs().map(|(_, method)| method.info().name);
    let mut alike = Vec::new();
    for a in 0..drawn.len() {
        for b in a + 1..drawn.len() {
            if drawn[a] == drawn[b] {
                alike.push(format!("{} and {}", names[a], names[b]));
            }
        }
    }
    assert!(alike.is_empty(), "the corpus cannot tell these apart: {}", alike.join(", "));
}
