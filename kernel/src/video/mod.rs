//! The screen and what is behind it: the [`Screen`] the show and the
//! server draw on, its frame as the methods draw into it (`canvas`), and
//! the paths it is shown on: mode 13h by the kernel's own register writes
//! (`vga`), after undoing a UEFI firmware's mode on the cards it knows
//! (`card`), or the firmware's framebuffer (`presenter`).
//!
//! Uses `platform`, `time` and `wire`.

mod canvas;
mod card;
mod presenter;
mod screen;
mod vga;

pub use screen::{Drawn, Screen};
