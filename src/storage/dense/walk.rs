//! The dense array's walk: the shared cell walk of `storage/walk.rs`,
//! entered with [`Walk::start`] and then stepped by a loop specialised for
//! one flat array.
//!
//! The loop keeps the walk's state in locals: the next crossing time of
//! each axis, the next plane of each axis as an `f32` (an integer below
//! 2^24, so adding 1 is exact and `(plane - origin) * inv_dir` is the very
//! crossing single steps compute), the flat index of the cell, moved by a
//! per-axis stride, and per axis the steps left before the ray leaves the
//! box it walks. The axis of each step is chosen as `Walk::step` chooses it:
//! the earliest crossing, ties to the lowest axis. The ray leaves the box
//! by position on the axis it steps along, as single steps do; the box is
//! convex, so a walk never comes back into it.
//!
//! Tracing walks only the occupied box: outside it every cell is empty, and
//! `Walk::start` enters it at the crossing single steps enter it by (the
//! octree starts at its occupied box the same way). The debug view's walk
//! visits every cell of the volume with `Walk::step`.

use glam::{BVec3A, IVec3, Vec3A, Vec3Swizzles};

use crate::geom::{Face, IAabb, Ray};
use crate::scene::{Hit, Traced};
use crate::storage::dense::DenseScene;
use crate::storage::walk::{Key, Walk};
use crate::voxel::Palette;

const MISS: Traced = Traced {
    hit: None,
    steps: 0,
};

/// Where a walk starts: its cell, its direction per axis, the crossing
/// times of the cell's exit planes and the key it entered the cell by.
struct Entry {
    cell: [i32; 3],
    step: [i32; 3],
    next_t: [f32; 3],
    key: Key,
}

impl Entry {
    /// The entry into `region` that [`Walk::start`] finds, or `None` when
    /// the ray misses it.
    #[inline]
    fn new(ray: &Ray, region: &IAabb) -> Option<Entry> {
        if let Some(entry) = Entry::inside(ray, region) {
            return Some(entry);
        }
        let walk = Walk::start(ray, region)?;
        Some(Entry {
            cell: walk.cell().to_array(),
            step: walk.step_dir().to_array(),
            next_t: walk.next_t(),
            key: walk.key(),
        })
    }

    /// [`Walk::start`] for an origin strictly inside `region` on every
    /// axis, the common case of secondary rays, without its general
    /// search: the start cell (floor of the origin, or ceil - 1 moving
    /// down) is then inside, the walk enters nothing, and its key is the
    /// start key of the highest moving axis whose origin lies on a plane.
    /// Every coordinate is then within +-2^22, so casts truncate exactly.
    #[inline]
    fn inside(ray: &Ray, region: &IAabb) -> Option<Entry> {
        let o = ray.origin();
        let strictly_inside =
            o.cmpgt(region.min.as_vec3()).all() && o.cmplt(region.max.as_vec3()).all();
        if !strictly_inside {
            return None;
        }
        let (o, d, inv) = (o.to_array(), ray.dir().to_array(), ray.inv_dir().to_array());
        let mut entry = Entry {
            cell: [0; 3],
            step: [0; 3],
            next_t: [f32::INFINITY; 3],
            key: Key {
                t: f32::NEG_INFINITY,
                axis: 0,
            },
        };
        // Branch-free per axis, so that the three axes unroll into straight
        // line code.
        for a in 0..3 {
            let truncated = o[a] as i32;
            let tf = truncated as f32;
            let floor = truncated - i32::from(tf > o[a]);
            let ceil = truncated + i32::from(tf < o[a]);
            let moving = (d[a] != 0.0) & inv[a].is_finite();
            let down = moving & (d[a] < 0.0);
            let cell = if down { ceil - 1 } else { floor };
            let exit = if down { cell } else { cell + 1 };
            let t = (exit as f32 - o[a]) * inv[a];
            entry.cell[a] = cell;
            entry.step[a] = i32::from(moving) - 2 * i32::from(down);
            entry.next_t[a] = if moving { t } else { f32::INFINITY };
            if moving & (tf == o[a]) {
                entry.key = Key {
                    t: 0.0,
                    axis: a as u8,
                };
            }
        }
        Some(entry)
    }

    /// The hit on `material` in `cell`, entered by `key`.
    #[inline]
    fn hit(
        palette: &Palette,
        cell: [i32; 3],
        step: [i32; 3],
        key: Key,
        material: u8,
    ) -> Option<Hit> {
        let (face, t) = if key.t == f32::NEG_INFINITY {
            (None, 0.0)
        } else {
            let a = usize::from(key.axis);
            (Some(Face::entered(a, step[a] > 0)), key.t)
        };
        Hit::from_palette(palette, IVec3::from_array(cell), face, t, material)
    }
}

impl<B: AsRef<[u8]>> DenseScene<B> {
    /// The first solid cell along `ray` in the occupied box, giving up once
    /// the walk enters a cell farther than `t_max`.
    #[inline]
    pub(super) fn walk(&self, ray: &Ray, t_max: f32) -> Traced {
        let region = self.occupied;
        if region.is_empty() {
            return MISS;
        }
        let Some(Entry {
            cell,
            step,
            next_t,
            key,
        }) = Entry::new(ray, &region)
        else {
            return MISS;
        };
        let cells = self.cells.as_ref();
        let mut idx = self.index(IVec3::from_array(cell));
        let material = cells[idx];
        if material != 0 {
            let hit = Entry::hit(&self.palette, cell, step, key, material);
            return Traced { hit, steps: 0 };
        }
        let size = self.bounds.size().as_uvec3();
        let strides = [1, size.x as usize, size.x as usize * size.y as usize];
        let (o, inv) = (ray.origin().to_array(), ray.inv_dir().to_array());
        let (lo, hi) = (region.min.to_array(), region.max.to_array());
        // Per axis: the crossing after the next one (`after`), the plane
        // after that one and its increment, the steps left inside the
        // region. An axis the ray does not move along crosses nothing: its
        // planes are 1 * inf away.
        let mut after = [f32::INFINITY; 3];
        let mut plane = [1.0f32; 3];
        let mut dplane = [0.0f32; 3];
        let mut origin = [0.0f32; 3];
        let mut inv_dir = [f32::INFINITY; 3];
        let mut left = [0.0f32; 3];
        // The index stride of a step, by the bitmask of its axis' lane.
        let mut stride = [0usize; 8];
        for a in 0..3 {
            let down = step[a] < 0;
            // Below 2^24: exact in f32.
            left[a] = if down {
                cell[a] - lo[a]
            } else {
                hi[a] - 1 - cell[a]
            } as f32;
            if step[a] == 0 {
                continue;
            }
            // Exit plane of the current cell, then one further.
            let (exit, d) = if down {
                (cell[a], -1)
            } else {
                (cell[a] + 1, 1)
            };
            after[a] = ((exit + d) as f32 - o[a]) * inv[a];
            plane[a] = (exit + 2 * d) as f32;
            dplane[a] = d as f32;
            origin[a] = o[a];
            inv_dir[a] = inv[a];
            stride[1 << a] = if down {
                strides[a].wrapping_neg()
            } else {
                strides[a]
            };
        }
        let (origin, inv_dir) = (Vec3A::from_array(origin), Vec3A::from_array(inv_dir));
        let dplane = Vec3A::from_array(dplane);
        let mut t = Vec3A::from_array(next_t);
        let mut after = Vec3A::from_array(after);
        let mut plane = Vec3A::from_array(plane);
        let mut left = Vec3A::from_array(left);
        // Giving up at +inf too: a crossing never reached ends the walk.
        let limit = Vec3A::splat(t_max.min(f32::MAX));
        // Lanes that win a tie against the lane after (x vs y, y vs z) and
        // the lane after that (x vs z): the lower axis.
        let ties_next = BVec3A::new(true, true, false);
        let ties_last = BVec3A::new(true, false, false);
        let mut steps = 0;
        loop {
            // The lane of the earliest crossing, ties to the lowest axis,
            // without a branch.
            let (next, last) = (t.yzx(), t.zxy());
            let first = (t.cmplt(next) | (t.cmpeq(next) & ties_next))
                & (t.cmplt(last) | (t.cmpeq(last) & ties_last));
            if (t.cmpgt(limit) & first).any() {
                return Traced { hit: None, steps };
            }
            steps += 1;
            left -= Vec3A::select(first, Vec3A::ONE, Vec3A::ZERO);
            if left.cmplt(Vec3A::ZERO).any() {
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
            plane += Vec3A::select(first, dplane, Vec3A::ZERO);
            let material = cells[idx];
            if material != 0 {
                let axis = lane.trailing_zeros() as usize;
                let key = Key {
                    t: entered[axis],
                    axis: axis as u8,
                };
                let left = left.to_array();
                let pos = core::array::from_fn(|a| {
                    if step[a] < 0 {
                        lo[a] + left[a] as i32
                    } else {
                        hi[a] - 1 - left[a] as i32
                    }
                });
                let hit = Entry::hit(&self.palette, pos, step, key, material);
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
