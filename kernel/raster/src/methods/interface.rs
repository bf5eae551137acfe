//! The one interface over every fill method, [`Method`], the typed name of
//! this crate's methods, [`MethodId`], and [`Builtin`], which this crate's
//! methods implement so that each can be compiled for its sink. The table
//! from names to methods is in [`methods`](super), with the methods.

use core::fmt;
use core::str::FromStr;

use crate::geometry::Polygon;
use crate::methods::info::{MethodInfo, Refusal};
use crate::target::SpanSink;

/// A fill method. Implementations never panic, never loop without bound
/// (their work is bounded by the clipped area and the edge count) and
/// never emit a span outside the sink's [`Size`](crate::Size).
///
/// The trait is object safe, so methods can be listed and picked at run
/// time (`&dyn Method`); through it, every span is a call through the
/// sink's vtable. A caller that names one of this crate's methods by its
/// [`MethodId`] fills through [`MethodId::fill`] instead, where the sink's
/// store is compiled into the method's loops; a `MethodId` becomes a
/// `&dyn Method` ([`MethodId::method`]) and never the other way, except
/// through [`Method::id`] for a caller that holds methods of any kind.
///
/// # Examples
///
/// Every method through the one interface, with what each declines:
///
/// ```
/// use raster::{methods, CoverageSink, Polygon, Refusal, Size};
///
/// let mut two = Polygon::from_pixels(&[(0, 0), (4, 0), (0, 4)], (0, 0), 1);
/// two.contours.push(Polygon::from_pixels(&[(6, 6), (9, 6), (6, 9)], (0, 0), 1).contours.remove(0));
/// for method in methods::ALL {
///     let mut drawn = CoverageSink::new(Size { width: 10, height: 10 });
///     match method.fill(&two, &mut drawn) {
///         Ok(()) => assert_eq!(drawn.out_of_bounds(), 0),
///         Err(refusal) => assert_eq!(refusal, Refusal::MultipleContours, "{}", method.info().name),
///     }
/// }
/// ```
pub trait Method: Sync {
    fn info(&self) -> &'static MethodInfo;
    /// Fills `polygon` into `sink`, or declines it.
    fn fill(&self, polygon: &Polygon, sink: &mut dyn SpanSink) -> Result<(), Refusal>;
    /// Which of this crate's methods it is; `None` for any other (a test's
    /// stand-in).
    fn id(&self) -> Option<MethodId> {
        None
    }
}

/// A method of this crate: its fill is generic over the sink, so that
/// called through [`MethodId::fill`] on a sink of a known type it compiles
/// with that sink's store inlined, and on `&mut dyn SpanSink` (what
/// [`Method::fill`] passes) it is the same code, calling through the
/// vtable. Implementing it implements [`Method`].
pub(crate) trait Builtin: Sync {
    const ID: MethodId;
    const INFO: &'static MethodInfo;
    fn fill_into<S: SpanSink + ?Sized>(&self, polygon: &Polygon, sink: &mut S) -> Result<(), Refusal>;
}

impl<T: Builtin> Method for T {
    fn info(&self) -> &'static MethodInfo {
        T::INFO
    }

    fn fill(&self, polygon: &Polygon, sink: &mut dyn SpanSink) -> Result<(), Refusal> {
        self.fill_into(polygon, sink)
    }

    fn id(&self) -> Option<MethodId> {
        Some(T::ID)
    }
}

/// Names one method of [`ALL`](crate::methods::ALL): the typed value a method name becomes once
/// it is parsed, at the edge (command line, serial line, scene file).
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
