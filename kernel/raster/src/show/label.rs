//! PLACEHOLDER (helper 2 replaces this file).
use super::Entry;
use crate::sink::Framebuffer;

pub(super) fn draw_labels(_target: &mut Framebuffer, _entry: &Entry, _frame: u32, _method: &str, _cycles: u64) {}
