//! Where the dense walk starts: the cell, crossings and key that
//! [`Walk::start`] finds for the occupied box, found faster for the two
//! common cases and by `Walk::start` itself otherwise.
//!
//! An origin strictly inside the box starts in its own cell. An origin
//! outside enters through the latest near-plane crossing, as `Walk::start`
//! decides it; on every other axis the walk is then in the first cell,
//! from the start (or the near side) on, whose exit crossing does not come
//! before the entry key: crossings only grow along an axis, so that cell
//! is unique, and `Walk::start`'s search from any guess ends there. This
//! file guesses it from the entry point and checks the guess with exact
//! key comparisons, leaving anything it cannot confirm to `Walk::start`.

use glam::{BVec3A, IVec3, Vec3A};

use crate::geom::{IAabb, Ray};
use crate::storage::walk::{start_rule, Key, Walk, EXACT};

/// Before every crossing.
const BEFORE: Key = Key {
    t: f32::NEG_INFINITY,
    axis: 0,
};

/// `(floor(v), ceil(v))` per lane for `|v| < 2^22`, without libm's
/// software rounding: adding and subtracting 1.5 * 2^23 rounds to the
/// nearest integer exactly (round-to-nearest is IEEE's default on every
/// target), and one compare corrects it. The same values as `floor` and
/// `ceil`, but for the sign of a zero, which no use below can tell.
#[inline]
fn floor_and_ceil(v: Vec3A) -> (Vec3A, Vec3A) {
    const ROUND: f32 = 12_582_912.0; // 1.5 * 2^23
    let nearest = (v + ROUND) - ROUND;
    let one = |mask: BVec3A| Vec3A::select(mask, Vec3A::ONE, Vec3A::ZERO);
    (
        nearest - one(nearest.cmpgt(v)),
        nearest + one(nearest.cmplt(v)),
    )
}

/// `v` (whole numbers with `|v| < 2^22`) as integers, read from the bits
/// of `v + 1.5 * 2^23`: that sum lies in `(2^23, 2^24)`, where the float's
/// last mantissa bit is worth 1, so its bits are those of 1.5 * 2^23 plus
/// `v`. Exact, without the saturating casts' range checks.
#[inline]
pub(super) fn whole_numbers(v: Vec3A) -> IVec3 {
    const ROUND: f32 = 12_582_912.0; // 1.5 * 2^23
    let bits = (v + ROUND)
        .to_array()
        .map(|x| x.to_bits().wrapping_sub(ROUND.to_bits()) as i32);
    IVec3::from_array(bits)
}

/// Where a walk starts: its cell, the axes it moves along and those of
/// them it moves down, the crossing times of the cell's exit planes and
/// the key it entered the cell by.
pub(super) struct Entry {
    pub(super) cell: IVec3,
    pub(super) moving: BVec3A,
    pub(super) down: BVec3A,
    pub(super) next_t: Vec3A,
    pub(super) key: Key,
}

impl Entry {
    /// The entry into `region` that [`Walk::start`] finds, or `None` when
    /// the ray misses it.
    #[inline(always)]
    pub(super) fn new(ray: &Ray, region: &IAabb) -> Option<Entry> {
        if let Some(entry) = Entry::inside(ray, region) {
            return Some(entry);
        }
        if let Some(entry) = Entry::outside(ray, region) {
            return entry;
        }
        let walk = Walk::start(ray, region)?;
        let step = walk.step_dir();
        Some(Entry {
            cell: walk.cell(),
            moving: BVec3A::new(step.x != 0, step.y != 0, step.z != 0),
            down: BVec3A::new(step.x < 0, step.y < 0, step.z < 0),
            next_t: Vec3A::from_array(walk.next_t()),
            key: walk.key(),
        })
    }

    /// [`Walk::start`] for an origin strictly inside `region` on every
    /// axis, the common case of secondary rays, without its general
    /// search: the start cell (floor of the origin, or ceil - 1 moving
    /// down) is then inside, the walk enters nothing, and its key is the
    /// start key of the highest moving axis whose origin lies on a plane.
    /// Every coordinate is then within +-2^22, where `floor` and `ceil` are
    /// exact on three lanes at once.
    #[inline]
    fn inside(ray: &Ray, region: &IAabb) -> Option<Entry> {
        let (o, d, inv) = ray.lanes();
        let strictly_inside =
            (o.cmpgt(region.min.as_vec3a()) & o.cmplt(region.max.as_vec3a())).all();
        if !strictly_inside {
            return None;
        }
        let (floor, ceil) = floor_and_ceil(o);
        let moving = d.cmpne(Vec3A::ZERO) & inv.is_finite_mask();
        let down = moving & d.cmplt(Vec3A::ZERO);
        let cell = Vec3A::select(down, ceil - 1.0, floor);
        let exit = Vec3A::select(down, cell, cell + 1.0);
        let next_t = Vec3A::select(moving, (exit - o) * inv, Vec3A::INFINITY);
        let on_plane = (moving & floor.cmpeq(o)).bitmask();
        let key = if on_plane == 0 {
            Key {
                t: f32::NEG_INFINITY,
                axis: 0,
            }
        } else {
            Key {
                t: 0.0,
                axis: (31 - on_plane.leading_zeros()) as u8,
            }
        };
        Some(Entry {
            // (Within +-2^22, as the origin.)
            cell: whole_numbers(cell),
            moving,
            down,
            next_t,
            key,
        })
    }

    /// [`Walk::start`] for an origin outside `region` (and within
    /// [`EXACT`]): `Some` of its answer, or `None` when a guess does not
    /// check out. Kept out of line: inlined, it keeps `new` from being
    /// inlined into the walk, and the common case of secondary rays (an
    /// origin inside) would pay for returning the entry through memory.
    #[inline(never)]
    fn outside(ray: &Ray, region: &IAabb) -> Option<Option<Entry>> {
        if ray.origin().abs().cmpge(glam::Vec3::splat(EXACT)).any() {
            return None;
        }
        // Plain arrays: indexing them by axis costs no panic branch.
        let o = ray.origin().to_array();
        let inv = ray.inv_dir().to_array();
        let d = ray.dir().to_array();
        let (lo, hi) = (region.min.to_array(), region.max.to_array());
        // The start rule, shared with `Walk::start`.
        let (step, start, start_keys) = start_rule(ray);
        let mut inside = [false; 3];
        let crossing = |axis: usize, plane: i32| Key {
            t: (plane as f32 - o[axis]) * inv[axis],
            axis: axis as u8,
        };
        // The key entering the region on each axis; the latest of them
        // enters the region.
        let mut key_in = BEFORE;
        let mut entry_axis = None;
        for a in 0..3 {
            inside[a] = (lo[a]..hi[a]).contains(&start[a]);
            let key = if inside[a] {
                start_keys[a]
            } else if step[a] > 0 && start[a] < lo[a] {
                crossing(a, lo[a])
            } else if step[a] < 0 && start[a] >= hi[a] {
                crossing(a, hi[a])
            } else {
                return Some(None);
            };
            if key_in.lt(key) {
                key_in = key;
                entry_axis = Some(a);
            }
        }
        if key_in.t == f32::INFINITY {
            return Some(None);
        }
        let mut cell = start;
        if let Some(a) = entry_axis.filter(|&a| !inside[a]) {
            cell[a] = if step[a] > 0 { lo[a] } else { hi[a] - 1 };
            for b in (0..3).filter(|&b| b != a && step[b] != 0) {
                let s = step[b];
                let (near, far) = if s > 0 {
                    (lo[b], hi[b] - 1)
                } else {
                    (hi[b] - 1, lo[b])
                };
                let from = if inside[b] { start[b] } else { near };
                let limit = far + s;
                // The guess: the cell of the entry point, within
                // `from..=limit`; checked, not trusted.
                let at = o[b] + key_in.t * d[b];
                // (NaN too: an entry time times a tiny direction.)
                if at.is_nan() || at.abs() >= EXACT {
                    return None;
                }
                let guess = at as i32 - i32::from((at as i32 as f32) > at);
                let guess = if s > 0 {
                    guess.clamp(from, limit)
                } else {
                    guess.clamp(limit, from)
                };
                // Exit plane of a cell: its upper side moving up.
                let exit = |c: i32| if s > 0 { c + 1 } else { c };
                let after_previous = guess == from || crossing(b, exit(guess - s)).lt(key_in);
                let not_before = guess == limit || !crossing(b, exit(guess)).lt(key_in);
                if !(after_previous && not_before) {
                    return None;
                }
                cell[b] = guess;
            }
            if (0..3).any(|a| !(lo[a]..hi[a]).contains(&cell[a])) {
                return Some(None);
            }
        }
        let mut next_t = [f32::INFINITY; 3];
        for a in 0..3 {
            if step[a] != 0 {
                let exit = if step[a] > 0 { cell[a] + 1 } else { cell[a] };
                next_t[a] = crossing(a, exit).t;
            }
        }
        Some(Some(Entry {
            cell: IVec3::from_array(cell),
            moving: BVec3A::new(step[0] != 0, step[1] != 0, step[2] != 0),
            down: BVec3A::new(step[0] < 0, step[1] < 0, step[2] < 0),
            next_t: Vec3A::from_array(next_t),
            key: key_in,
        }))
    }
}
