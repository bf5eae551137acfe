//! PLACEHOLDER (helper 1 replaces this file).
use alloc::vec::Vec;

use super::Scratch;
use crate::method::Method;
use crate::scene::DrawReport;
use crate::sink::Framebuffer;

pub(super) const GOURAUD_FRAMES: u32 = 120;
pub(super) const TEXTURE_FRAMES: u32 = 120;
pub(super) const DEPTH_FRAMES: u32 = 120;

pub(super) fn gouraud(_frame: u32, _method: &dyn Method, _scratch: &mut Scratch, _target: &mut Framebuffer) -> DrawReport {
    DrawReport::default()
}

pub(super) fn texture(_frame: u32, _method: &dyn Method, _scratch: &mut Scratch, _target: &mut Framebuffer) -> DrawReport {
    DrawReport::default()
}

pub(super) fn depth(
    _frame: u32,
    _method: &dyn Method,
    _scratch: &mut Scratch,
    _depth: &mut Vec<i32>,
    _target: &mut Framebuffer,
) -> DrawReport {
    DrawReport::default()
}
