//! `exact`'s pixels pinned by a hash over a large seeded corpus, so that a
//! change to how it walks edges or hands spans to its sink cannot move a
//! pixel unnoticed, even where no reference comparison looks (the `i32`
//! extremes, screen-sized polygons).
//!
//! The corpus is the `exact_*` generators fed by our own seeded stream
//! ([`Seeded`]), so nothing but a change of `exact`'s pixels (or of this
//! corpus) changes the hash: polygons of every kind on the small test
//! target, huge ones, and the same kinds scaled up to cover the 320x200
//! screen. Each fill is reduced to the pixels it sets (its spans sorted by
//! row and column, touching or overlapping ones joined), plus its result
//! and how many spans broke the sink contract, and all of that is hashed
//! with FNV-1a.
//!
//! `EXPECTED` was printed by this test when the corpus moved to the seeded
//! stream, with `exact` as it was then; before that the corpus came from
//! proptest's runner, and its hash had been recorded before the sink
//! rework, so the pixels are still the pixels of that `exact`.
//! Each polygon is filled twice, through `Method::fill` (a call per span
//! through the sink's vtable) and through `MethodId::fill` (the sink's
//! store compiled into the fill), which must emit the same spans; the
//! screen-sized ones are also filled into a `Framebuffer`, whose pixels
//! must be the spans' pixels.
//!
//! A hash printed from `exact`'s own output is a change detector, not a
//! judge: had `exact` been wrong when it was printed, it would pin the
//! error. So a sample of the same corpus, picked by a seeded stream of its
//! own ([`SAMPLE_SEED`]), is judged by `raster::reference` pixel for pixel
//! (no pixel missing, none extra, none drawn twice), the screen-sized
//! polygons among it, where the property tests' small target never looks.

mod exact_support;

use exact_support::{against_reference, generate, generate_any, Draws, Kind, Seeded, TARGET};
use raster::methods::Exact;
use raster::{CoverageReport, Framebuffer, Method, MethodId, Point, Polygon, Size, SpanSink, SCREEN};

/// The hash of the whole corpus.
const EXPECTED: u64 = 0x1c2a_8b66_00d8_fcc6;

/// Where the corpus's stream starts.
const SEED: u64 = 0x5eed_e8ac_7001;

/// Polygons of every kind on the small target.
const SMALL: usize = 60_000;
/// Huge polygons (any `i32` vertex) on the small target.
const HUGE: usize = 6_000;
/// Polygons of every kind scaled by [`SCALE`] onto the screen.
const SCREEN_SIZED: usize = 12_000;
const SCALE: i32 = 7;

/// Where the stream that picks the judged sample starts.
const SAMPLE_SEED: u64 = 0x5a3b_1e0f_c0de;

/// The corpus's three parts, in order: how many polygons each has, and one
/// in how many of them the sample judges (the reference visits every
/// pixel of a polygon's box, which on the screen costs a debug build
/// a few milliseconds a polygon).
const PARTS: [(&str, usize, u64); 3] = [("small", SMALL, 100), ("huge", HUGE, 20), ("screen-sized", SCREEN_SIZED, 40)];

/// Keeps every span as emitted.
struct Spans {
    size: Size,
    spans: Vec<(i32, i32, i32)>,
}

impl SpanSink for Spans {
    fn size(&self) -> Size {
        self.size
    }

    fn span(&mut self, y: i32, x_start: i32, x_end: i32, _color: u8) {
        self.spans.push((y, x_start, x_end));
    }
}

/// FNV-1a, 64 bits: stable across platforms and Rust versions.
struct Fnv(u64);

impl Fnv {
    fn add(&mut self, value: i64) {
        for byte in value.to_le_bytes() {
            self.0 = (self.0 ^ u64::from(byte)).wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
}

/// Fills `polygon` into a target of `size` and adds what it drew to `hash`.
fn add_fill(hash: &mut Fnv, polygon: &Polygon, size: Size) {
    let mut sink = Spans { size, spans: Vec::new() };
    let result = Exact.fill(polygon, &mut sink);
    let mut inlined = Spans { size, spans: Vec::new() };
    assert_eq!(MethodId::Exact.fill(polygon, &mut inlined), result);
    assert_eq!(inlined.spans, sink.spans, "the two dispatches differ on {polygon:?}");
    if size == SCREEN {
        assert_framebuffer_holds(polygon, &sink.spans);
    }
    hash.add(i64::from(result.is_ok()));
    let broken = sink.spans.iter().filter(|&&(y, x0, x1)| !size.holds_span(y, x0, x1)).count();
    hash.add(broken as i64);
    let mut spans = sink.spans;
    spans.sort_unstable();
    let mut pixels: Vec<(i32, i32, i32)> = Vec::with_capacity(spans.len());
    for (y, x0, x1) in spans {
        match pixels.last_mut() {
            Some(last) if last.0 == y && x0 <= last.2 => last.2 = last.2.max(x1),
            _ => pixels.push((y, x0, x1)),
        }
    }
    hash.add(pixels.len() as i64);
    for (y, x0, x1) in pixels {
        hash.add(i64::from(y));
        hash.add(i64::from(x0));
        hash.add(i64::from(x1));
    }
}

/// `polygon` filled into a [`Framebuffer`] sets exactly the pixels of
/// `spans`, which lie inside the screen.
fn assert_framebuffer_holds(polygon: &Polygon, spans: &[(i32, i32, i32)]) {
    let mut drawn = Framebuffer::new(SCREEN);
    MethodId::Exact.fill(polygon, &mut drawn).expect("exact takes every polygon");
    let mut expected = vec![0u8; drawn.pixels().len()];
    for &(y, x0, x1) in spans {
        let row = (y * SCREEN.width) as usize;
        expected[row + x0 as usize..row + x1 as usize].fill(polygon.color);
    }
    assert!(drawn.pixels() == expected, "the framebuffer differs from the spans of {polygon:?}");
}

/// Hands `visit` every polygon of the corpus, in order, with its part
/// (an index into [`PARTS`]) and its target.
fn for_each_polygon(mut visit: impl FnMut(usize, &Polygon, Size)) {
    let mut draws = Seeded::new(SEED);
    for _ in 0..SMALL {
        visit(0, &generate_any(&mut draws).1, TARGET);
    }
    for _ in 0..HUGE {
        visit(1, &generate(&mut draws, Kind::Huge), TARGET);
    }
    for _ in 0..SCREEN_SIZED {
        let mut polygon = generate_any(&mut draws).1;
        for p in polygon.contours.iter_mut().flatten() {
            *p = Point::new(p.x.saturating_mul(SCALE), p.y.saturating_mul(SCALE));
        }
        visit(2, &polygon, SCREEN);
    }
}

fn corpus_hash() -> u64 {
    let mut hash = Fnv(0xcbf2_9ce4_8422_2325);
    for_each_polygon(|_, polygon, size| add_fill(&mut hash, polygon, size));
    hash.0
}

#[test]
fn exact_draws_the_recorded_pixels() {
    let hash = corpus_hash();
    assert_eq!(hash, EXPECTED, "exact's pixels changed: the corpus now hashes to {hash:#018x}");
}

#[test]
fn a_seeded_sample_of_the_recorded_corpus_is_the_reference_s_pixels() {
    let mut picks = Seeded::new(SAMPLE_SEED);
    let (mut judged, mut failures) = ([0usize; PARTS.len()], Vec::new());
    for_each_polygon(|part, polygon, size| {
        if picks.below(PARTS[part].2) != 0 {
            return;
        }
        judged[part] += 1;
        let (result, report, picture) = against_reference(|p, s| Exact.fill(p, s), polygon, size);
        if result.is_err() || report != CoverageReport::default() {
            // A picture of the small target reads in a message; the
            // screen's would not.
            let picture = if size == SCREEN { String::new() } else { picture };
            failures.push(format!("{} {polygon:?}: {result:?}, {report:?}\n{picture}", PARTS[part].0));
        }
    });
    for ((name, count, one_in), judged) in PARTS.into_iter().zip(judged) {
        // At least half the expected share: the sample really reaches each part.
        assert!(judged as u64 >= count as u64 / one_in / 2, "only {judged} of the {count} {name} polygons judged");
    }
    assert!(
        failures.is_empty(),
        "{} of {judged:?} sampled polygons differ from the reference; the first:\n{}",
        failures.len(),
        failures.iter().take(3).cloned().collect::<Vec<_>>().join("\n")
    );
}
