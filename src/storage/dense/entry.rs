//! Where the dense walk starts: the cell, crossings and key that
//! [`Walk::start`] finds for the occupied box, found faster for the two
//! common cases and by `Walk::start` itself otherwise.
//!
//! An origin strictly inside the box starts in its own cell. An origin
//! outside enters through the latest near-plane crossing, as `Walk::start`
//! decides it; on every other axis the walk is then in the first cell,
//! from the start (or the near side) on, whose exit crossing does not come
//! before the entry key: crossings only grow along an axis, so that cell
//! is unique, and `Walk::start`'s search from any guess ends there. The
//! shared `storage/walk/entry.rs` guesses it from the entry point and
//! checks the guess with exact key comparisons, on lanes (the octree
//! enters its box the same way); anything it cannot confirm is left to
//! `Walk::start`.

use glam::{BVec3A, IVec3, Vec3A};

use crate::geom::{IAabb, Ray};
use crate::storage::walk::{directions, entry_cell, entry_key, exact_start, Key, Walk};

/// 1.5 * 2^23: added to a float below 2^22 in size, a sum whose last
/// mantissa bit is worth 1.
const ROUND: f32 = 12_582_912.0;

/// `(floor(v), ceil(v))` per lane for `|v| < 2^22`, without libm's
/// software rounding: adding and subtracting 1.5 * 2^23 rounds to the
/// nearest integer exactly (round-to-nearest is IEEE's default on every
/// target), and one compare corrects it. The same values as `floor` and
/// `ceil`, but for the sign of a zero, which no use below can tell.
#[inline]
fn floor_and_ceil(v: Vec3A) -> (Vec3A, Vec3A) {
    let nearest = (v + ROUND) - ROUND;
    let one = |mask: BVec3A| Vec3A::select(mask, Vec3A::ONE, Vec3A::ZERO);
    (
        nearest - one(nearest.cmpgt(v)),
        nearest + one(nearest.cmplt(v)),
    )
}

/// `v` (whole numbers with `|v| <= 2^22`) as integers, read from the bits
/// of `v + 1.5 * 2^23`: that sum lies in `[2^23, 2^24]`, where the float's
/// last mantissa bit is worth 1, so its bits are those of 1.5 * 2^23 plus
/// `v`. Exact, without the saturating casts' range checks.
#[inline]
pub(super) fn whole_numbers(v: Vec3A) -> IVec3 {
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

    /// [`Walk::start`] for an origin outside `region` (and within 2^23 on
    /// every axis): `Some` of its answer, or `None` for `Walk::start` to
    /// find it: when the entry cell's check does not confirm its guess
    /// (`storage/walk/entry.rs`), or the start cell is inside on every
    /// axis (an origin on the box's face). On lanes: the start rule's
    /// cell, the latest per-axis entry key, the cell there, its exit
    /// crossings. Kept out of line: inlined, it keeps `new` from being
    /// inlined into the walk, and the common case of secondary rays (an
    /// origin inside) would pay for returning the entry through memory.
    #[inline(never)]
    fn outside(ray: &Ray, region: &IAabb) -> Option<Option<Entry>> {
        let (o, d, inv) = ray.lanes();
        let (up, down) = directions(ray);
        let (start, on_plane) = exact_start(o, up, down)?;
        let moving = up | down;
        let (lo, hi) = (region.min.as_vec3a(), region.max.as_vec3a());
        let start_t = Vec3A::select(on_plane, Vec3A::ZERO, Vec3A::NEG_INFINITY);
        let Some((key, _)) = entry_key(o, inv, (start, start_t), (up, down), (lo, hi)) else {
            return Some(None);
        };
        if key.t == f32::INFINITY {
            return Some(None);
        }
        let Some(cell) = entry_cell(o, d, inv, start, (up, down), (lo, hi), key)? else {
            return Some(None);
        };
        let exit = Vec3A::select(up, cell + 1.0, cell);
        let next_t = Vec3A::select(moving, (exit - o) * inv, Vec3A::INFINITY);
        Some(Some(Entry {
            // (Within +-2^22, as the region.)
            cell: whole_numbers(cell),
            moving,
            down,
            next_t,
            key,
        }))
    }
}
