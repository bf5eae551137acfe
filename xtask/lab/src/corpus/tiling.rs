//! The tiling group: jittered meshes that cover the screen exactly once
//! under the exact rule, and what the stress group's rotated and moved
//! tilings share with them.

use rand::RngExt;
use rand_pcg::Pcg64Mcg;
use raster::{FillRule, Polygon};

use super::family::{rng_for, Family, Group};
use super::shapes::{color, polygon, HEIGHT, WIDTH};

/// A jittered grid of `columns` x `rows` cells of `cell` px from `origin`,
/// every inner point moved by at most a fifth of a cell (which keeps every
/// cell a convex quad), as points in pixels.
pub(super) fn jittered_grid(
    rng: &mut Pcg64Mcg,
    origin: (f64, f64),
    cell: f64,
    columns: usize,
    rows: usize,
) -> Vec<Vec<(f64, f64)>> {
    (0..=rows)
        .map(|j| {
            (0..=columns)
                .map(|i| {
                    let inner = i > 0 && j > 0 && i < columns && j < rows;
                    let jitter = if inner { cell / 5.0 } else { 0.0 };
                    let mut wiggle = || if inner { rng.random_range(-jitter..jitter) } else { 0.0 };
                    (origin.0 + i as f64 * cell + wiggle(), origin.1 + j as f64 * cell + wiggle())
                })
                .collect()
        })
        .collect()
}

/// The cells of a grid as quads, or split along a random diagonal into
/// triangles, all with one colour per tile.
pub(super) fn grid_tiles(
    rng: &mut Pcg64Mcg,
    grid: &[Vec<(f64, f64)>],
    quads: bool,
    map: impl Fn((f64, f64)) -> (f64, f64),
) -> Vec<Polygon> {
    let mut tiles = Vec::new();
    for j in 0..grid.len() - 1 {
        for i in 0..grid[j].len() - 1 {
            let [a, b, c, d] = [grid[j][i], grid[j][i + 1], grid[j + 1][i + 1], grid[j + 1][i]].map(&map);
            if quads {
                tiles.push(polygon(&[a, b, c, d], color(rng), FillRule::EvenOdd));
            } else if rng.random_bool(0.5) {
                tiles.push(polygon(&[a, b, c], color(rng), FillRule::EvenOdd));
                tiles.push(polygon(&[a, c, d], color(rng), FillRule::EvenOdd));
            } else {
                tiles.push(polygon(&[a, b, d], color(rng), FillRule::EvenOdd));
                tiles.push(polygon(&[b, c, d], color(rng), FillRule::EvenOdd));
            }
        }
    }
    tiles
}

pub(super) fn mesh_family(name: &'static str, description: &'static str, meshes: usize, quads: bool) -> Family {
    let mut rng = rng_for(name);
    let mut polygons = Vec::new();
    let mut tilings = Vec::new();
    for _ in 0..meshes {
        let cell = rng.random_range(12.0..40.0);
        // One cell of margin on every side, so the mesh covers the screen.
        let origin = (-cell + rng.random_range(0.0..1.0), -cell + rng.random_range(0.0..1.0));
        let (columns, rows) = ((WIDTH / cell).ceil() as usize + 2, (HEIGHT / cell).ceil() as usize + 2);
        let grid = jittered_grid(&mut rng, origin, cell, columns, rows);
        let start = polygons.len();
        polygons.extend(grid_tiles(&mut rng, &grid, quads, |p| p));
        tilings.push(start..polygons.len());
    }
    Family { name, group: Group::Tiling, description, polygons, tilings, sweep: None }
}

pub(super) fn push_tiling(family: &mut Family, tiles: Vec<Polygon>, value: f64) {
    let start = family.polygons.len();
    if let Some(sweep) = &mut family.sweep {
        sweep.values.extend(std::iter::repeat_n(value, tiles.len()));
    }
    family.polygons.extend(tiles);
    family.tilings.push(start..family.polygons.len());
}
