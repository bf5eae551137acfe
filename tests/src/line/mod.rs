//! The protocol over a real serial line, which QEMU's stdio is not: a
//! tty device opened raw at 115200 baud 8N1 (`tty`), commands sealed so
//! that the kernel refuses a damaged one and each reply names the line it
//! answers, steps retried when the line damages or loses something
//! (`sealed`), and a relay that damages a line on purpose to prove it
//! (`relay`).

mod relay;
mod sealed;
mod tty;

pub use relay::{FaultCounts, FaultRates, Relay};
pub use sealed::transfer_time;
pub use sealed::{LineStats, Sealing, Trouble, TroubleKind};
pub use tty::open_console;

/// The kernel's line speed.
pub const BAUD: u32 = 115_200;
