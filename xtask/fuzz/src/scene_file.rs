//! The `scene_file` target: any text as a scene file (`scenes::file`).
//! Parsing never panics, and what it accepts:
//! - renders with every method, inside the screen, and `exact` draws every
//!   polygon (it refuses none);
//! - written back (`file::write`) parses to the very same palette and
//!   operations;
//! - reaches the kernel as the host sends it (`dump` and `run`): packed
//!   (`scenes::packed`), it unpacks to the very same scene within the
//!   memory it declares, and not within a byte less.

use raster::{CoverageSink, MethodId, SCREEN};
use scenes::{file, packed};

pub fn check(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else { return };
    let Ok(scene) = file::parse("fuzz", text) else { return };
    let bytes = packed::pack(&scene);
    let memory = packed::memory(&scene);
    let unpacked = packed::unpack(scene.name.clone(), &bytes, memory);
    assert_eq!(unpacked.as_ref(), Ok(&scene), "packed as {bytes:?}");
    if let Some(less) = memory.checked_sub(1) {
        let refused = packed::unpack(scene.name.clone(), &bytes, less);
        assert_eq!(refused, Err(packed::UnpackError::OverBudget { budget: less }));
    }
    for id in MethodId::ALL {
        let mut sink = CoverageSink::new(SCREEN);
        let report = scene.draw(id, &mut sink);
        assert_eq!(sink.out_of_bounds(), 0, "{id} drew outside the screen");
        if id == MethodId::Exact {
            assert_eq!(report.refused, 0, "exact refused {:?}", report.first_refusal);
        }
    }
    let written = file::write(&scene);
    let again = file::parse("fuzz", &written).unwrap_or_else(|error| panic!("written back as {written:?}: {error}"));
    assert_eq!((again.palette, again.ops), (scene.palette, scene.ops), "written back as {written:?}");
}

/// The built-in scenes written as scene files, and the scene of
/// `docs/scenes.md`'s example.
pub fn seeds() -> Vec<(String, Vec<u8>)> {
    let mut seeds: Vec<(String, Vec<u8>)> = scenes::builtin::ALL
        .iter()
        .map(|page| (page.name.to_string(), file::write(&page.scene()).into_bytes()))
        .collect();
    let example = "# a square with a square hole, then a triangle\nclear 0\n\
                   poly color=5 0,0 320,0 320,200 0,200 | 50,50 50,150 270,150 270,50\n\
                   poly color=14 rule=nonzero 160,30 50,150.5 270,180\n";
    seeds.push(("readme-example".to_string(), example.as_bytes().to_vec()));
    seeds
}

/// The words of the format.
pub fn dictionary() -> Vec<String> {
    ["clear", "poly", "palette", "color=", "rule=", "evenodd", "nonzero", "|", "#", ",", ".", "-", "\n", " "]
        .map(String::from)
        .into()
}
