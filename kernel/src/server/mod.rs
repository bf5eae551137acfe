//! The protocol server on COM1: the kernel's announcement at boot
//! ([`announce`]) and the loop that answers one command line with one
//! frame ([`serve`]), `BENCH`'s timings (`bench`) among its commands.
//!
//! Uses every other subsystem; none uses it.

mod bench;
mod commands;

pub use commands::{announce, serve};
