//! The embedded-graphics adapter (`raster-eg`) over the lab's quick
//! corpus, on a 320x200 `DrawTarget` that refuses a pixel drawn twice:
//! every polygon, in its 1/256-px vertices, with a `FixedScratch` for the
//! ones of more edges than the stack's tables hold, draws exactly the
//! pixels of raster's reference, each once.

use embedded_graphics::pixelcolor::Gray8;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::Rectangle;
use lab::corpus::{self, Budget};
use raster::reference::{self, SampleOffset};
use raster::{CoverageSink, SCREEN};
use raster_eg::{FilledPolygon, FixedScratch};

/// A 320x200 target that counts what is drawn on each pixel and refuses a
/// pixel drawn twice (or outside it), naming it.
struct Once {
    drawn: Vec<u32>,
}

#[derive(Debug, PartialEq)]
enum Refused {
    Twice(Point),
    Outside(Point),
}

impl Dimensions for Once {
    fn bounding_box(&self) -> Rectangle {
        Rectangle::new(Point::zero(), Size::new(SCREEN.width as u32, SCREEN.height as u32))
    }
}

impl DrawTarget for Once {
    type Color = Gray8;
    type Error = Refused;

    fn draw_iter<I: IntoIterator<Item = Pixel<Gray8>>>(&mut self, pixels: I) -> Result<(), Refused> {
        for Pixel(p, _) in pixels {
            if !self.bounding_box().contains(p) {
                return Err(Refused::Outside(p));
            }
            let count = &mut self.drawn[(p.y * SCREEN.width + p.x) as usize];
            *count += 1;
            if *count > 1 {
                return Err(Refused::Twice(p));
            }
        }
        Ok(())
    }
}

/// The most edges of any polygon of the quick corpus is below this.
const EDGES: usize = 1 << 14;

fn check_the_corpus() {
    let mut scratch = Box::new(FixedScratch::<EDGES>::new());
    let (mut polygons, mut pixels, mut wrong) = (0, 0, 0);
    for family in corpus::build(Budget::QUICK).unwrap() {
        for polygon in &family.polygons {
            assert!(polygon.vertex_count() <= EDGES, "{}: {} edges", family.name, polygon.vertex_count());
            let contours: Vec<&[raster::Point]> = polygon.contours.iter().map(Vec::as_slice).collect();
            let shape = FilledPolygon::subpixels(&contours, polygon.rule);
            let mut target = Once { drawn: vec![0; (SCREEN.width * SCREEN.height) as usize] };
            let filled = shape.fill_with(Gray8::new(polygon.color), &mut target, &mut *scratch);
            assert_eq!(filled, Ok(Ok(())), "{}: {polygon:?}", family.name);
            let mut judge = CoverageSink::new(SCREEN);
            reference::fill(polygon, SampleOffset::CENTRE, &mut judge);
            for y in 0..SCREEN.height {
                for x in 0..SCREEN.width {
                    let ours = target.drawn[(y * SCREEN.width + x) as usize];
                    wrong += usize::from(ours != judge.count(x, y).min(1));
                    pixels += ours as usize;
                }
            }
            polygons += 1;
        }
    }
    println!("raster-eg over the quick corpus: {polygons} polygons, {pixels} pixels drawn, {wrong} wrong, 0 twice");
    assert_eq!(wrong, 0);
}

#[test]
fn the_quick_corpus_draws_the_references_pixels_each_once() {
    // The scratch's tables are built on the stack before they are boxed.
    let run = std::thread::Builder::new().stack_size(256 << 20).spawn(check_the_corpus).unwrap();
    run.join().unwrap();
}
