//! Camera rays in packets: a tile's pixels, for a kernel that makes them
//! 8x4 at a time ([`Kernel::in_blocks`]), handed to the kernel a block at
//! a time ([`Kernel::block`]), which traces the block's camera rays as
//! packets ([`crate::Scene::trace_lanes`]); every pixel is the one
//! [`Kernel::pixel`] gives.

use crate::render::camera::{Camera, BLOCK_HEIGHT, BLOCK_WIDTH};
use crate::render::shader::Kernel;
use crate::render::stats::{RayStats, Rect};
use crate::scene::{Scene, WalkMemory};

/// Width of a tile whose rays go in packets (its height stays `TILE`,
/// the threaded renderer's band): a packet's own walk shares the empty
/// space among its rays, and the beam pays for itself over wider tiles.
/// Measured at 1920x1080, `--flat`, one thread, on an AMD EPYC VM, with
/// the first packets (16 rays, branches by the hull one child at a time):
/// 16 wide took 128 ms at size 250 (100 ms at 100), no beam at all 122
/// ms (96 ms), 64 wide 115 ms (86 ms), 128 and 256 the same as 64.
pub(super) const PACKET_TILE: u32 = 64;

/// The widest a packet of rays may be, in voxels, where its walk begins:
/// beyond, rays that diverge go alone. Measured at 1920x1080, `--flat`,
/// one thread, on an AMD EPYC VM: packets everywhere took 537 ms at size
/// 2048 against 481 ms with this bound (sizes 100 and 250 unchanged); 4
/// voxels made size 250 slower (126 ms against 98 ms).
const MAX_SPREAD: f32 = 16.0;

/// Whether a tile's rays, clear until `t_start`, are coherent enough for
/// packets: an 8x4 block's rays are at most [`MAX_SPREAD`] voxels apart
/// there, or clear forever (a tile of sky: its rays are made in blocks,
/// and none is traced).
/// Never for an orthographic camera, whose rays share no origin.
pub(super) fn packets_pay(camera: &Camera, t_start: f32) -> bool {
    let spread = t_start * camera.pixel_spread() * BLOCK_WIDTH as f32;
    !camera.is_orthographic() && (spread <= MAX_SPREAD || t_start == f32::INFINITY)
}

/// The pixels of `tile` (of `rect`; the tile's corner and size are
/// offsets inside `rect`) for a [`Kernel::in_blocks`] kernel, 8x4 at a
/// time by [`Kernel::block`] (a block the tile's edge cuts, by the mask
/// of its lanes inside), handed to `put(dx, dy, rgba)` at their offsets
/// inside `rect`.
#[allow(clippy::too_many_arguments)]
pub(super) fn in_packets<'s, K: Kernel, S: Scene + ?Sized>(
    kernel: &K,
    scene: &'s S,
    rect: Rect,
    tile: Rect,
    t_start: f32,
    memory: &mut WalkMemory<'s>,
    put: &mut impl FnMut(u32, u32, u32),
    stats: &mut RayStats,
) {
    // Offsets, which stay below the rectangle's size: no sum overflows.
    let (dx1, dy1) = (tile.x + tile.width, tile.y + tile.height);
    for by in (tile.y..dy1).step_by(BLOCK_HEIGHT as usize) {
        for bx in (tile.x..dx1).step_by(BLOCK_WIDTH as usize) {
            let (width, height) = ((dx1 - bx).min(BLOCK_WIDTH), (dy1 - by).min(BLOCK_HEIGHT));
            // `height` rows of `width` lanes each.
            let row = u32::MAX >> (32 - width);
            let lanes = (0..height).fold(0, |lanes, dy| lanes | row << (dy * BLOCK_WIDTH));
            let corner = (rect.x.wrapping_add(bx), rect.y.wrapping_add(by));
            kernel.block(scene, corner, lanes, t_start, memory, |i, rgba, rays| {
                let (dx, dy) = (i as u32 % BLOCK_WIDTH, i as u32 / BLOCK_WIDTH);
                put(bx + dx, by + dy, rgba);
                *stats += rays;
            });
        }
    }
}
