//! The one interface over every fill method, [`Method`], and [`Builtin`],
//! which this crate's methods implement so that each can be compiled for
//! its sink. Their typed names, [`MethodId`](crate::MethodId), are in
//! `method_id.rs`.

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
/// [`MethodId`](crate::MethodId) fills through
/// [`MethodId::fill`](crate::MethodId::fill) instead, where the sink's
/// store is compiled into the method's loops; a `MethodId` becomes a
/// `&dyn Method` ([`MethodId::method`](crate::MethodId::method)) and never
/// the other way.
///
/// # Examples
///
/// Every method through the one interface, with what each declines:
///
/// ```
/// use raster::{CoverageSink, MethodId, Polygon, Refusal, Size};
///
/// let mut two = Polygon::from_pixels(&[(0, 0), (4, 0), (0, 4)], (0, 0), 1);
/// two.contours.push(Polygon::from_pixels(&[(6, 6), (9, 6), (6, 9)], (0, 0), 1).contours.remove(0));
/// for method in MethodId::ALL.map(MethodId::method) {
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
}

/// A method of this crate: its fill is generic over the sink, so that
/// called through [`MethodId::fill`](crate::MethodId::fill) on a sink of a known type it compiles
/// with that sink's store inlined, and on `&mut dyn SpanSink` (what
/// [`Method::fill`] passes) it is the same code, calling through the
/// vtable. Implementing it implements [`Method`].
pub(crate) trait Builtin: Sync {
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
}
