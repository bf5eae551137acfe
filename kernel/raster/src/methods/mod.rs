//! Every fill method, one file or folder each, named after its source,
//! each named by a [`MethodId`] (`method_id.rs`: the list of them all,
//! and from an id the method, its fill and its name). What they share
//! lives beside them: the interface, [`Method`], in `interface.rs`; what a
//! method says of itself ([`MethodInfo`]) and why it declines a polygon
//! ([`Refusal`]) in `info.rs`.
//!
//! [`Method`]: crate::Method
//! [`MethodId`]: crate::MethodId
//! [`MethodInfo`]: crate::MethodInfo
//! [`Refusal`]: crate::Refusal

mod abrash_aet;
mod abrash_float;
mod abrash_int;
pub(crate) mod exact;
pub(crate) mod info;
pub(crate) mod interface;
mod lamothe;
pub(crate) mod method_id;
mod pendleton;
#[cfg(test)]
pub(crate) mod test_support;
mod wgt;

pub use abrash_aet::AbrashAet;
pub use abrash_float::AbrashFloat;
pub use abrash_int::AbrashInt;
pub use exact::Exact;
pub use lamothe::{Lamothe, LamotheFixed};
pub use pendleton::Pendleton;
pub use wgt::Wgt;
