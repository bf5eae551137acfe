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
//!
//! The `key=value` reader they share is in `fields.rs`. The other texts
//! are prose for people, not read back into values: `ERR`, `LOG`,
//! `FATAL`, and the `OK` of `VGACHECK` and `FAULT strayinterrupt`.

mod bench;
mod clock;
mod demo;
mod drawn;
mod fields;
mod list;
mod pong;
mod ready;
mod show;

pub use bench::{BenchReply, BenchRow, BENCH_UNIT_LINE};
pub use clock::{ClockReadings, ClockSource, TscRate};
pub use demo::{DemoReply, OWN_METHOD};
pub use drawn::{Cleared, DrawReply};
pub use fields::{Expected, Malformed};
pub use list::Listing;
pub use pong::{HeapState, InterruptCounts, LineErrors, LineLosses, Pong, PONG};
pub use ready::{Firmware, Machine, MemoryType, PciAddress, PciId, Presentation, Ready, Video};
pub use show::ShowReply;
