//! Every fill method, one module each, named after its source, each named
//! by a [`MethodId`]; the interface they share is in `interface.rs`.

use crate::geometry::Polygon;
use crate::method::Refusal;
use crate::sink::SpanSink;

pub mod abrash_aet;
pub mod abrash_float;
pub mod abrash_int;
pub mod exact;
mod interface;
pub mod lamothe;
pub mod pendleton;
#[cfg(test)]
pub(crate) mod test_support;
pub mod wgt;

pub(crate) use interface::Builtin;
pub use interface::{Method, MethodId, UnknownMethod};

impl MethodId {
    /// The method itself.
    pub const fn method(self) -> &'static dyn Method {
        match self {
            MethodId::AbrashFloat => &abrash_float::AbrashFloat,
            MethodId::AbrashInt => &abrash_int::AbrashInt,
            MethodId::AbrashAet => &abrash_aet::AbrashAet,
            MethodId::Pendleton => &pendleton::Pendleton,
            MethodId::Lamothe => &lamothe::Lamothe,
            MethodId::LamotheFixed => &lamothe::LamotheFixed,
            MethodId::Wgt => &wgt::Wgt,
            MethodId::Exact => &exact::Exact,
        }
    }

    /// Fills `polygon` into `sink` with this method, statically dispatched:
    /// each method's loops are compiled for the sink's type, with its store
    /// inlined, so a span costs no call. The same pixels as
    /// `self.method().fill(polygon, sink)`.
    pub fn fill<S: SpanSink + ?Sized>(self, polygon: &Polygon, sink: &mut S) -> Result<(), Refusal> {
        match self {
            MethodId::AbrashFloat => abrash_float::AbrashFloat.fill_into(polygon, sink),
            MethodId::AbrashInt => abrash_int::AbrashInt.fill_into(polygon, sink),
            MethodId::AbrashAet => abrash_aet::AbrashAet.fill_into(polygon, sink),
            MethodId::Pendleton => pendleton::Pendleton.fill_into(polygon, sink),
            MethodId::Lamothe => lamothe::Lamothe.fill_into(polygon, sink),
            MethodId::LamotheFixed => lamothe::LamotheFixed.fill_into(polygon, sink),
            MethodId::Wgt => wgt::Wgt.fill_into(polygon, sink),
            MethodId::Exact => exact::Exact.fill_into(polygon, sink),
        }
    }

    /// Its name on the command line, in the protocol and in scene files.
    pub fn name(self) -> &'static str {
        self.method().info().name
    }
}

/// All methods, in [`MethodId::ALL`]'s order.
pub static ALL: &[&dyn Method] = &{
    let mut all: [&dyn Method; MethodId::ALL.len()] = [&exact::Exact; MethodId::ALL.len()];
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
