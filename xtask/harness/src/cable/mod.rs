//! The protocol over a real serial cable, which QEMU's stdio is not: a
//! tty device opened raw at the kernel's speed, 8N1 (`tty`), spoken to by
//! a sealing console (`crate::client`: commands sealed so that the kernel
//! refuses a damaged one and each reply names the line it answers, steps
//! retried when the line damages or loses something), and a relay that
//! damages a line on purpose to prove it (`relay`).

mod relay;
mod tty;

pub use relay::{FaultCounts, FaultRates, Relay};
pub use tty::open_console;
