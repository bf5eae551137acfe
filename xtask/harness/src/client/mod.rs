//! The host end of the serial protocol, over any byte stream: QEMU's
//! stdio (`crate::qemu`), Bochs's COM1 socket (`crate::bochs`) or a real
//! serial line (`crate::cable`). `frame_reader.rs` finds the frames in
//! the bytes, `channel.rs` sends command bytes and keeps the `LOG`
//! frames on the way, `reply.rs` decodes the replies, `sealing.rs` seals
//! commands and retries steps on a line that can damage bytes, and
//! `console.rs` is the typed client over them all.

mod channel;
mod console;
mod frame_reader;
mod reply;
mod sealing;

pub use console::{pack_for_upload, upload_name, Console, Uploaded, READY_TIMEOUT};
pub(crate) use frame_reader::gather_after;
pub use frame_reader::{forward_bytes, Frame, FrameReader, ReadError, ReadErrorKind};
pub use reply::{Dump, Reply, REPLY_TIMEOUT};
pub use sealing::{transfer_time, LineStats, Sealing, Trouble, TroubleKind, BAUD};
