//! The dense array's walk: the shared cell walk of `storage/walk/`,
//! begun where every walk begins (`WalkRay::begin`), then stepped by a loop
//! specialised for one flat array.
//!
//! The loop keeps the walk's state in scalar registers, four per axis:
//! the next crossing time, the one after it, the plane after that as an
//! `f32` (an integer below 2^24, so adding 1 is exact and
//! `(plane - origin) * inv_dir` is the very crossing single steps compute),
//! and the steps left before the ray leaves the box it walks; the cell is a
//! flat index moved by a per-axis stride. The axis of each step is chosen
//! as `Walk::step` chooses it, the earliest crossing with ties to the
//! lowest axis, by two compares and a branch: a predicted branch lets the
//! next step start before this one's choice is known, where selects put
//! every choice on one chain of dependent instructions (1.4x faster on an
//! Intel Xeon VM; `benches/README.md`). The ray leaves the box by position
//! on the axis it steps along, as single steps do; the box is convex, so a
//! walk never comes back into it.
//!
//! Tracing walks only the occupied box: outside it every cell is empty, and
//! the walk enters it at the crossing single steps enter it by (the octree
//! begins at its occupied box the same way). The debug view's walk visits
//! every cell of the volume with `Walk::step`.

use glam::{BVec3A, IVec3, Vec3A};

use crate::geom::{IAabb, Ray};
use crate::scene::{Hit, Traced};
use crate::storage::dense::DenseScene;
use crate::storage::walk::{Begin, Key, Walk, WalkRay};
use crate::voxel::Palette;

/// 1.5 * 2^23: added to a float below 2^22 in size, a sum whose last
/// mantissa bit is worth 1.
const ROUND: f32 = 12_582_912.0;

/// `v` (whole numbers with `|v| <= 2^22`) as integers, read from the bits
/// of `v + 1.5 * 2^23`: that sum lies in `[2^23, 2^24]`, where the float's
/// last mantissa bit is worth 1, so its bits are those of 1.5 * 2^23 plus
/// `v`. Exact, without the saturating casts' range checks.
#[inline]
fn whole_numbers(v: Vec3A) -> IVec3 {
    let bits = (v + ROUND)
        .to_array()
        .map(|x| x.to_bits().wrapping_sub(ROUND.to_bits()) as i32);
    IVec3::from_array(bits)
}

const MISS: Traced = Traced {
    hit: None,
    steps: 0,
};

/// The hit on `material` in `cell`, entered by `key` on a walk moving down
/// the axes of `down`.
#[inline]
fn hit(palette: &Palette, cell: IVec3, down: BVec3A, key: Key, material: u8) -> Option<Hit> {
    // The key's axis is one the walk moves along: up where not down.
    let (face, t) = key.entered(!down);
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
        let walker = WalkRay::of(ray);
        let Begin::At { cell: cellf, key } = walker.begin(ray, region, 0.0) else {
            return MISS;
        };
        let (moving, down) = (walker.moving, walker.start.down);
        // (A cell of the region: within +-2^22.)
        let cell = whole_numbers(cellf);
        let cells = self.cells.as_ref();
        let mut idx = self.index(cell);
        let material = cells[idx];
        if material != 0 {
            let hit = hit(&self.palette, cell, down, key, material);
            return Traced { hit, steps: 0 };
        }
        // Per axis: the direction, the next crossing, the one after it,
        // the plane after that one, the steps left inside the region. An
        // axis the ray does not move along crosses nothing: its planes
        // are 1 * inf away.
        let (lo, hi) = (region.min.as_vec3a(), region.max.as_vec3a());
        let dir = Vec3A::select(down, Vec3A::NEG_ONE, Vec3A::ONE);
        let exit = Vec3A::select(down, cellf, cellf + 1.0);
        let next_t = (exit - walker.origin) * walker.inv_dir;
        let next_t = Vec3A::select(moving, next_t, Vec3A::INFINITY);
        let origin = Vec3A::select(moving, walker.origin, Vec3A::ZERO);
        let inv_dir = Vec3A::select(moving, walker.inv_dir, Vec3A::INFINITY);
        let step = Vec3A::select(moving, dir, Vec3A::ZERO);
        let plane = Vec3A::select(moving, exit + dir, Vec3A::ONE);
        let after = (plane - origin) * inv_dir;
        // Below 2^24: exact in f32.
        let left = Vec3A::select(down, cellf - lo, hi - 1.0 - cellf);
        let size = self.bounds.size().as_uvec3();
        let strides = [1, size.x as usize, size.x as usize * size.y as usize];
        let stride = |a: usize| {
            if down.test(a) {
                strides[a].wrapping_neg()
            } else {
                strides[a]
            }
        };
        let (stride_x, stride_y, stride_z) = (stride(0), stride(1), stride(2));
        let limit = t_max.min(f32::MAX);
        // The state, one scalar per axis: in registers, where the walk's
        // runtime axis would put an indexed array on the stack.
        let [mut next_x, mut next_y, mut next_z] = next_t.to_array();
        let [mut after_x, mut after_y, mut after_z] = after.to_array();
        let [mut plane_x, mut plane_y, mut plane_z] = (plane + step).to_array();
        let [mut left_x, mut left_y, mut left_z] = left.to_array();
        let [origin_x, origin_y, origin_z] = origin.to_array();
        let [inv_x, inv_y, inv_z] = inv_dir.to_array();
        let [step_x, step_y, step_z] = step.to_array();
        let mut steps = 0;
        loop {
            // One step along the axis whose crossing comes first: it leaves
            // the walk past the caller's reach (when `LIMITED`) or past the
            // box's far side, else moves the index and takes the axis' next
            // crossing; the crossing it entered by, and its axis.
            macro_rules! step_along {
                ($axis:literal, $next:ident, $after:ident, $plane:ident, $left:ident,
                 $origin:ident, $inv:ident, $step:ident, $stride:ident) => {{
                    if LIMITED && $next > limit {
                        return Traced { hit: None, steps };
                    }
                    steps += 1;
                    $left -= 1.0;
                    if $left < 0.0 {
                        return Traced { hit: None, steps };
                    }
                    idx = idx.wrapping_add($stride);
                    let entered = $next;
                    $next = $after;
                    $after = ($plane - $origin) * $inv;
                    $plane += $step;
                    Key {
                        t: entered,
                        axis: $axis,
                    }
                }};
            }
            // The earliest crossing, ties to the lowest axis: x when it is
            // no later than both others; else y when no later than z (then
            // y is strictly before x); else z.
            let key = if next_x <= next_y && next_x <= next_z {
                step_along!(0, next_x, after_x, plane_x, left_x, origin_x, inv_x, step_x, stride_x)
            } else if next_y <= next_z {
                step_along!(1, next_y, after_y, plane_y, left_y, origin_y, inv_y, step_y, stride_y)
            } else {
                step_along!(2, next_z, after_z, plane_z, left_z, origin_z, inv_z, step_z, stride_z)
            };
            let material = cells[idx];
            if material != 0 {
                if key.t > limit {
                    return Traced { hit: None, steps };
                }
                let left = Vec3A::new(left_x, left_y, left_z);
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
