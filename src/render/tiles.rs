//! The one tile loop: the pixels of a rectangle, a tile at a time, each
//! tile's camera rays starting at the distance its frustum of rays is
//! known to be clear ([`Scene::clear_distance`]), handed to the kernel a
//! block at a time ([`Kernel::block`]): 8x4 blocks, whose camera rays go
//! in packets ([`Scene::trace_lanes`]), for a kernel that traces them
//! together where the tile's rays are coherent enough ([`packets_pay`]),
//! else lone pixels. One pass and every round of a render in rounds run
//! it, and so does every target.
//!
//! The clear distance only moves where walks begin, never what they hit,
//! and a block's pixels are the lone pixels', so any tiling (a crop, a
//! band of rows on one thread, a single pixel) gives the same pixels: the
//! scalar, cropped and threaded renders stay byte-identical.

use crate::render::camera::{Camera, BLOCK_HEIGHT, BLOCK_WIDTH};
use crate::render::rounds::PixelSamples;
use crate::render::shader::{Block, BlockSamples, Kernel};
use crate::render::stats::{RayStats, Rect};
use crate::scene::{Scene, WalkMemory, PACKET};

/// Side of a tile in pixels: 256 rays share one walk of the tree's empty
/// space (the measurements behind it are in benches/README.md).
pub(crate) const TILE: u32 = 16;

/// Width of a tile whose rays go in packets (its height stays [`TILE`]):
/// a packet's own walk shares the empty space among its rays, and the
/// beam pays for itself over wider tiles (benches/README.md).
#[cfg(feature = "packets")]
const PACKET_TILE: u32 = 64;

/// The widest a packet of rays may be, in voxels, where its walk begins:
/// beyond, rays that diverge go alone (benches/README.md).
#[cfg(feature = "packets")]
const MAX_SPREAD: f32 = 16.0;

/// A round of a render in rounds: the round to take every pixel to, and
/// the pixels' samples so far (row-major, stride the rectangle's width).
pub(crate) struct Round<'a> {
    pub(crate) n: u32,
    pub(crate) samples: &'a mut [PixelSamples],
}

/// Renders every pixel of `rect` with `kernel`, tile by tile (row-major
/// tiles; inside a tile, row-major blocks or pixels), handing `put(dx,
/// dy, rgba)` each pixel made at its offset inside `rect`: in one pass
/// (`round` `None`), or to the end of a round, where a tile whose pixels
/// are all done is skipped whole. Returns the rays traced and whether a
/// pixel is left that is not done. Allocates nothing.
pub(crate) fn render_tiles<K: Kernel, S: Scene + ?Sized>(
    kernel: &K,
    scene: &S,
    camera: &Camera,
    rect: Rect,
    round: Option<Round<'_>>,
    put: impl FnMut(u32, u32, u32),
) -> (RayStats, bool) {
    let mut blocks = Blocks {
        kernel,
        scene,
        rect,
        // One memory for the whole rectangle: a tile's first ray begins
        // from the last ray of the tile before, its neighbour.
        memory: WalkMemory::new(),
        round,
        put,
        stats: RayStats::default(),
    };
    let mut left = false;
    let width = tile_width(kernel);
    // Offsets inside the rectangle, so that no sum passes u32::MAX for a
    // rectangle that reaches the last pixel of the largest frame.
    for dy0 in (0..rect.height).step_by(TILE as usize) {
        let dy1 = dy0 + TILE.min(rect.height - dy0);
        for dx0 in (0..rect.width).step_by(width as usize) {
            let dx1 = dx0 + width.min(rect.width - dx0);
            let tile = Rect {
                x: dx0,
                y: dy0,
                width: dx1 - dx0,
                height: dy1 - dy0,
            };
            if K::RESUMES && blocks.all_done(tile) == Some(true) {
                continue;
            }
            let (x0, y0) = (rect.x.wrapping_add(dx0), rect.y.wrapping_add(dy0));
            let (x1, y1) = (rect.x.wrapping_add(dx1), rect.y.wrapping_add(dy1));
            // (A tile past u32::MAX, outside every frame, wraps: no beam.)
            let beam = kernel.uses_beam() && x1 > x0 && y1 > y0;
            let frustum = beam.then(|| camera.tile_frustum(x0, y0, x1, y1)).flatten();
            let clear = frustum.map_or(0.0, |f| scene.clear_distance(&f));
            #[cfg(feature = "packets")]
            let in_blocks = kernel.in_blocks() && beam && packets_pay(camera, clear);
            #[cfg(not(feature = "packets"))]
            let in_blocks = false;
            if in_blocks {
                // 8x4 blocks, row-major; one the tile's edge cuts has the
                // mask of its lanes inside: `h` rows of `w` lanes each.
                for by in (dy0..dy1).step_by(BLOCK_HEIGHT as usize) {
                    let h = (dy1 - by).min(BLOCK_HEIGHT);
                    for bx in (dx0..dx1).step_by(BLOCK_WIDTH as usize) {
                        let row = u32::MAX >> (32 - (dx1 - bx).min(BLOCK_WIDTH));
                        let lanes = (0..h).fold(0, |lanes, dy| lanes | row << (dy * BLOCK_WIDTH));
                        blocks.make::<PACKET>((bx, by), lanes, clear);
                    }
                }
            } else {
                // Lone pixels, row-major: lane 0 alone.
                for dy in dy0..dy1 {
                    for dx in dx0..dx1 {
                        blocks.make::<1>((dx, dy), 1, clear);
                    }
                }
            }
            left |= K::RESUMES && blocks.all_done(tile) == Some(false);
        }
    }
    (blocks.stats, left)
}

/// What the blocks of a rectangle share: the kernel, the walk memory,
/// the round's pixel states, where pixels go and the rays counted.
struct Blocks<'a, 's, K, S: ?Sized, P> {
    kernel: &'a K,
    scene: &'s S,
    rect: Rect,
    memory: WalkMemory<'s>,
    round: Option<Round<'a>>,
    put: P,
    stats: RayStats,
}

impl<K: Kernel, S: Scene + ?Sized, P: FnMut(u32, u32, u32)> Blocks<'_, '_, K, S, P> {
    /// The pixels of the lanes `lanes` of the block whose corner is at
    /// offset `(bx, by)` in the rectangle, whose rays are clear until
    /// `clear`, in arrays of `N` lanes ([`Kernel::block`]).
    #[inline(always)]
    fn make<const N: usize>(&mut self, (bx, by): (u32, u32), lanes: u32, clear: f32) {
        let rect = self.rect;
        let corner = (rect.x.wrapping_add(bx), rect.y.wrapping_add(by));
        let block = Block {
            corner,
            lanes,
            clear,
        };
        let stride = rect.width as usize;
        let mut samples = self.round.as_mut().map(|r| BlockSamples {
            round: r.n,
            cells: &mut r.samples[by as usize * stride + bx as usize..],
            stride,
        });
        let put = &mut self.put;
        let (memory, samples) = (&mut self.memory, samples.as_mut());
        self.stats += self
            .kernel
            .block::<S, N>(self.scene, block, memory, samples, |i, rgba| {
                let (dx, dy) = lane_offset(i);
                put(bx + dx, by + dy, rgba);
            });
    }

    /// Whether every pixel of `tile` is done, in a round (`None` in one
    /// pass).
    fn all_done(&self, tile: Rect) -> Option<bool> {
        let samples = &self.round.as_ref()?.samples;
        let stride = self.rect.width as usize;
        let (dx0, dx1) = (tile.x as usize, (tile.x + tile.width) as usize);
        Some((tile.y..tile.y + tile.height).all(|dy| {
            let row = dy as usize * stride;
            samples[row + dx0..row + dx1]
                .iter()
                .all(PixelSamples::is_done)
        }))
    }
}

/// Lane `i`'s offset from its block's corner.
#[inline]
fn lane_offset(i: usize) -> (u32, u32) {
    (i as u32 % BLOCK_WIDTH, i as u32 / BLOCK_WIDTH)
}

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

/// Whether a tile's rays, clear until their clear distance `clear`, are coherent enough for
/// packets: an 8x4 block's rays are at most [`MAX_SPREAD`] voxels apart
/// there, or clear forever (a tile of sky: its rays are made in blocks,
/// and none is traced). Never for an orthographic camera, whose rays
/// share no origin.
#[cfg(feature = "packets")]
fn packets_pay(camera: &Camera, clear: f32) -> bool {
    let spread = clear * camera.pixel_spread() * BLOCK_WIDTH as f32;
    !camera.is_orthographic() && (spread <= MAX_SPREAD || clear == f32::INFINITY)
}
