//! The kernel's end of an upload, here so that the host can test and fuzz
//! it as the kernel runs it: `UPLOAD` states the scene's name, its packed
//! size, the memory it unpacks to and its CRC-32; `CHUNK`s bring its bytes
//! in base64, each at its offset; once the last byte is in, the whole is
//! checked against the CRC-32 and unpacked (`scenes::packed`), and the
//! scene is kept for `DRAW NAME` and `BENCH NAME` until the next `UPLOAD`.
//!
//! Memory is bounded before any is taken: the packed bytes and the
//! unpacked scene together may not pass `protocol::UPLOAD_BUDGET`, and
//! unpacking holds the scene to the memory `UPLOAD` declared. A chunk sent
//! twice (its answer lost on a bad line) writes the same bytes again, so a
//! host may retry any chunk; an upload that fails its CRC-32 or does not
//! unpack is dropped, and nothing of it is drawn.

use alloc::string::String;
use alloc::vec::Vec;

use base64::Engine;
use scenes::packed::{self, UnpackError};
use scenes::{builtin, Scene};

use crate::{ChunkReply, ErrorReply, UploadReply, UPLOAD_BUDGET};

/// What the host has uploaded.
#[derive(Debug, Default)]
pub enum Upload {
    #[default]
    Nothing,
    /// An upload under way.
    Receiving(Receiving),
    /// The last upload, whole and unpacked: `total` packed bytes.
    Whole { scene: Scene, total: usize },
}

/// An upload under way.
#[derive(Debug)]
pub struct Receiving {
    name: String,
    /// The packed bytes, as long as the whole upload; those past
    /// `received` are not in yet.
    bytes: Vec<u8>,
    /// Bytes in from the start, with no gap.
    received: usize,
    /// Memory the unpacked scene may hold, as `UPLOAD` declared.
    memory: usize,
    crc: u32,
}

impl Upload {
    /// `UPLOAD`: drops what was uploaded before, and waits for `bytes`
    /// packed bytes, if they and `memory` fit the budget.
    pub fn start<'a>(
        &mut self,
        name: &'a str,
        bytes: usize,
        memory: usize,
        crc: u32,
    ) -> Result<UploadReply<'a>, ErrorReply<'a>> {
        *self = Upload::Nothing;
        if builtin::named(name).is_some() {
            return Err(ErrorReply::BuiltinName(name));
        }
        if bytes.checked_add(memory).is_none_or(|total| total > UPLOAD_BUDGET) {
            return Err(ErrorReply::OverBudget { bytes, memory, budget: UPLOAD_BUDGET });
        }
        let mut buffer = Vec::new();
        buffer.try_reserve_exact(bytes).map_err(|_| ErrorReply::Unpack(UnpackError::OutOfMemory))?;
        buffer.resize(bytes, 0);
        *self = Upload::Receiving(Receiving { name: String::from(name), bytes: buffer, received: 0, memory, crc });
        Ok(UploadReply { name, bytes, memory, budget: UPLOAD_BUDGET })
    }

    /// `CHUNK`: `data`'s bytes at `offset`; once the upload is whole, it is
    /// checked and unpacked.
    pub fn chunk(&mut self, offset: usize, data: &str) -> Result<ChunkReply, ErrorReply<'static>> {
        let data = base64::engine::general_purpose::STANDARD.decode(data).map_err(|_| ErrorReply::NotBase64)?;
        let (received, total) = match self {
            Upload::Nothing => return Err(ErrorReply::NoUpload),
            Upload::Receiving(receiving) => (receiving.received, receiving.bytes.len()),
            // Sent again after the last chunk was answered: already whole.
            Upload::Whole { total, .. } => (*total, *total),
        };
        let end = offset.checked_add(data.len()).filter(|&end| offset <= received && end <= total);
        let Some(end) = end else {
            return Err(ErrorReply::ChunkOutOfPlace { offset, bytes: data.len(), received, total });
        };
        let Upload::Receiving(receiving) = self else { return Ok(ChunkReply { received, total }) };
        receiving.bytes[offset..end].copy_from_slice(&data);
        receiving.received = received.max(end);
        if receiving.received < total {
            return Ok(ChunkReply { received: receiving.received, total });
        }
        let Upload::Receiving(whole) = core::mem::take(self) else { return Err(ErrorReply::NoUpload) };
        let scene = whole.unpack()?;
        *self = Upload::Whole { scene, total };
        Ok(ChunkReply { received: total, total })
    }

    /// The uploaded scene called `name`, if it is whole.
    pub fn scene(&self, name: &str) -> Option<&Scene> {
        match self {
            Upload::Whole { scene, .. } if scene.name == name => Some(scene),
            _ => None,
        }
    }
}

impl Receiving {
    /// The scene, if the bytes check against the CRC-32 declared and
    /// unpack within the memory declared.
    fn unpack(self) -> Result<Scene, ErrorReply<'static>> {
        let actual = crc32fast::hash(&self.bytes);
        if actual != self.crc {
            return Err(ErrorReply::UploadDamaged { declared: self.crc, actual });
        }
        packed::unpack(self.name, &self.bytes, self.memory).map_err(ErrorReply::Unpack)
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use raster::{FillRule, MethodId, Point, Polygon};
    use scenes::{Op, PaletteEntry};
    use std::string::ToString;
    use std::vec;

    fn scene() -> Scene {
        let square = vec![Point::new(0, 0), Point::new(2560, 0), Point::new(2560, 2560), Point::new(0, 2560)];
        let fill = Op::Fill(Polygon { contours: vec![square], color: 9, rule: FillRule::NonZero });
        let mut scene = Scene::new("mine".to_string(), vec![Op::Clear(2), fill], MethodId::Exact);
        scene.palette.push(PaletteEntry { index: 9, rgb: [63, 0, 0] });
        scene
    }

    fn base64(bytes: &[u8]) -> String {
        base64::engine::general_purpose::STANDARD.encode(bytes)
    }

    /// `scene` started and sent in chunks of `each` bytes, in order.
    fn uploaded(scene: &Scene, each: usize) -> Upload {
        let bytes = packed::pack(scene);
        let mut upload = Upload::default();
        let reply = upload.start("mine", bytes.len(), packed::memory(scene), crc32fast::hash(&bytes)).unwrap();
        assert_eq!(reply.budget, UPLOAD_BUDGET);
        for (i, chunk) in bytes.chunks(each).enumerate() {
            let reply = upload.chunk(i * each, &base64(chunk)).unwrap();
            assert_eq!(reply, ChunkReply { received: i * each + chunk.len(), total: bytes.len() });
        }
        upload
    }

    #[test]
    fn a_scene_sent_in_chunks_is_kept_whole_under_its_name() {
        for each in [1, 3, 7, 1000] {
            let upload = uploaded(&scene(), each);
            assert_eq!(upload.scene("mine"), Some(&scene()), "chunks of {each}");
            assert_eq!(upload.scene("yours"), None);
        }
    }

    #[test]
    fn a_chunk_sent_again_does_no_harm_even_after_the_last() {
        let bytes = packed::pack(&scene());
        let mut upload = Upload::default();
        upload.start("mine", bytes.len(), packed::memory(&scene()), crc32fast::hash(&bytes)).unwrap();
        let (head, tail) = bytes.split_at(10);
        for _ in 0..2 {
            assert_eq!(upload.chunk(0, &base64(head)), Ok(ChunkReply { received: 10, total: bytes.len() }));
        }
        let whole = ChunkReply { received: bytes.len(), total: bytes.len() };
        for _ in 0..2 {
            assert_eq!(upload.chunk(10, &base64(tail)), Ok(whole));
        }
        assert_eq!(upload.chunk(0, &base64(head)), Ok(whole));
        assert_eq!(upload.scene("mine"), Some(&scene()));
    }

    #[test]
    fn what_does_not_fit_is_refused_and_nothing_is_kept() {
        let mut upload = uploaded(&scene(), 5);
        let over = UPLOAD_BUDGET - 99;
        assert_eq!(
            upload.start("big", 100, over, 0),
            Err(ErrorReply::OverBudget { bytes: 100, memory: over, budget: UPLOAD_BUDGET })
        );
        assert_eq!(upload.scene("mine"), None, "a new upload drops the last");
        let refused = upload.start("big", usize::MAX, 1, 0);
        assert_eq!(refused, Err(ErrorReply::OverBudget { bytes: usize::MAX, memory: 1, budget: UPLOAD_BUDGET }));
        assert_eq!(upload.start("abrash38-1", 10, 10, 0), Err(ErrorReply::BuiltinName("abrash38-1")));
        assert_eq!(upload.chunk(0, "AAAA"), Err(ErrorReply::NoUpload));
        upload.start("mine", 8, 100, 0).unwrap();
        assert_eq!(upload.chunk(0, "not base64!"), Err(ErrorReply::NotBase64));
        assert_eq!(
            upload.chunk(3, "AAAA"),
            Err(ErrorReply::ChunkOutOfPlace { offset: 3, bytes: 3, received: 0, total: 8 })
        );
        assert_eq!(upload.chunk(0, "AAAA"), Ok(ChunkReply { received: 3, total: 8 }));
        assert_eq!(
            upload.chunk(3, &base64(&[0; 6])),
            Err(ErrorReply::ChunkOutOfPlace { offset: 3, bytes: 6, received: 3, total: 8 })
        );
        assert_eq!(
            upload.chunk(usize::MAX, "AAAA"),
            Err(ErrorReply::ChunkOutOfPlace { offset: usize::MAX, bytes: 3, received: 3, total: 8 })
        );
    }

    #[test]
    fn a_damaged_or_unreadable_upload_is_dropped() {
        let bytes = packed::pack(&scene());
        let mut upload = Upload::default();
        let crc = crc32fast::hash(&bytes);
        upload.start("mine", bytes.len(), packed::memory(&scene()), crc ^ 1).unwrap();
        let damaged = upload.chunk(0, &base64(&bytes));
        assert_eq!(damaged, Err(ErrorReply::UploadDamaged { declared: crc ^ 1, actual: crc }));
        assert_eq!(upload.chunk(0, &base64(&bytes)), Err(ErrorReply::NoUpload));
        let less = packed::memory(&scene()) - 1;
        upload.start("mine", bytes.len(), less, crc).unwrap();
        assert_eq!(upload.chunk(0, &base64(&bytes)), Err(ErrorReply::Unpack(UnpackError::OverBudget { budget: less })));
        let garbage = [7u8; 12];
        upload.start("mine", garbage.len(), 100, crc32fast::hash(&garbage)).unwrap();
        assert_eq!(upload.chunk(0, &base64(&garbage)), Err(ErrorReply::Unpack(UnpackError::NotPacked)));
        assert_eq!(upload.scene("mine"), None);
    }
}
