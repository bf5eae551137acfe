//! The peers: the fills most Rust users would reach for, run on the same
//! polygons as our methods and judged by the same reference, each in a
//! file of its own behind one trait, [`Peer`], and listed once, in
//! [`ALL`]:
//!
//! - tiny-skia (`tiny_skia.rs`), Cairo (`cairo.rs`) and vello_cpu
//!   (`vello_cpu.rs`), aliased, given our subpixel vertices as floats, each
//!   twice: with its paths built before the clock starts (Cairo's kept
//!   with `copy_path` and appended for each fill) and for every fill;
//! - embedded-graphics (`embedded_graphics.rs`), a triangle of whole-pixel
//!   vertices, for triangle families only;
//! - and the aliased fillers people reach for to fill a byte buffer, each
//!   called as its users call it, each taking one contour of whole-pixel
//!   vertices (ours rounded, halves up) and filling by even-odd; what one
//!   cannot take is declined before it is called: Allegro 4.4's
//!   `polygon()` (`allegro.rs`), SDL2_gfx's `filledPolygonRGBA`
//!   (`sdl_gfx.rs`), GD's `gdImageFilledPolygon` (`gd.rs`) and
//!   imageproc's `draw_polygon_mut` (`imageproc.rs`). Each samples
//!   whole-pixel points and includes both ends of every span, so its own
//!   convention is the closed polygon at whole-pixel points
//!   ([`Own::Closed`]); Allegro and imageproc draw the outline too. These
//!   four are driven alike (`integer.rs`): each file gives its library's
//!   target as an `integer::IntegerTarget`, and an `integer::IntegerPeer` over it
//!   is the peer.
//!
//! Each file's own notes say how its peer is called and what it computes
//! in. A peer's picture is read back as spans by `rows.rs`.
//!
//! Adding a peer: a file with a value implementing [`Peer`] (`peer.rs`: a
//! unit struct, or an `IntegerPeer` over an `IntegerTarget` for a library taking
//! whole-pixel contours), its `mod` line here and its place in [`ALL`].
//! Its [`PeerInfo`] says what it does inside the clock ([`Clock`]): a row
//! of the table in docs/lab.md, which a test holds to these.

mod allegro;
mod cairo;
mod embedded_graphics;
mod gd;
mod imageproc;
mod integer;
mod peer;
mod rows;
mod sdl_gfx;
#[cfg(test)]
mod test_support;
mod tiny_skia;
mod vello_cpu;

pub use peer::{Clock, Peer};
// The peers' own descriptions, which the tests of measure.rs make up.
#[cfg(test)]
pub(crate) use peer::PeerInfo;

/// Every peer, in the order the results and the charts list them. Where a
/// peer's API lets a program build its path once, it is here twice: with
/// the paths built before the clock starts and for every fill inside it.
pub static ALL: [&dyn Peer; 11] = [
    &tiny_skia::TINY_SKIA,
    &tiny_skia::TINY_SKIA_PATH_EACH_FILL,
    &cairo::CAIRO,
    &cairo::CAIRO_PATH_KEPT,
    &embedded_graphics::EmbeddedGraphics,
    &vello_cpu::VELLO_CPU,
    &vello_cpu::VELLO_CPU_PATH_EACH_FILL,
    &allegro::ALLEGRO,
    &sdl_gfx::SDL_GFX,
    &gd::GD,
    &imageproc::IMAGEPROC,
];

#[cfg(test)]
mod tests {
    use raster::{CoverageSink, FillRule, Polygon, SCREEN};

    use super::test_support::{family, square, Spans};
    use super::*;
    use crate::convention::Own;

    const INTEGER_PEERS: [&dyn Peer; 4] = [&allegro::ALLEGRO, &sdl_gfx::SDL_GFX, &gd::GD, &imageproc::IMAGEPROC];

    /// The triangle (10,10) (100,20) (50,90), area 3,400 px, drawn by
    /// Allegro, SDL2_gfx and GD in C by hand: 3,571, 3,493 and 3,461
    /// pixels. imageproc draws 3,541. The closed triangle at whole-pixel
    /// points holds 3,431 (`closed.rs`, Pick's theorem), 3,501 with its
    /// outline: each peer draws all of its own convention's pixels and
    /// some more, none twice.
    #[test]
    fn the_integer_peers_draw_the_hand_counted_triangle() {
        let triangle = Polygon::from_pixels(&[(10, 10), (100, 20), (50, 90)], (0, 0), 1);
        let mut counts = vec![];
        for peer in INTEGER_PEERS {
            let mut drawn = CoverageSink::new(SCREEN);
            peer.draw(&triangle, &mut drawn).unwrap();
            let Own::Closed { outline } = peer.info().own else {
                panic!("{} judged by another convention", peer.info().name)
            };
            let mut own = CoverageSink::new(SCREEN);
            crate::closed_reference::fill(&triangle, outline, &mut own);
            let report = drawn.report(&own);
            assert_eq!((report.gaps, report.overdrawn, report.out_of_bounds), (0, 0, 0), "{}", peer.info().name);
            counts.push(own.ascii().matches('#').count() + report.extras);
        }
        assert_eq!(counts, [3571, 3493, 3461, 3541]);
    }

    #[test]
    fn the_integer_peers_decline_what_they_cannot_take() {
        let mut holed = square(0, 0, 60);
        holed.contours.push(square(20, 20, 10).contours.remove(0));
        let mut star = Polygon::from_pixels(&[(50, 0), (80, 90), (5, 35), (95, 35), (20, 90)], (0, 0), 1);
        star.rule = FillRule::NonZero;
        for peer in INTEGER_PEERS {
            for polygon in [&holed, &star] {
                assert!(peer.draw(polygon, &mut Spans(vec![])).is_err(), "{}", peer.info().name);
            }
        }
        // Each C library's reach, and one pixel past it.
        let reaches: [(&dyn Peer, _); 3] =
            [(&allegro::ALLEGRO, allegro::REACH), (&sdl_gfx::SDL_GFX, sdl_gfx::REACH), (&gd::GD, gd::REACH)];
        for (peer, reach) in reaches {
            let at = |x| Polygon::from_pixels(&[(x, 0), (0, 10), (10, 10)], (0, 0), 1);
            assert!(peer.draw(&at(-reach.pixels), &mut Spans(vec![])).is_ok(), "{}", peer.info().name);
            assert_eq!(peer.draw(&at(-reach.pixels - 1), &mut Spans(vec![])), Err(reach.beyond));
        }
        assert!(imageproc::IMAGEPROC.draw(&square(-5_000_000, 0, 9_000_000), &mut Spans(vec![])).is_ok());
        assert!(sdl_gfx::SDL_GFX
            .draw(&Polygon::from_pixels(&[(0, 0), (9, 9)], (0, 0), 1), &mut Spans(vec![]))
            .is_err());
    }

    #[test]
    fn the_integer_peers_take_a_family_they_take_any_of() {
        let far = square(5000, 0, 10);
        assert!(allegro::ALLEGRO.takes(&family(vec![far.clone(), square(0, 0, 10)])));
        assert!(!allegro::ALLEGRO.takes(&family(vec![far.clone()])));
        assert!(gd::GD.takes(&family(vec![far])));
    }
}
