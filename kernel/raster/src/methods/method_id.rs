//! [`MethodId`], the typed name of each of this crate's methods, and all
//! it answers: the list of every method ([`MethodId::ALL`]), the method
//! itself ([`MethodId::method`]), a fill compiled for the sink
//! ([`MethodId::fill`]), and its name, parsed ([`FromStr`]) and written
//! ([`Display`](fmt::Display)).

use core::fmt;
use core::str::FromStr;

use super::{AbrashAet, AbrashFloat, AbrashInt, Exact, Lamothe, LamotheFixed, Pendleton, Wgt};
use crate::geometry::Polygon;
use crate::methods::info::Refusal;
use crate::methods::interface::{Builtin, Method};
use crate::target::SpanSink;

/// Names one method of this crate: the typed value a method name becomes
/// once it is parsed, at the edge (command line, serial line, scene file).
///
/// # Examples
///
/// Choosing a method by name, and what it says of itself:
///
/// ```
/// use raster::{Class, Framebuffer, MethodId, Polygon, SCREEN};
///
/// let method: MethodId = "abrash_int".parse().expect("a method's name");
/// let info = method.method().info();
/// assert_eq!((info.name, info.handles), ("abrash_int", Class::Convex));
/// let triangle = Polygon::from_pixels(&[(10, 10), (60, 20), (20, 50)], (0, 0), 4);
/// let mut screen = Framebuffer::new(SCREEN);
/// method.fill(&triangle, &mut screen).unwrap();
/// assert_eq!(screen.get(20, 20), Some(4));
///
/// let unknown = "bresenham".parse::<MethodId>().unwrap_err();
/// assert!(unknown.to_string().starts_with("unknown method; the methods are abrash_float, "));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum MethodId {
    AbrashFloat,
    AbrashInt,
    AbrashAet,
    Pendleton,
    Lamothe,
    LamotheFixed,
    Wgt,
    Exact,
}

impl MethodId {
    /// Every method, in the order the demo, the protocol and the lab list
    /// them (the digit keys of the demo count in this order from 1).
    pub const ALL: [MethodId; 8] = [
        MethodId::AbrashFloat,
        MethodId::AbrashInt,
        MethodId::AbrashAet,
        MethodId::Pendleton,
        MethodId::Lamothe,
        MethodId::LamotheFixed,
        MethodId::Wgt,
        MethodId::Exact,
    ];

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

impl fmt::Display for MethodId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for MethodId {
    type Err = UnknownMethod;

    fn from_str(name: &str) -> Result<Self, UnknownMethod> {
        MethodId::ALL.into_iter().find(|id| id.name() == name).ok_or(UnknownMethod)
    }
}

/// A name that is not a method's. Its message lists the names that are.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct UnknownMethod;

impl fmt::Display for UnknownMethod {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("unknown method; the methods are")?;
        for (i, id) in MethodId::ALL.iter().enumerate() {
            f.write_str(if i == 0 { " " } else { ", " })?;
            f.write_str(id.name())?;
        }
        Ok(())
    }
}

impl core::error::Error for UnknownMethod {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_name_parses_back_to_its_method() {
        for id in MethodId::ALL {
            assert_eq!(id.name(), id.method().info().name);
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
