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

use glam::IVec3;

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
            mut next_t,
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
        // Per axis: the plane crossed after the next one, its increment,
        // the steps left inside the region, the index stride.
        let mut plane = [0.0f32; 3];
        let mut dplane = [0.0f32; 3];
        let mut left = [0i32; 3];
        let mut stride = [0usize; 3];
        for a in 0..3 {
            let down = step[a] < 0;
            // Exit plane of the current cell, then one further.
            let (exit, d) = if down {
                (cell[a], -1)
            } else {
                (cell[a] + 1, 1)
            };
            plane[a] = (exit + d) as f32;
            dplane[a] = d as f32;
            left[a] = if down {
                cell[a] - lo[a]
            } else {
                hi[a] - 1 - cell[a]
            };
            stride[a] = if down {
                strides[a].wrapping_neg()
            } else {
                strides[a]
            };
        }
        // Giving up at +inf too: a crossing never reached ends the walk.
        let limit = t_max.min(f32::MAX);
        let mut steps = 0;
        loop {
            // The earliest crossing, ties to the lowest axis.
            let a01 = usize::from(next_t[1] < next_t[0]);
            let t01 = if next_t[1] < next_t[0] {
                next_t[1]
            } else {
                next_t[0]
            };
            let axis = if next_t[2] < t01 { 2 } else { a01 };
            let t = next_t[axis];
            if t > limit {
                return Traced { hit: None, steps };
            }
            steps += 1;
            if left[axis] == 0 {
                return Traced { hit: None, steps };
            }
            left[axis] -= 1;
            idx = idx.wrapping_add(stride[axis]);
            next_t[axis] = (plane[axis] - o[axis]) * inv[axis];
            plane[axis] += dplane[axis];
            let material = cells[idx];
            if material != 0 {
                let key = Key {
                    t,
                    axis: axis as u8,
                };
                let pos = core::array::from_fn(|a| {
                    if step[a] < 0 {
                        lo[a] + left[a]
                    } else {
                        hi[a] - 1 - left[a]
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
