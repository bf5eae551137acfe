//! Every fill method, one file or folder each, named after its source,
//! each named by a [`MethodId`] (`method_id.rs`: the list of them all,
//! and from an id the method, its fill and its name). What they share
//! lives beside them: the interface, [`Method`], in `interface.rs`; what a
//! method says of itself ([`MethodInfo`]) and why it declines a polygon
//! ([`Refusal`]) in `info.rs`.
//!
//! Without the `alloc` feature only `exact`'s fill is here, and
//! [`Refusal`], not the [`Method`] interface or the classic methods.
//!
//! [`Method`]: crate::Method
//! [`MethodId`]: crate::MethodId
//! [`MethodInfo`]: crate::MethodInfo
//! [`Refusal`]: crate::Refusal

#[cfg(feature = "alloc")]
mod abrash_aet;
#[cfg(feature = "alloc")]
mod abrash_float;
#[cfg(feature = "alloc")]
mod abrash_int;
pub(crate) mod exact;
pub(crate) mod info;
#[cfg(feature = "alloc")]
pub(crate) mod interface;
#[cfg(feature = "alloc")]
mod lamothe;
#[cfg(feature = "alloc")]
pub(crate) mod method_id;
#[cfg(feature = "alloc")]
mod pendleton;
#[cfg(test)]
pub(crate) mod test_support;
#[cfg(feature = "alloc")]
mod wgt;

#[cfg(feature = "alloc")]
pub use abrash_aet::AbrashAet;
#[cfg(feature = "alloc")]
pub use abrash_float::AbrashFloat;
#[cfg(feature = "alloc")]
pub use abrash_int::AbrashInt;
#[cfg(feature = "alloc")]
pub use exact::Exact;
#[cfg(feature = "alloc")]
pub use lamothe::{Lamothe, LamotheFixed};
#[cfg(feature = "alloc")]
pub use pendleton::Pendleton;
#[cfg(feature = "alloc")]
pub use wgt::Wgt;
