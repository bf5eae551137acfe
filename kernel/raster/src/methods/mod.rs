//! Every fill method, one module each, named after its source.

use crate::method::Method;

pub mod abrash_aet;
pub mod abrash_float;
pub mod abrash_int;
pub mod exact;
pub mod lamothe;
pub mod pendleton;
#[cfg(test)]
pub(crate) mod test_support;
pub mod wgt;

/// All methods, in the order the demo, the protocol and the lab list them.
pub static ALL: &[&dyn Method] = &[
    &abrash_float::AbrashFloat,
    &abrash_int::AbrashInt,
    &abrash_aet::AbrashAet,
    &pendleton::Pendleton,
    &lamothe::Lamothe,
    &lamothe::LamotheFixed,
    &wgt::Wgt,
    &exact::Exact,
];

/// The method called `name`.
pub fn by_name(name: &str) -> Option<&'static dyn Method> {
    ALL.iter().copied().find(|m| m.info().name == name)
}
