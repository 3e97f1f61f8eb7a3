//! Primary rays in packets: a tile's pixels, for a kernel whose pixels
//! are one ray each ([`Kernel::one_ray`]), traced 32 at a time, an 8x4
//! block per packet ([`Scene::trace_packet`]); the lanes a packet leaves
//! walk alone, and every hit goes to the kernel's [`Kernel::shade`], so
//! each pixel is the one [`Kernel::pixel`] gives.

use crate::render::camera::{Camera, BLOCK_HEIGHT, BLOCK_WIDTH};
use crate::render::shader::Kernel;
use crate::render::stats::{RayStats, Rect};
use crate::scene::{Reach, Scene, WalkMemory, PACKET};

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
/// offsets inside `rect`) for a [`Kernel::one_ray`] kernel: its whole 8x4
/// blocks traced as packets (or, clear forever, all misses), the lanes a
/// packet leaves and the pixels of partial blocks one ray at a time, each
/// shaded by the kernel, handed to `put(dx, dy, rgba)` at their offsets
/// inside `rect`.
#[allow(clippy::too_many_arguments)]
pub(super) fn in_packets<'s, K: Kernel, S: Scene + ?Sized>(
    kernel: &K,
    scene: &'s S,
    camera: &Camera,
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
            if (width, height) != (BLOCK_WIDTH, BLOCK_HEIGHT) {
                // A partial block: the kernel's own pixels.
                for dy in by..by + height {
                    for dx in bx..bx + width {
                        let (x, y) = (rect.x.wrapping_add(dx), rect.y.wrapping_add(dy));
                        let (rgba, rays) = kernel.pixel(scene, x, y, t_start, memory);
                        put(dx, dy, rgba);
                        *stats += rays;
                    }
                }
                continue;
            }
            let (x, y) = (rect.x.wrapping_add(bx), rect.y.wrapping_add(by));
            let rays = camera.block_rays(x, y);
            let mut hits = [None; PACKET];
            // Clear forever: every ray misses (the promise of `t_start`).
            // Clear for no distance: the camera touches a solid voxel,
            // where a packet's lanes would mostly go back undecided; they
            // walk alone.
            let answered = if t_start == f32::INFINITY {
                u32::MAX
            } else if t_start == 0.0 {
                0
            } else {
                scene.trace_packet(&rays, u32::MAX, Reach::after(t_start), &mut hits)
            };
            // The lanes the packet left, lowest first.
            let mut alone = !answered;
            while alone != 0 {
                let i = alone.trailing_zeros() as usize;
                alone &= alone - 1;
                hits[i] = scene
                    .trace_with(&rays[i], Reach::after(t_start), memory, None)
                    .hit;
            }
            let lane = |i: usize| (i as u32 % BLOCK_WIDTH, i as u32 / BLOCK_WIDTH);
            let at = |i| {
                let (dx, dy) = lane(i);
                (x.wrapping_add(dx), y.wrapping_add(dy))
            };
            kernel.shade_packet(scene, (&rays, &hits), at, memory, |i, rgba, rays| {
                let (dx, dy) = lane(i);
                put(bx + dx, by + dy, rgba);
                *stats += rays;
            });
        }
    }
}
