//! Kernel to host, the frames that are not a command's answer with
//! fields: `ERR` (why a line was not run, [`ErrorReply`]), `LOG` (what
//! the kernel tells unasked, [`LogEvent`]) and `FATAL` (the end of a run,
//! [`Fatal`]). They are sentences for people, and the host reads each
//! back all the same: the kernel writes them with `Display`, the harness
//! parses them, and a text `Display` would not write is refused.

mod error;
mod fatal;
mod log;

pub use error::ErrorReply;
pub use fatal::{Fatal, PageFaultCode, DOUBLE_FAULT_VECTOR, EXCEPTION_NAMES, PAGE_FAULT_VECTOR};
pub use log::{EndedAt, LogEvent, MachineEvidence};
