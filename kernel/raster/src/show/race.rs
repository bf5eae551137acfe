//! PLACEHOLDER (helper 2 replaces this file).
use super::Scratch;
use crate::method::Method;
use crate::methods;
use crate::scene::DrawReport;
use crate::sink::Framebuffer;

pub(super) const FRAMES: u32 = 8 * 30;

pub(super) fn method_at(frame: u32) -> &'static dyn Method {
    methods::ALL[(frame / 30) as usize % methods::ALL.len()]
}

pub(super) fn draw(_frame: u32, _method: &dyn Method, _scratch: &mut Scratch, _target: &mut Framebuffer) -> DrawReport {
    DrawReport::default()
}
