//! The show that runs when no host talks: the demo's loop through the
//! pages and animations (`demo`), the one way a frame of them reaches the
//! screen (`player`, which `SHOW` uses too), and the PS/2 keys the viewer
//! steers it with (`keyboard`).
//!
//! Uses `platform`, `time`, `wire`, `interrupts` and `video`.

pub mod demo;
mod keyboard;
pub mod player;
