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
use crate::storage::walk::{EntryCell, Key, Lanes, Start, Walk};

/// 1.5 * 2^23: added to a float below 2^22 in size, a sum whose last
/// mantissa bit is worth 1.
const ROUND: f32 = 12_582_912.0;

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

/// What the entry from outside found ([`Entry::outside`]).
enum Outside {
    /// The walk enters the region here.
    Enters(Entry),
    /// The ray misses the region.
    Misses,
    /// Not settled on lanes: `Walk::start` decides.
    Unsure,
}

impl Entry {
    /// The entry into `region` that [`Walk::start`] finds for the walk of
    /// `ray`, or `None` when the ray misses it.
    #[inline(always)]
    pub(super) fn new(ray: &Ray, region: &IAabb) -> Option<Entry> {
        if let Some(entry) = Entry::inside(ray, region) {
            return Some(entry);
        }
        match Entry::outside(ray, region) {
            Outside::Enters(entry) => return Some(entry),
            Outside::Misses => return None,
            Outside::Unsure => {}
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
    /// search: the start cell is then inside, the walk enters nothing, and
    /// its key is the start key ([`crate::storage::walk::Start::key`]).
    #[inline]
    fn inside(ray: &Ray, region: &IAabb) -> Option<Entry> {
        let (o, _, inv_dir) = ray.lanes();
        let strictly_inside =
            (o.cmpgt(region.min.as_vec3a()) & o.cmplt(region.max.as_vec3a())).all();
        if !strictly_inside {
            return None;
        }
        let start = Start::of(ray);
        let (moving, down, cell) = (start.moving(), start.down, start.cell_f);
        let exit = Vec3A::select(down, cell, cell + 1.0);
        let next_t = Vec3A::select(moving, (exit - o) * inv_dir, Vec3A::INFINITY);
        Some(Entry {
            cell: start.cell,
            moving,
            down,
            next_t,
            key: start.key(),
        })
    }

    /// [`Walk::start`] for an origin outside `region`, on lanes: the latest
    /// per-axis entry key, the cell there ([`Lanes::entry_cell`]), its exit
    /// crossings. [`Outside::Unsure`] when the entry cell's check does not
    /// confirm its guess, the start cell is inside on every axis (an origin
    /// on the box's face) or the origin is too far out. Kept out of line:
    /// inlined, it keeps `new` from being inlined into the walk, and the
    /// common case of secondary rays (an origin inside) would pay for
    /// returning the entry through memory.
    #[inline(never)]
    fn outside(ray: &Ray, region: &IAabb) -> Outside {
        let lanes = Lanes::of(ray);
        let (lo, hi) = (region.min.as_vec3a(), region.max.as_vec3a());
        let Some((key, starts_inside)) = lanes.entry_of(lo, hi) else {
            return Outside::Misses;
        };
        if key.t == f32::INFINITY {
            return Outside::Misses;
        }
        if starts_inside {
            return Outside::Unsure;
        }
        let cell = match lanes.entry_cell(lo, hi, key) {
            EntryCell::In(cell) => cell,
            EntryCell::Beside => return Outside::Misses,
            EntryCell::Unsure => return Outside::Unsure,
        };
        let exit = Vec3A::select(lanes.start.up, cell + 1.0, cell);
        let next_t = Vec3A::select(
            lanes.moving,
            (exit - lanes.origin) * lanes.inv_dir,
            Vec3A::INFINITY,
        );
        Outside::Enters(Entry {
            // (Within +-2^22, as the region.)
            cell: whole_numbers(cell),
            moving: lanes.moving,
            down: lanes.start.down,
            next_t,
            key,
        })
    }
}
