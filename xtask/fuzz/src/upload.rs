//! The `upload` target: any bytes as what the kernel's end of an upload
//! meets (`protocol::Upload`, the code the kernel's server runs for
//! `UPLOAD` and `CHUNK`), and as a packed scene (`scenes::packed`).
//!
//! - Split at newlines, the bytes are command lines; each `UPLOAD` or
//!   `CHUNK` among them goes to one `Upload`, as the server hands them on.
//!   Nothing panics; a scene kept whole holds no more memory than its
//!   `UPLOAD` declared, and `exact` fills it inside the screen refusing no
//!   polygon.
//! - Whole, the bytes are a packed scene: unpacking never panics nor takes
//!   more than its bound, and what it accepts packs to bytes that unpack to
//!   the same scene.

use base64::Engine;
use protocol::{Command, Upload, UPLOAD_BUDGET};
use raster::{CoverageSink, FillRule, MethodId, Point, Polygon, SCREEN};
use scenes::{packed, Op, Scene};

pub fn check(data: &[u8]) {
    let mut upload = Upload::default();
    let mut declared = 0;
    for line in data.split(|&byte| byte == b'\n') {
        match Command::parse(line) {
            Ok(Command::Upload { name, bytes, memory, crc }) if upload.start(name, bytes, memory, crc).is_ok() => {
                declared = memory;
            }
            Ok(Command::Chunk { offset, data }) => {
                if let Ok(reply) = upload.chunk(offset, data) {
                    assert!(reply.received <= reply.total, "{reply}");
                }
            }
            _ => {}
        }
        if let Upload::Whole { scene, .. } = &upload {
            assert!(packed::memory(scene) <= declared, "{} holds more than the {declared} declared", scene.name);
            fills_inside_the_screen(scene);
        }
    }
    if let Ok(scene) = packed::unpack("fuzz".to_string(), data, UPLOAD_BUDGET) {
        assert!(packed::memory(&scene) <= UPLOAD_BUDGET);
        let again = packed::pack(&scene);
        assert_eq!(packed::unpack("fuzz".to_string(), &again, UPLOAD_BUDGET).as_ref(), Ok(&scene));
    }
}

fn fills_inside_the_screen(scene: &Scene) {
    let mut sink = CoverageSink::new(SCREEN);
    let report = scene.draw(MethodId::Exact, &mut sink);
    assert_eq!(sink.out_of_bounds(), 0, "exact drew {} outside the screen", scene.name);
    assert_eq!(report.refused, 0, "exact refused {:?} in {}", report.first_refusal, scene.name);
}

/// The lines that upload `scene` under `name` in chunks of `each` bytes.
fn upload_lines(name: &str, scene: &Scene, each: usize) -> Vec<u8> {
    let bytes = packed::pack(scene);
    let start =
        Command::Upload { name, bytes: bytes.len(), memory: packed::memory(scene), crc: crc32fast::hash(&bytes) };
    let mut lines = format!("{start}\n");
    for (i, chunk) in bytes.chunks(each).enumerate() {
        let data = base64::engine::general_purpose::STANDARD.encode(chunk);
        lines.push_str(&format!("{}\n", Command::Chunk { offset: i * each, data: &data }));
    }
    lines.into_bytes()
}

/// Every built-in page uploaded in chunks of a few sizes, a scene with a
/// palette and a hole, each page's packed bytes alone, and a damaged
/// upload.
pub fn seeds() -> Vec<(String, Vec<u8>)> {
    let mut seeds = Vec::new();
    for page in &scenes::builtin::ALL {
        let scene = page.scene();
        for each in [7, 64, 1024] {
            seeds.push((format!("{}-chunks-of-{each}", page.name), upload_lines("page", &scene, each)));
        }
        seeds.push((format!("{}-packed", page.name), packed::pack(&scene)));
    }
    let square = |at: i32, side: i32| {
        vec![Point::new(at, at), Point::new(at + side, at), Point::new(at + side, at + side), Point::new(at, at + side)]
    };
    let polygon = Polygon { contours: vec![square(0, 9000), square(2000, 3000)], color: 4, rule: FillRule::EvenOdd };
    let mut scene = Scene::new("hole".to_string(), vec![Op::Clear(1), Op::Fill(polygon)], MethodId::Exact);
    scene.palette.push(scenes::PaletteEntry { index: 4, rgb: [63, 40, 0] });
    let lines = upload_lines("hole", &scene, 16);
    seeds.push(("hole".to_string(), lines.clone()));
    let mut damaged = lines;
    let last = damaged.len() - 3;
    damaged[last] ^= 0x01;
    seeds.push(("hole-damaged".to_string(), damaged));
    seeds
}

/// The commands' words.
pub fn dictionary() -> Vec<String> {
    ["UPLOAD ", "CHUNK ", "PLS1", "\n", " ", "0", "1024", "==", "AAAA"].map(String::from).into()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_uploaded_seed_is_kept_whole() {
        let scene = scenes::builtin::ALL[0].scene();
        let mut upload = Upload::default();
        for line in upload_lines("page", &scene, 64).split(|&byte| byte == b'\n') {
            match Command::parse(line) {
                Ok(Command::Upload { name, bytes, memory, crc }) => {
                    upload.start(name, bytes, memory, crc).unwrap();
                }
                Ok(Command::Chunk { offset, data }) => {
                    upload.chunk(offset, data).unwrap();
                }
                _ => {}
            }
        }
        let kept = upload.scene("page").expect("the page is kept whole");
        assert_eq!(kept.ops, scene.ops);
    }
}
