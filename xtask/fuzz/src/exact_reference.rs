//! The `exact_reference` target, differential: `exact` (through
//! [`fill_auto`] and each of its paths that takes the polygon) against
//! `raster::reference`, the brute-force judge, on any polygon filled into
//! a small target, where the judge is cheap. Any pixel that differs, any
//! pixel drawn twice, is a bug in one of the two
//! (`docs/conventions.md#what-exact-means`).

use raster::reference::{self, SampleOffset};
use raster::{fill_auto, CoverageReport, CoverageSink, ExactPath, Size};

use crate::polygon::{decode, Fill};

/// Small targets: the reference visits every pixel of the polygon's box
/// within the target for every edge.
pub const TARGETS: [Size; 4] = [
    Size { width: 40, height: 25 },
    Size { width: 1, height: 1 },
    Size { width: 7, height: 3 },
    Size { width: 16, height: 16 },
];

pub fn check(data: &[u8]) {
    let Fill { polygon, target } = decode(data);
    let size = TARGETS[target % TARGETS.len()];
    let mut judge = CoverageSink::new(size);
    reference::fill(&polygon, SampleOffset::CENTRE, &mut judge);
    let compare = |name: &str, sink: &CoverageSink| {
        assert_eq!(
            sink.report(&judge),
            CoverageReport::default(),
            "{name} on {polygon:?} into {size:?}:\n{}",
            sink.ascii_against(&judge)
        );
    };
    let mut sink = CoverageSink::new(size);
    assert_eq!(fill_auto(&polygon, &mut sink), Ok(()));
    compare("fill_auto", &sink);
    for path in ExactPath::every(&polygon) {
        let mut sink = CoverageSink::new(size);
        assert_eq!(path.fill(&mut sink), Ok(()));
        compare(path.name(), &sink);
    }
}

/// Every built-in polygon, into the largest of the small targets.
pub fn seeds() -> Vec<(String, Vec<u8>)> {
    crate::polygon::builtin_seeds(0)
}
