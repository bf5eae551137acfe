//! Kernel to host: the text of every reply the host reads back into
//! values, one file per reply or family of replies. Each type's `Display`
//! writes the text (the kernel) and its `parse` reads it back (the
//! harness), refusing any text `Display` would not write with a
//! [`Malformed`] that names the reply and what it expected.
//!
//! | command          | frame   | type                | file        |
//! |------------------|---------|---------------------|-------------|
//! | boot, `READY`    | `READY` | [`Ready`]           | `ready.rs`  |
//! | `PING`           | `OK`    | [`Pong`]            | `pong.rs`   |
//! | `CLOCK`          | `OK`    | [`TscRate`]         | `clock.rs`  |
//! | `SHOW`           | `OK`    | [`ShowReply`]       | `show.rs`   |
//! | `DRAW`, `POLY`   | `OK`    | [`DrawReply`]       | `drawn.rs`  |
//! | `CLEAR`          | `OK`    | [`Cleared`]         | `drawn.rs`  |
//! | `DEMO`           | `OK`    | [`DemoReply`]       | `demo.rs`   |
//! | `BENCH`          | `BENCH` | [`BenchReply`]      | `bench.rs`  |
//! | `LIST`           | `LIST`  | [`Listing`]         | `list.rs`   |
//! | `VGACHECK`       | `OK`, `ERR` | [`VgaCheck`]    | `vga_check.rs` |
//! | `FAULT strayinterrupt` | `OK` | [`StrayRaised`] | `fault.rs`  |
//!
//! The `key=value` reader they share is in `fields.rs`; the reader of the
//! texts written as sentences (`VGACHECK`'s, `FAULT`'s and the
//! `crate::events`), in `prose.rs`.

mod bench;
mod clock;
mod demo;
mod drawn;
mod fault;
mod fields;
mod list;
mod pong;
mod prose;
mod ready;
mod show;
mod vga_check;

pub use bench::{BenchReply, BenchRow, BENCH_UNIT_LINE};
pub use clock::{ClockReadings, ClockSource, TscRate};
pub use demo::{DemoReply, OWN_METHOD};
pub use drawn::{Cleared, DrawReply};
pub use fault::{Raised, StrayRaised};
pub use fields::{Expected, Malformed};
pub use list::Listing;
pub use pong::{HeapState, InterruptCounts, LineErrors, LineLosses, Pong, PONG};
pub(crate) use prose::{writes, Prose};
pub use ready::{Firmware, Machine, MemoryType, PciAddress, PciId, Presentation, Ready, Video};
pub use show::ShowReply;
pub use vga_check::{FramebufferCheck, Mismatch, PageMapping, RegisterGroup, VgaCheck, Window};
