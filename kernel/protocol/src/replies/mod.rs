//! Kernel to host: the text of every reply the host reads back into
//! values, one file per reply or family of replies, named for its type. Each type's `Display`
//! writes the text (the kernel) and its `parse` reads it back (the
//! harness), refusing any text `Display` would not write with a
//! [`Malformed`] that names the reply and what it expected.
//!
//! | command          | frame   | type                | file              |
//! |------------------|---------|---------------------|-------------------|
//! | boot, `READY`    | `READY` | [`Ready`]           | `ready.rs`        |
//! | `PING`           | `OK`    | [`Pong`]            | `pong.rs`         |
//! | `CLOCK`          | `OK`    | [`TscRate`]         | `tsc_rate.rs`     |
//! | `SHOW`           | `OK`    | [`ShowReply`]       | `show_reply.rs`   |
//! | `DRAW`, `POLY`   | `OK`    | [`DrawReply`]       | `draw_reply.rs`   |
//! | `CLEAR`          | `OK`    | [`Cleared`]         | `draw_reply.rs`   |
//! | `DEMO`           | `OK`    | [`DemoReply`]       | `demo_reply.rs`   |
//! | `UPLOAD`         | `OK`    | [`UploadReply`]     | `upload_reply.rs` |
//! | `CHUNK`          | `OK`    | [`ChunkReply`]      | `upload_reply.rs` |
//! | `BENCH`          | `BENCH` | [`BenchReply`]      | `bench_reply.rs`  |
//! | `LIST`           | `LIST`  | [`Listing`]         | `listing.rs`      |
//! | `VGACHECK`       | `OK`, `ERR` | [`VgaCheck`] | `vga_check.rs`  |
//! | `FAULT strayinterrupt` | `OK` | [`StrayRaised`] | `fault_reply.rs` |
//!
//! The `key=value` reader they share is in `fields.rs`; the reader of the
//! texts written as sentences (`VGACHECK`'s, `FAULT`'s and the
//! `crate::events`), in `prose.rs`.

mod bench_reply;
mod demo_reply;
mod draw_reply;
mod fault_reply;
mod fields;
mod listing;
mod pong;
mod prose;
mod ready;
mod show_reply;
mod tsc_rate;
mod upload_reply;
mod vga_check;

pub use bench_reply::{BenchReply, BenchRow, BENCH_UNIT_LINE};
pub use demo_reply::{DemoReply, OWN_METHOD};
pub use draw_reply::{Cleared, DrawReply};
pub use fault_reply::{Raised, StrayRaised};
pub use fields::{Expected, Malformed};
pub use listing::Listing;
pub use pong::{HeapState, InterruptCounts, LineErrors, LineLosses, Pong, PONG};
pub(crate) use prose::{writes, Prose};
pub use ready::{Firmware, Machine, MemoryType, PciAddress, PciId, Presentation, Ready, Video};
pub use show_reply::ShowReply;
pub use tsc_rate::{ClockReadings, ClockSource, TscRate};
pub use upload_reply::{ChunkReply, UploadReply};
pub use vga_check::{FramebufferCheck, Mismatch, PageMapping, RegisterGroup, VgaCheck, Window};
