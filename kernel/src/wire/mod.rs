//! The wire to the host: COM1, frames out and bytes in (`serial`), and
//! the command line those bytes make (`line`), for the show and the
//! server alike.
//!
//! Uses `platform` and `time` alone, so that the interrupt handlers below
//! can send their `LOG` and `FATAL` frames through it.

pub mod line;
pub mod serial;
