//! Running the image in QEMU: what a run is asked for (`options.rs`, the
//! machine around the card in `board.rs`), QEMU's command line, every flag
//! saying why (`arguments.rs`), the running process and its channels
//! (`process.rs`: COM1 on the child's stdin/stdout, QMP on a unix socket,
//! `qmp.rs`), and the protocol spoken on COM1 (`serial.rs` finds the
//! frames, `console.rs` sends commands and reads the replies).

mod arguments;
mod board;
pub(crate) mod channel;
pub mod console;
mod options;
mod process;
pub mod qmp;
pub mod reply;
pub mod serial;

pub use board::{Board, DisplayAhead};
pub use options::{Adapter, Clock, Cpu, Display, ExitDevice, Medium, QemuOptions, SerialLine};
pub use process::Qemu;
