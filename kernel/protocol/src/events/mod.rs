//! Kernel to host, the frames that are not a command's answer with
//! fields: `ERR` (why a line was not run, [`ErrorReply`]), `LOG` (what
//! the kernel tells unasked, [`LogEvent`]) and `FATAL` (the end of a run,
//! [`FatalReport`]). They are sentences for people, and the host reads each
//! back all the same: the kernel writes them with `Display`, the harness
//! parses them, and a text `Display` would not write is refused.

mod error_reply;
mod fatal_report;
mod log_event;

pub use error_reply::ErrorReply;
pub use fatal_report::{FatalReport, PageFaultCode, DOUBLE_FAULT_VECTOR, EXCEPTION_NAMES, PAGE_FAULT_VECTOR};
pub use log_event::{EndedAt, HpetRefusal, IoApicRefusal, LogEvent, MachineEvidence, MaskedAt};
