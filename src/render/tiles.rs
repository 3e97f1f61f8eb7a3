//! Primary rays in tiles: the pixels of a rectangle, a square of
//! [`TILE`] x [`TILE`] at a time, each square's rays starting at the
//! distance its frustum of rays is known to be clear ([`Scene::clear_distance`]).
//! A kernel that makes its pixels 8x4 at a time (`Kernel::in_blocks`:
//! the flat and lit looks) has its tiles' rays traced 32 at a time, a
//! block per packet ([`Scene::trace_packet`], `render/packets.rs`), in
//! wider tiles.
//!
//! The clear distance only moves where walks begin, never what they hit, so
//! any tiling (a crop, a band of rows on one thread, a single pixel) gives
//! the same pixels: the scalar, cropped and threaded renders stay
//! byte-identical.

use crate::render::camera::Camera;
#[cfg(feature = "packets")]
use crate::render::packets::{in_packets, packets_pay, PACKET_TILE};
#[cfg(feature = "path")]
use crate::render::rounds::PixelSamples;
use crate::render::shader::Kernel;
#[cfg(feature = "path")]
use crate::render::shader::Resumable;
use crate::render::stats::{RayStats, Rect};
use crate::scene::{Scene, WalkMemory};

/// Side of a tile in pixels: 256 rays share one walk of the tree's empty
/// space. Measured at 1920x1080 on the size-250 terrain (with the first,
/// cone-shaped beam): 8 gave starts a little closer to the hits (3.8 moves
/// left per ray instead of 4.2) but cost five times as much beam time (190
/// ms against 36 ms on one thread); 32 left 4.7 moves.
pub(crate) const TILE: u32 = 16;

/// The width of the tiles of `kernel`'s pixels: [`TILE`], or wider for a
/// kernel whose rays go in packets.
fn tile_width(kernel: &impl Kernel) -> u32 {
    #[cfg(feature = "packets")]
    if kernel.in_blocks() {
        return PACKET_TILE;
    }
    let _ = kernel;
    TILE
}

/// Renders every pixel of `rect` with `kernel`, tile by tile (row-major
/// tiles; inside a tile, row-major pixels or, for a kernel that makes
/// them 8x4 at a time, row-major blocks), handing `put(dx, dy, rgba)` each
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
        let width = tile_width(kernel);
        for dx0 in (0..rect.width).step_by(width as usize) {
            let dx1 = dx0 + width.min(rect.width - dx0);
            let (x0, y0) = (rect.x.wrapping_add(dx0), rect.y.wrapping_add(dy0));
            let (x1, y1) = (rect.x.wrapping_add(dx1), rect.y.wrapping_add(dy1));
            // (A tile past u32::MAX, outside every frame, wraps: no beam.)
            let beam = kernel.uses_beam() && x1 > x0 && y1 > y0;
            let frustum = beam.then(|| camera.tile_frustum(x0, y0, x1, y1)).flatten();
            let t_start = frustum.map_or(0.0, |f| scene.clear_distance(&f));
            let tile = Tile { dx0, dy0, dx1, dy1 };
            #[cfg(feature = "packets")]
            let offsets = Rect {
                x: dx0,
                y: dy0,
                width: dx1 - dx0,
                height: dy1 - dy0,
            };
            #[cfg(feature = "packets")]
            if kernel.in_blocks() && beam && packets_pay(camera, t_start) {
                let memory = &mut memory;
                in_packets(
                    kernel, scene, rect, offsets, t_start, memory, &mut put, &mut stats,
                );
                continue;
            }
            for (dx, dy) in tile.offsets() {
                let (x, y) = (rect.x.wrapping_add(dx), rect.y.wrapping_add(dy));
                let (rgba, rays) = kernel.pixel(scene, x, y, t_start, &mut memory);
                put(dx, dy, rgba);
                stats += rays;
            }
        }
    }
    stats
}

/// Continues every pixel of `rect` to the end of round `round` (from 1)
/// with `kernel` ([`Resumable::resume`]), in the tiles of [`render_tiles`]:
/// `pixels` holds each pixel's samples so far (row-major, stride
/// `rect.width`), and `put(dx, dy, rgba)` hears each pixel that took
/// samples. A tile whose pixels are all done is skipped whole. Returns
/// the rays traced and whether a pixel is left that is not done.
/// Allocates nothing.
#[cfg(feature = "path")]
pub(crate) fn resume_tiles<K: Resumable, S: Scene + ?Sized>(
    kernel: &K,
    scene: &S,
    camera: &Camera,
    rect: Rect,
    pixels: &mut [PixelSamples],
    round: u32,
    mut put: impl FnMut(u32, u32, u32),
) -> (RayStats, bool) {
    let mut stats = RayStats::default();
    let mut memory = WalkMemory::new();
    let mut left = false;
    let stride = rect.width as usize;
    let index = |dx: u32, dy: u32| dy as usize * stride + dx as usize;
    for tile in tiles_of(rect) {
        let all_done = tile
            .offsets()
            .all(|(dx, dy)| pixels.get(index(dx, dy)).is_none_or(|p| p.done));
        if all_done {
            continue;
        }
        let t_start = clear_distance(kernel, scene, camera, rect, tile);
        for (dx, dy) in tile.offsets() {
            let Some(pixel) = pixels.get_mut(index(dx, dy)) else {
                continue;
            };
            let (x, y) = (rect.x.wrapping_add(dx), rect.y.wrapping_add(dy));
            let (rgba, rays) = kernel.resume(scene, x, y, t_start, &mut memory, pixel, round);
            if let Some(rgba) = rgba {
                put(dx, dy, rgba);
            }
            left |= !pixel.done;
            stats += rays;
        }
    }
    (stats, left)
}

/// One tile: its pixels' offsets inside the rectangle, `dx0..dx1` by
/// `dy0..dy1`.
#[derive(Clone, Copy)]
struct Tile {
    dx0: u32,
    dy0: u32,
    dx1: u32,
    dy1: u32,
}

impl Tile {
    /// The tile's pixel offsets, row-major.
    fn offsets(self) -> impl Iterator<Item = (u32, u32)> {
        (self.dy0..self.dy1).flat_map(move |dy| (self.dx0..self.dx1).map(move |dx| (dx, dy)))
    }
}

/// The tiles of `rect`, row-major. Offsets inside the rectangle, so that
/// no sum passes u32::MAX for a rectangle that reaches the last pixel of
/// the largest frame.
#[cfg(feature = "path")]
fn tiles_of(rect: Rect) -> impl Iterator<Item = Tile> {
    (0..rect.height)
        .step_by(TILE as usize)
        .flat_map(move |dy0| {
            let dy1 = dy0 + TILE.min(rect.height - dy0);
            (0..rect.width).step_by(TILE as usize).map(move |dx0| Tile {
                dx0,
                dy0,
                dx1: dx0 + TILE.min(rect.width - dx0),
                dy1,
            })
        })
}

/// The distance before which no primary ray of `tile` (of `rect`) hits
/// anything, for a kernel that uses it; 0 otherwise.
#[cfg(feature = "path")]
fn clear_distance<K: Kernel, S: Scene + ?Sized>(
    kernel: &K,
    scene: &S,
    camera: &Camera,
    rect: Rect,
    tile: Tile,
) -> f32 {
    let (x0, y0) = (rect.x.wrapping_add(tile.dx0), rect.y.wrapping_add(tile.dy0));
    let (x1, y1) = (rect.x.wrapping_add(tile.dx1), rect.y.wrapping_add(tile.dy1));
    // (A tile past u32::MAX, outside every frame, wraps: no beam.)
    let beam = kernel.uses_beam() && x1 > x0 && y1 > y0;
    let frustum = beam.then(|| camera.tile_frustum(x0, y0, x1, y1)).flatten();
    frustum.map_or(0.0, |f| scene.clear_distance(&f))
}
