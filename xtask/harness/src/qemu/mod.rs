//! Running the image in QEMU: what a run is asked for (`options.rs`, the
//! machine around the card in `board.rs`), QEMU's command line, every flag
//! saying why (`arguments.rs`), the running process and its channels
//! (`process.rs`: COM1 on the child's stdin/stdout, spoken to by the
//! protocol client of `crate::client`; QMP on a unix socket, `qmp.rs`).

mod arguments;
mod board;
mod options;
mod process;
pub mod qmp;

pub use board::{Board, DisplayAhead};
pub use options::{Adapter, Cpu, Display, ExitDevice, Medium, QemuOptions, SerialLine, TimeBase};
pub use process::Qemu;
