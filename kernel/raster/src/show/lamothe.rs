//! PLACEHOLDER (helper 2 replaces this file).
use super::Scratch;
use crate::method::Method;
use crate::scene::DrawReport;
use crate::sink::Framebuffer;

pub(super) const FRAMES: u32 = 120;

pub(super) fn draw(_frame: u32, _method: &dyn Method, _scratch: &mut Scratch, _target: &mut Framebuffer) -> DrawReport {
    DrawReport::default()
}
