//! Primary rays in tiles: the pixels of a rectangle, a square of
//! [`TILE`] x [`TILE`] at a time, each square's rays starting at the
//! distance its frustum of rays is known to be clear ([`Scene::clear_distance`]).
//!
//! The clear distance only moves where walks begin, never what they hit, so
//! any tiling (a crop, a band of rows on one thread, a single pixel) gives
//! the same pixels: the scalar, cropped and threaded renders stay
//! byte-identical.

use crate::render::camera::Camera;
use crate::render::shader::Kernel;
use crate::render::stats::{RayStats, Rect};
use crate::scene::Scene;
use crate::scene::WalkMemory;

/// Side of a tile in pixels: 256 rays share one walk of the tree's empty
/// space. Measured at 1920x1080 on the size-250 terrain (with the first,
/// cone-shaped beam): 8 gave starts a little closer to the hits (3.8 moves
/// left per ray instead of 4.2) but cost five times as much beam time (190
/// ms against 36 ms on one thread); 32 left 4.7 moves.
pub(crate) const TILE: u32 = 16;

/// Renders every pixel of `rect` with `kernel`, tile by tile (row-major
/// tiles, row-major pixels inside a tile), handing `put(dx, dy, rgba)` each
/// pixel at its offset inside `rect`. Allocates nothing.
pub(crate) fn render_tiles<K: Kernel, S: Scene + ?Sized>(
    kernel: &K,
    scene: &S,
    camera: &Camera,
    rect: Rect,
    mut put: impl FnMut(u32, u32, u32),
) -> RayStats {
    let mut stats = RayStats::default();
    // One memory for the whole rectangle: a tile's first ray begins from
    // the last ray of the tile before, its neighbour.
    let mut memory = WalkMemory::new();
    // Offsets inside the rectangle, so that no sum passes u32::MAX for a
    // rectangle that reaches the last pixel of the largest frame.
    for dy0 in (0..rect.height).step_by(TILE as usize) {
        let dy1 = dy0 + TILE.min(rect.height - dy0);
        for dx0 in (0..rect.width).step_by(TILE as usize) {
            let dx1 = dx0 + TILE.min(rect.width - dx0);
            let (x0, y0) = (rect.x.wrapping_add(dx0), rect.y.wrapping_add(dy0));
            let (x1, y1) = (rect.x.wrapping_add(dx1), rect.y.wrapping_add(dy1));
            // (A tile past u32::MAX, outside every frame, wraps: no beam.)
            let beam = kernel.uses_beam() && x1 > x0 && y1 > y0;
            let frustum = beam.then(|| camera.tile_frustum(x0, y0, x1, y1)).flatten();
            let t_start = frustum.map_or(0.0, |f| scene.clear_distance(&f));
            for dy in dy0..dy1 {
                for dx in dx0..dx1 {
                    let (x, y) = (rect.x.wrapping_add(dx), rect.y.wrapping_add(dy));
                    let (rgba, rays) = kernel.pixel(scene, x, y, t_start, &mut memory);
                    put(dx, dy, rgba);
                    stats += rays;
                }
            }
        }
    }
    stats
}
