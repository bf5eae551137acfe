//! Every method on hostile input: Pendleton's rule 3
//! (`docs/conventions.md#garbage-in-never-crashes`: "no
//! method may panic, loop forever, or write outside the target on any
//! input"). One list of cases for every method of [`MethodId::ALL`], each filled
//! with both fill rules into targets of odd sizes (two exceptions keep the
//! debug build's run time down, each saying why); a case fails when a
//! method panics (caught, so the report names every method and case that
//! did), emits a span outside the target ([`CoverageSink::out_of_bounds`]),
//! declines it for a reason the method does not own up to, or spends more
//! than [`HANG_LIMIT`] of CPU time on one fill: a hang guard, far above any
//! honest fill, not a speed test. CPU time, not the wall clock, so that a
//! fill kept waiting by a busy machine is not taken for a hang.
//!
//! What each method draws is pinned elsewhere (its unit tests,
//! `deviations.rs`, and for `exact` `exact_*.rs`, which also holds it to
//! the reference on hostile input); here only survival counts.

use std::panic::{self, AssertUnwindSafe};
use std::sync::{mpsc, Arc, Mutex};
use std::thread;
use std::time::Duration;

use raster::{CoverageSink, FillRule, MethodId, Point, Polygon, Refusal, Size, SCREEN, SUBPIXEL_ONE};

/// More CPU time than this for one fill, in a debug build, is a hang (the
/// slowest honest fills here take about a second).
const HANG_LIMIT: Duration = Duration::from_secs(5);

/// Targets of odd sizes: none, one pixel, narrow, the screen, and a
/// negative height (no pixels, and no row a span could be on).
const TARGETS: &[Size] = &[
    Size { width: 0, height: 0 },
    Size { width: 1, height: 1 },
    Size { width: 7, height: 3 },
    SCREEN,
    Size { width: 3, height: -4 },
];

/// [`TARGETS`] but the screen.
const SMALL_TARGETS: &[Size] = &[TARGETS[0], TARGETS[1], TARGETS[2], TARGETS[4]];

const BOTH_RULES: &[FillRule] = &[FillRule::EvenOdd, FillRule::NonZero];

/// One polygon, the targets it is filled into and the rules it is filled
/// with.
struct Case {
    name: String,
    polygon: Polygon,
    targets: &'static [Size],
    rules: &'static [FillRule],
}

impl Case {
    fn new(name: impl Into<String>, contours: Vec<Vec<Point>>) -> Self {
        let polygon = Polygon { contours, color: 7, rule: FillRule::EvenOdd };
        Self { name: name.into(), polygon, targets: TARGETS, rules: BOTH_RULES }
    }

    /// A case of one contour in subpixels.
    fn subpixels(name: impl Into<String>, points: &[(i32, i32)]) -> Self {
        Self::new(name, vec![points.iter().map(|&(x, y)| Point::new(x, y)).collect()])
    }

    /// A case of one contour in whole pixels.
    fn pixels(name: impl Into<String>, points: &[(i32, i32)]) -> Self {
        Self::new(name, vec![points.iter().map(|&(x, y)| Point::from_pixels(x, y)).collect()])
    }

    /// This case on the small targets only (see where it is used for why).
    fn off_screen_only(self) -> Self {
        Self { targets: SMALL_TARGETS, ..self }
    }

    /// This case on the small targets with both rules, and on the screen
    /// with the even-odd rule only. For the cases of thousands of
    /// vertices, whose fills take up to a second each on the screen in a
    /// debug build (LaMothe's fans of thousands of triangles, `exact` and
    /// `abrash_aet` with thousands of edges on every row): only `exact`
    /// honours the non-zero rule, its non-zero path is the same on the
    /// small targets with fewer rows, and `exact_hostile.rs` holds it to
    /// the reference on thousands of vertices with both rules.
    fn on_the_screen_with_one_rule(self) -> [Self; 2] {
        let name = self.name.clone();
        let on_the_screen =
            Self { name, polygon: self.polygon.clone(), targets: &[SCREEN], rules: &[FillRule::EvenOdd] };
        [Self { targets: SMALL_TARGETS, ..self }, on_the_screen]
    }
}

/// Whether `method` may decline `polygon` with `refusal`, by its docs:
/// `abrash_aet` and `exact` take every polygon; the others take one
/// contour; `pendleton` and `wgt` have a coordinate range (fp14 and 16-bit
/// `int` in their originals).
fn may_refuse(method: &str, polygon: &Polygon, refusal: Refusal) -> bool {
    match (method, refusal) {
        ("abrash_aet" | "exact", _) => false,
        (_, Refusal::MultipleContours) => polygon.contours.len() != 1,
        ("pendleton" | "wgt", Refusal::OutOfRange) => true,
        _ => false,
    }
}

/// Which fill is running, for the hang guard.
#[derive(Clone, Copy)]
struct Running {
    /// Counts the fills, so that the guard knows a new one from the last.
    fill: u64,
    case: usize,
    method: usize,
    rule: FillRule,
    size: Size,
}

/// The calling thread's id, as `/proc/self/task` names it.
fn this_thread() -> String {
    let link = std::fs::read_link("/proc/thread-self").expect("the hang guard reads the CPU time from /proc (Linux)");
    link.file_name().expect("/proc/thread-self is PID/task/TID").to_string_lossy().into_owned()
}

/// The CPU time (user and system) thread `thread` of this process has
/// used: fields 14 and 15 of `/proc/self/task/TID/stat`, in clock ticks,
/// a hundredth of a second each on Linux.
fn cpu_time(thread: &str) -> Duration {
    let path = format!("/proc/self/task/{thread}/stat");
    let stat = std::fs::read_to_string(&path).unwrap_or_else(|error| panic!("{path}: {error}"));
    // `TID (COMMAND) STATE ...`: the command may hold spaces, so the fields
    // count from its end, STATE being field 3.
    let fields: Vec<&str> = stat.rsplit_once(") ").map(|(_, rest)| rest.split(' ').collect()).unwrap_or_default();
    let ticks = |field: usize| -> u64 {
        fields.get(field - 3).and_then(|value| value.parse().ok()).unwrap_or_else(|| panic!("{path}: `{stat}`"))
    };
    Duration::from_millis((ticks(14) + ticks(15)) * 10)
}

fn describe(cases: &[Case], case: usize, method: usize, rule: FillRule, size: Size) -> String {
    let Size { width, height } = size;
    format!("{} on {} ({}, {width}x{height})", MethodId::ALL[method].name(), cases[case].name, rule.name())
}

/// Fills every case with every method, with each of its rules, into each
/// of its targets, on a worker thread this one watches for hangs: a fill
/// seen running on two looks has used at least the worker's CPU time
/// between them.
fn survive(cases: Vec<Case>) {
    let cases = Arc::new(cases);
    let running = Arc::new(Mutex::new(None::<Running>));
    let (sender, receiver) = mpsc::channel();
    let worker = {
        let (cases, running) = (Arc::clone(&cases), Arc::clone(&running));
        thread::spawn(move || {
            sender.send(this_thread()).expect("the guard waits for the worker's id");
            fill_all(&cases, &running)
        })
    };
    let worker_thread = receiver.recv().expect("the worker says who it is");
    // The fill last seen running, and the worker's CPU time then.
    let mut watched: Option<(u64, Duration)> = None;
    while !worker.is_finished() {
        thread::sleep(Duration::from_millis(20));
        let Some(r) = *running.lock().unwrap() else { continue };
        let used = cpu_time(&worker_thread);
        match watched {
            Some((fill, since)) if fill == r.fill => {
                let spent = used.saturating_sub(since);
                assert!(
                    spent < HANG_LIMIT,
                    "{} still running after {spent:?} of CPU time",
                    describe(&cases, r.case, r.method, r.rule, r.size)
                );
            }
            _ => watched = Some((r.fill, used)),
        }
    }
    let failures = worker.join().expect("the worker catches every panic");
    assert!(failures.is_empty(), "{} failures:\n{}", failures.len(), failures.join("\n"));
}

fn fill_all(cases: &[Case], running: &Mutex<Option<Running>>) -> Vec<String> {
    let mut failures = Vec::new();
    let mut fill = 0;
    for (case_index, case) in cases.iter().enumerate() {
        for &rule in case.rules {
            let polygon = Polygon { rule, ..case.polygon.clone() };
            for (method_index, method) in MethodId::ALL.map(MethodId::method).into_iter().enumerate() {
                for &size in case.targets {
                    fill += 1;
                    *running.lock().unwrap() =
                        Some(Running { fill, case: case_index, method: method_index, rule, size });
                    let mut sink = CoverageSink::new(size);
                    let outcome = panic::catch_unwind(AssertUnwindSafe(|| method.fill(&polygon, &mut sink)));
                    let failure = match outcome {
                        Err(payload) => Some(format!("panicked: {}", panic_message(payload.as_ref()))),
                        Ok(_) if sink.out_of_bounds() > 0 => {
                            Some(format!("{} spans outside the target", sink.out_of_bounds()))
                        }
                        Ok(Err(refusal)) if !may_refuse(method.info().name, &polygon, refusal) => {
                            Some(format!("declined it: {}", refusal.describe()))
                        }
                        Ok(_) => None,
                    };
                    if let Some(failure) = failure {
                        failures.push(format!("{}: {failure}", describe(cases, case_index, method_index, rule, size)));
                    }
                }
            }
        }
    }
    *running.lock().unwrap() = None;
    failures
}

fn panic_message(payload: &(dyn std::any::Any + Send)) -> &str {
    payload
        .downcast_ref::<&str>()
        .copied()
        .or_else(|| payload.downcast_ref::<String>().map(String::as_str))
        .unwrap_or("?")
}

/// A small deterministic generator (Numerical Recipes' LCG), so the random
/// cases are the same on every run.
struct Lcg(u32);

impl Lcg {
    fn next(&mut self) -> i32 {
        self.0 = self.0.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
        self.0 as i32
    }

    /// A value in `low..high`.
    fn within(&mut self, low: i32, high: i32) -> i32 {
        low + (self.next() as u32 % (high - low) as u32) as i32
    }
}

const PX: i32 = SUBPIXEL_ONE;
const MIN: i32 = i32::MIN;
const MAX: i32 = i32::MAX;

#[test]
fn fewer_than_three_vertices_collinear_and_repeated_points() {
    survive(vec![
        Case::new("no contours", vec![]),
        Case::new("one empty contour", vec![vec![]]),
        Case::pixels("one vertex", &[(3, 3)]),
        Case::pixels("two vertices", &[(3, 3), (4, 4)]),
        Case::subpixels("two vertices, a long way", &[(0, 0), (2000, 1500)]),
        Case::subpixels("two vertices across the plane", &[(MIN, MIN), (MAX, MAX)]),
        Case::pixels("one point three times", &[(3, 3), (3, 3), (3, 3)]),
        Case::pixels("every vertex twice", &[(1, 1), (1, 1), (4, 4), (4, 4)]),
        Case::pixels("a square, every vertex twice", &[(1, 1), (1, 1), (6, 1), (6, 1), (6, 4), (6, 4), (1, 4), (1, 4)]),
        Case::pixels("collinear, diagonal", &[(0, 0), (4, 2), (8, 4)]),
        Case::subpixels(
            "collinear through centres, back and forth",
            &[(128, 128), (2688, 2688), (1408, 1408), (5248, 5248)],
        ),
        Case::subpixels("collinear, horizontal, doubling back", &[(0, 300), (9000, 300), (-4000, 300)]),
        Case::pixels("collinear, vertical", &[(4, -1), (4, 50), (4, 3)]),
        Case::subpixels("collinear across the plane", &[(MIN, MIN), (MAX, MAX), (0, 0), (-1, -1)]),
    ]);
}

/// Every contour of `vertices` vertices whose coordinates are all in
/// {`i32::MIN`, 0, `i32::MAX`}: 9 points, 9^`vertices` contours.
fn contours_of_i32_extremes(vertices: usize) -> Vec<Vec<Point>> {
    let values = [MIN, 0, MAX];
    let points: Vec<Point> = values.iter().flat_map(|&x| values.iter().map(move |&y| Point::new(x, y))).collect();
    let mut contours = vec![vec![]];
    for _ in 0..vertices {
        contours =
            contours.iter().flat_map(|c: &Vec<Point>| points.iter().map(move |&p| [&c[..], &[p]].concat())).collect();
    }
    contours
}

#[test]
fn every_triangle_of_i32_extremes() {
    survive(contours_of_i32_extremes(3).into_iter().map(|c| Case::new(format!("triangle {c:?}"), vec![c])).collect());
}

#[test]
fn every_quad_of_i32_extremes() {
    // 6561 quads: on the small targets only. Most of them cover the screen,
    // where each fill would work through all its rows to learn nothing the
    // 7x3 target does not show: the same arithmetic on the same extremes,
    // the same clipping (their vertices at 0 are inside both targets).
    let quads =
        contours_of_i32_extremes(4).into_iter().map(|c| Case::new(format!("quad {c:?}"), vec![c]).off_screen_only());
    survive(quads.collect());
}

#[test]
fn absurd_but_finite_coordinates() {
    // The edges of the methods' ranges: 2^23 subpixels (32768 px, where
    // Pendleton's fp14 and WGT's 16-bit `int` end, and LaMothe's 16.16
    // wraps), a pixel either side, the rounding boundary (32767.5 px), and
    // the ends of `i32`.
    let edges = [
        MIN,
        MIN + 1,
        -(1 << 30),
        -(1 << 23) - 1,
        -(1 << 23),
        -(1 << 23) + 128,
        -1,
        0,
        1,
        (1 << 23) - 129,
        (1 << 23) - 128,
        (1 << 23) - 1,
        1 << 23,
        1 << 30,
        MAX - 1,
        MAX,
    ];
    let mut cases = Vec::new();
    for &a in &edges {
        for &b in &edges {
            cases.push(Case::subpixels(format!("range edges {a} {b}"), &[(a, b), (b, a), (a, a)]));
        }
    }
    cases.extend([
        Case::subpixels("a pentagram over the plane", &[(MAX, MAX), (MIN, MIN), (MAX, MIN), (0, 0), (MIN, MAX)]),
        Case::subpixels("across the plane, one pixel tall", &[(MIN, 1000), (MAX, 1000), (0, 1256)]),
        Case::subpixels("across the plane, one subpixel tall", &[(MIN, 1000), (MAX, 1001), (0, 1001)]),
        Case::subpixels("a needle from the top of the plane", &[(0, MIN), (1, MAX), (-1, MAX)]),
        Case::subpixels("slope across the plane", &[(MIN, 0), (MAX, 256), (0, MAX)]),
        Case::subpixels(
            "near the i32 end, almost flat",
            &[(8_388_000 * PX, 0), (-8_388_000 * PX, 10 * PX), (0, 20 * PX)],
        ),
        Case::subpixels(
            "beyond 16 bits",
            &[(40_000 * PX, -30_000 * PX), (-40_000 * PX, 30_000 * PX), (32_767 * PX, 32_767 * PX)],
        ),
        Case::pixels("WGT's sentinel column", &[(-16000, 0), (3, 0), (3, 4), (-16000, 4)]),
        Case::pixels("on row 32767", &[(0, 32760), (5, 32767), (0, 32767)]),
        Case::pixels("far off the screen", &[(-1_000_000, -1_000_000), (-999_990, -1_000_000), (-999_990, -999_990)]),
    ]);
    survive(cases);
}

#[test]
fn thousands_of_random_vertices() {
    // `abrash_aet` keeps the book's bubble sort, quadratic in the active
    // edges on rows where many cross: the 3000 points near the screen are
    // its worst case here, about half a second on the screen in debug.
    let mut random = Lcg(0x2545_f491);
    let near_the_screen: Vec<(i32, i32)> =
        (0..3000).map(|_| (random.within(-40 * PX, 360 * PX), random.within(-40 * PX, 240 * PX))).collect();
    let scattered: Vec<(i32, i32)> =
        (0..3000).map(|_| (random.next(), random.next() >> (random.next() as u32 & 31))).collect();
    survive(
        [
            Case::subpixels("3000 random points near the screen", &near_the_screen).on_the_screen_with_one_rule(),
            Case::subpixels("3000 points scattered over the plane", &scattered).on_the_screen_with_one_rule(),
        ]
        .into_iter()
        .flatten()
        .collect(),
    );
}

#[test]
fn thousands_of_vertices_in_a_zigzag() {
    let zigzag: Vec<(i32, i32)> = (0..5000).map(|i| (i % 400 - 40, if i % 2 == 0 { -10 } else { 210 })).collect();
    let tall_zigzag: Vec<(i32, i32)> = (0..5000).map(|i| (i % 7 * 40 - 100, i / 2 - 1000)).collect();
    let mut cases = vec![Case::pixels("a zigzag of 5000, mostly off the screen", &tall_zigzag)];
    cases.extend(Case::pixels("a zigzag of 5000 across the screen", &zigzag).on_the_screen_with_one_rule());
    survive(cases);
}

#[test]
fn thousands_of_vertices_in_a_star() {
    let star: Vec<(i32, i32)> = (0..5001).map(|i| (i * 389 % 997 - 300, i * 7919 % 1009 - 400)).collect();
    survive(Case::pixels("a star of 5001", &star).on_the_screen_with_one_rule().into());
}

#[test]
fn several_contours() {
    let square = |from: i32, to: i32| -> Vec<Point> {
        [(from, from), (to, from), (to, to), (from, to)].iter().map(|&(x, y)| Point::from_pixels(x, y)).collect()
    };
    let reversed = |mut contour: Vec<Point>| {
        contour.reverse();
        contour
    };
    let plane: Vec<Point> =
        [(MIN, MIN), (MAX, MIN), (MAX, MAX), (MIN, MAX)].iter().map(|&(x, y)| Point::new(x, y)).collect();
    let mut random = Lcg(0x0bad_cafe);
    let triangles: Vec<Vec<Point>> = (0..1000)
        .map(|_| {
            (0..3).map(|_| Point::new(random.within(-20 * PX, 340 * PX), random.within(-20 * PX, 220 * PX))).collect()
        })
        .collect();
    survive(vec![
        Case::new(
            "an empty, a one-point and a two-point contour",
            vec![vec![], vec![Point::from_pixels(3, 3)], vec![Point::from_pixels(1, 1), Point::from_pixels(5, 5)]],
        ),
        Case::new("two one-point contours", vec![vec![Point::new(0, 0)], vec![Point::new(1, 1)]]),
        Case::new("a ring", vec![square(1, 6), square(2, 4)]),
        Case::new("a ring, the hole wound the other way", vec![square(1, 6), reversed(square(2, 4))]),
        Case::new("overlapping squares", vec![square(0, 5), square(3, 8)]),
        Case::new("the plane with a hole", vec![plane.clone(), square(2, 4)]),
        Case::new("the plane twice", vec![plane.clone(), reversed(plane)]),
        Case::new("1000 random triangles", triangles),
    ]);
}
