//! The dense array's walk: the shared cell walk of `storage/walk/`,
//! entered as [`Walk::start`] enters, then stepped by a loop specialised
//! for one flat array.
//!
//! The loop keeps the walk's state in three-lane vectors, one lane per
//! axis: the next crossing time, the one after it, the plane after that
//! as an `f32` (an integer below 2^24, so adding 1 is exact and
//! `(plane - origin) * inv_dir` is the very crossing single steps compute),
//! and the steps left before the ray leaves the box it walks; the cell is a
//! flat index moved by a per-axis stride. The axis of each step is chosen
//! as `Walk::step` chooses it, the earliest crossing with ties to the
//! lowest axis, by compares and selects, without a branch. The ray leaves
//! the box by position on the axis it steps along, as single steps do; the
//! box is convex, so a walk never comes back into it.
//!
//! Tracing walks only the occupied box: outside it every cell is empty, and
//! `Walk::start` enters it at the crossing single steps enter it by (the
//! octree starts at its occupied box the same way); `entry.rs` finds that
//! entry by shortcuts where it can. The debug view's walk visits every
//! cell of the volume with `Walk::step`.

use glam::{BVec3A, IVec3, Vec3A, Vec3Swizzles};

use crate::geom::{Face, IAabb, Ray};
use crate::scene::{Hit, Traced};
use crate::storage::dense::entry::{whole_numbers, Entry};
use crate::storage::dense::DenseScene;
use crate::storage::walk::{Key, Walk};
use crate::voxel::Palette;

const MISS: Traced = Traced {
    hit: None,
    steps: 0,
};

/// The hit on `material` in `cell`, entered by `key` on a walk moving down
/// the axes of `down`.
#[inline]
fn hit(palette: &Palette, cell: IVec3, down: BVec3A, key: Key, material: u8) -> Option<Hit> {
    let (face, t) = if key.t == f32::NEG_INFINITY {
        (None, 0.0)
    } else {
        let a = usize::from(key.axis);
        (Some(Face::entered(a, !down.test(a))), key.t)
    };
    Hit::from_palette(palette, cell, face, t, material)
}

impl<B: AsRef<[u8]>> DenseScene<B> {
    /// The first solid cell along `ray` in the occupied box, giving up once
    /// the walk enters a cell farther than `t_max`: at that step when
    /// `LIMITED`, else only when it finds a solid cell (keys only grow
    /// along a walk, so that cell is beyond the limit too, and the walk
    /// ends by leaving the box anyway). Giving up at +inf too: a crossing
    /// never reached ends the walk.
    #[inline]
    pub(super) fn walk<const LIMITED: bool>(&self, ray: &Ray, t_max: f32) -> Traced {
        // Fields read in place: a copy of the box would be stored to the
        // stack and read back across the store, stalling every ray.
        let region = &self.occupied;
        if region.min.cmpge(region.max).any() {
            return MISS;
        }
        let Some(Entry {
            cell,
            moving,
            down,
            next_t,
            key,
        }) = Entry::new(ray, region)
        else {
            return MISS;
        };
        let cells = self.cells.as_ref();
        let mut idx = self.index(cell);
        let material = cells[idx];
        if material != 0 {
            let hit = hit(&self.palette, cell, down, key, material);
            return Traced { hit, steps: 0 };
        }
        // Per axis: the direction, the crossing after the next one, the
        // plane after that one, the steps left inside the region. An axis
        // the ray does not move along crosses nothing: its planes are
        // 1 * inf away.
        let (lo, hi) = (region.min.as_vec3a(), region.max.as_vec3a());
        let cellf = cell.as_vec3a();
        let dir = Vec3A::select(down, Vec3A::NEG_ONE, Vec3A::ONE);
        let exit = Vec3A::select(down, cellf, cellf + 1.0);
        let (ray_origin, _, ray_inv_dir) = ray.lanes();
        let origin = Vec3A::select(moving, ray_origin, Vec3A::ZERO);
        let inv_dir = Vec3A::select(moving, ray_inv_dir, Vec3A::INFINITY);
        let step = Vec3A::select(moving, dir, Vec3A::ZERO);
        let mut t = next_t;
        let mut plane = Vec3A::select(moving, exit + dir, Vec3A::ONE);
        let mut after = (plane - origin) * inv_dir;
        plane += step;
        // Below 2^24: exact in f32.
        let mut left = Vec3A::select(down, cellf - lo, hi - 1.0 - cellf);
        // The index stride of a step, by the bitmask of its axis' lane.
        let size = self.bounds.size().as_uvec3();
        let mut stride = [0usize; 8];
        let strides = [1, size.x as usize, size.x as usize * size.y as usize];
        for (a, s) in strides.into_iter().enumerate() {
            stride[1 << a] = if down.test(a) { s.wrapping_neg() } else { s };
        }
        let limit = t_max.min(f32::MAX);
        let limits = Vec3A::splat(limit);
        // The earliest lane, ties to the lowest axis, is the lane before
        // both others: x if tx <= ty and tx <= tz, y if ty <= tz and
        // ty < tx, z if tz < tx and tz < ty. With only `<=` compares, a
        // strict `<` is the flip of the `<=` with its sides swapped.
        let flip_a = BVec3A::new(false, false, true);
        let flip_b = BVec3A::new(false, true, true);
        let mut steps = 0;
        loop {
            // [tx <= ty, ty <= tz, tz < tx] & [tx <= tz, ty < tx, tz < ty].
            let a = t.xyx().cmple(t.yzz()) ^ flip_a;
            let b = t.xxy().cmple(t.zyz()) ^ flip_b;
            let first = a & b;
            if LIMITED && (t.cmpgt(limits) & first).any() {
                return Traced { hit: None, steps };
            }
            steps += 1;
            left -= Vec3A::select(first, Vec3A::ONE, Vec3A::ZERO);
            if left.is_negative_bitmask() != 0 {
                return Traced { hit: None, steps };
            }
            let lane = first.bitmask();
            idx = idx.wrapping_add(stride[lane as usize & 7]);
            // The crossing after the next, computed before the choice is
            // known so that the choice only selects.
            let ahead = (plane - origin) * inv_dir;
            let entered = t;
            t = Vec3A::select(first, after, t);
            after = Vec3A::select(first, ahead, after);
            plane += Vec3A::select(first, step, Vec3A::ZERO);
            let material = cells[idx];
            if material != 0 {
                let axis = lane.trailing_zeros() as usize;
                let key = Key {
                    t: entered[axis],
                    axis: axis as u8,
                };
                if key.t > limit {
                    return Traced { hit: None, steps };
                }
                // (A cell of the region: within +-2^22.)
                let pos = whole_numbers(Vec3A::select(down, lo + left, hi - 1.0 - left));
                let hit = hit(&self.palette, pos, down, key, material);
                return Traced { hit, steps };
            }
        }
    }

    /// The cell walk through the whole volume by single steps, showing
    /// `visit` each empty cell it leaves.
    pub(super) fn walk_visiting(&self, ray: &Ray, visit: &mut dyn FnMut(IAabb) -> bool) -> Traced {
        let Some(mut walk) = Walk::start(ray, &self.bounds) else {
            return MISS;
        };
        let cells = self.cells.as_ref();
        loop {
            let pos = walk.cell();
            let material = cells[self.index(pos)];
            if material != 0 {
                let (face, t) = walk.entry();
                let hit = Hit::from_palette(&self.palette, pos, face, t, material);
                return Traced {
                    hit,
                    steps: walk.steps(),
                };
            }
            let cell = IAabb {
                min: pos,
                max: pos + 1,
            };
            if !visit(cell) || !walk.step() {
                return Traced {
                    hit: None,
                    steps: walk.steps(),
                };
            }
        }
    }
}
