//! Every fill method, one file or folder each, named after its source,
//! each named by a [`MethodId`]: this module is where a caller finds them
//! ([`ALL`], and each by its type). What they share lives beside them:
//! the interface, [`Method`], and the typed names in `interface.rs`; what
//! a method says of itself ([`MethodInfo`]) and why it declines a polygon
//! ([`Refusal`]) in `info.rs`.
//!
//! [`Method`]: crate::Method
//! [`MethodInfo`]: crate::MethodInfo
//! [`Refusal`]: crate::Refusal

mod abrash_aet;
mod abrash_float;
mod abrash_int;
pub(crate) mod exact;
pub(crate) mod info;
pub(crate) mod interface;
mod lamothe;
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

use crate::geometry::Polygon;
use crate::methods::info::Refusal;
use crate::methods::interface::{Builtin, Method, MethodId};
use crate::target::SpanSink;

impl MethodId {
    /// The method itself.
    pub const fn method(self) -> &'static dyn Method {
        match self {
            MethodId::AbrashFloat => &AbrashFloat,
            MethodId::AbrashInt => &AbrashInt,
            MethodId::AbrashAet => &AbrashAet,
            MethodId::Pendleton => &Pendleton,
            MethodId::Lamothe => &Lamothe,
            MethodId::LamotheFixed => &LamotheFixed,
            MethodId::Wgt => &Wgt,
            MethodId::Exact => &Exact,
        }
    }

    /// Fills `polygon` into `sink` with this method, statically dispatched:
    /// each method's loops are compiled for the sink's type, with its store
    /// inlined, so a span costs no call. The same pixels as
    /// `self.method().fill(polygon, sink)`.
    pub fn fill<S: SpanSink + ?Sized>(self, polygon: &Polygon, sink: &mut S) -> Result<(), Refusal> {
        match self {
            MethodId::AbrashFloat => AbrashFloat.fill_into(polygon, sink),
            MethodId::AbrashInt => AbrashInt.fill_into(polygon, sink),
            MethodId::AbrashAet => AbrashAet.fill_into(polygon, sink),
            MethodId::Pendleton => Pendleton.fill_into(polygon, sink),
            MethodId::Lamothe => Lamothe.fill_into(polygon, sink),
            MethodId::LamotheFixed => LamotheFixed.fill_into(polygon, sink),
            MethodId::Wgt => Wgt.fill_into(polygon, sink),
            MethodId::Exact => Exact.fill_into(polygon, sink),
        }
    }

    /// Its name on the command line, in the protocol and in scene files.
    pub fn name(self) -> &'static str {
        self.method().info().name
    }
}

/// All methods, in [`MethodId::ALL`]'s order.
pub static ALL: &[&dyn Method] = &{
    let mut all: [&dyn Method; MethodId::ALL.len()] = [&Exact; MethodId::ALL.len()];
    let mut i = 0;
    while i < all.len() {
        all[i] = MethodId::ALL[i].method();
        i += 1;
    }
    all
};

#[cfg(test)]
mod tests {
    use super::*;
    use crate::methods::interface::UnknownMethod;

    #[test]
    fn every_name_parses_back_to_its_method() {
        for (id, method) in MethodId::ALL.into_iter().zip(ALL) {
            assert_eq!(id.name(), method.info().name);
            assert_eq!(id.name().parse(), Ok(id));
        }
    }

    #[test]
    fn an_unknown_name_is_an_error_listing_every_method() {
        assert_eq!("exakt".parse::<MethodId>(), Err(UnknownMethod));
        assert_eq!(
            alloc::format!("{UnknownMethod}"),
            "unknown method; the methods are abrash_float, abrash_int, abrash_aet, pendleton, lamothe, \
             lamothe_fixed, wgt, exact"
        );
    }
}
