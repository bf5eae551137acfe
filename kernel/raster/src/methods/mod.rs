//! Every fill method, one module each, named after its source.

use crate::method::Method;

pub mod abrash_float;

/// All methods, in the order the demo, the protocol and the lab list them.
pub static ALL: &[&dyn Method] = &[&abrash_float::AbrashFloat];

/// The method called `name`.
pub fn by_name(name: &str) -> Option<&'static dyn Method> {
    ALL.iter().copied().find(|m| m.info().name == name)
}

/// The method the demo uses when none is named.
pub fn default_method() -> &'static dyn Method {
    ALL[0]
}
