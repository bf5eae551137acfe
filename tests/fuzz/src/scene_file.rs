//! The `scene_file` target: any text as a scene file (`scenes::file`).
//! Parsing never panics, and what it accepts:
//! - renders with every method, inside the screen, and `exact` draws every
//!   polygon (it refuses none);
//! - written back (`file::write`) parses to the very same operations;
//! - reaches the kernel as the host sends it (`dump` and `run`): each
//!   polygon's line, in a `POLY` command that fits a command line, is
//!   accepted by the protocol's parser, and the kernel's `parse_poly` reads
//!   it as the same polygon.

use protocol::{Command, MAX_LINE};
use raster::{CoverageSink, MethodId, SCREEN};
use scenes::file;
use scenes::Op;

pub fn check(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else { return };
    let parsed = file::parse("fuzz", text);
    let lines = file::parse_lines(text);
    let scene = match (parsed, lines) {
        (Ok(scene), Ok(lines)) => {
            let ops: Vec<&Op> = lines.iter().map(|line| &line.op).collect();
            assert_eq!(ops, scene.ops.iter().collect::<Vec<_>>(), "parse and parse_lines disagree");
            reaches_the_kernel(&lines);
            scene
        }
        (Err(error), Err(same)) => {
            assert_eq!(error, same, "parse and parse_lines reject differently");
            return;
        }
        (parsed, lines) => panic!("parse says {parsed:?}, parse_lines {lines:?}"),
    };
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
    assert_eq!(again.ops, scene.ops, "written back as {written:?}");
}

/// Each polygon line as the harness sends it, `POLY exact <spec>`, when it
/// fits a command line.
fn reaches_the_kernel(lines: &[file::Line<'_>]) {
    for line in lines {
        let Op::Fill(polygon) = &line.op else { continue };
        let command = Command::Poly { method: MethodId::Exact, spec: line.spec };
        let sent = command.to_string();
        if sent.len() > MAX_LINE {
            continue;
        }
        assert_eq!(Command::parse(sent.as_bytes()), Ok(command), "line {}", line.number);
        assert_eq!(file::parse_poly(line.spec).as_ref(), Ok(polygon), "line {}", line.number);
    }
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
    ["clear", "poly", "color=", "rule=", "evenodd", "nonzero", "|", "#", ",", ".", "-", "\n", " "]
        .map(String::from)
        .into()
}
