//! Where a walk starts: the start cell and its keys (the start rule,
//! [`Start`], once per ray for every walk of every storage), and the scalar
//! walk's entry into its volume by the robust slab test in key form
//! ([`Walk::start`]), every coordinate settled by exact key comparisons:
//! the definition the faster entries (`begin.rs`) are tested against.

use glam::{BVec3A, IVec3, Vec3A};

use crate::geom::{IAabb, Ray};
use crate::math::floor_cell;
use crate::storage::walk::{Key, Walk};

impl Walk {
    /// Starts a walk of `ray` through the volume `bounds`, or `None` when the
    /// ray misses it. Implements the robust slab test of Williams et al.
    /// 2005 in key form: the ray is inside once it has crossed the near plane
    /// of every axis, and misses if it crosses a far plane first.
    pub(crate) fn start(ray: &Ray, bounds: &IAabb) -> Option<Walk> {
        let (origin, dir, inv_dir) = ray.vectors();
        let begins = Start::of(ray);
        let mut walk = Walk {
            origin,
            dir,
            inv_dir,
            step: begins.step(),
            start: begins.cell,
            start_keys: begins.keys(),
            lo: bounds.min,
            hi: bounds.max,
            cell: begins.cell,
            key: Key::BEFORE,
            steps: 0,
        };
        walk.enter().then_some(walk)
    }

    /// The walk of `ray` through `bounds` where single steps from its start
    /// are at `key`: in the cell the last crossing before `key` entered
    /// (the entry cell, for a ray that enters at or after it), or `None`
    /// when the ray misses the volume or has left it by then. The
    /// definition a walk begun at a clear distance is tested against.
    #[cfg(test)]
    pub(crate) fn at(ray: &Ray, bounds: &IAabb, key: Key) -> Option<Walk> {
        let mut walk = Walk::start(ray, bounds)?;
        while super::earliest(glam::Vec3::from_array(walk.next_t())).lt(key) {
            if !walk.step() {
                return None;
            }
        }
        Some(walk)
    }

    /// Moves the walk from its start cell to the first cell inside the
    /// volume: `false` when the ray misses it.
    fn enter(&mut self) -> bool {
        let (lo, hi, start) = (self.lo, self.hi, self.start);
        // The key of entering the volume: the latest of the per-axis entries.
        let mut key_in = Key::BEFORE;
        let mut inside = [false; 3];
        for axis in 0..3 {
            let (s, c) = (self.step[axis], start[axis]);
            inside[axis] = lo[axis] <= c && c < hi[axis];
            let key = if inside[axis] {
                self.start_keys[axis]
            } else if s > 0 && c < lo[axis] {
                self.crossing(axis, lo[axis])
            } else if s < 0 && c >= hi[axis] {
                self.crossing(axis, hi[axis])
            } else {
                return false; // outside on an axis and not moving toward it
            };
            if key_in.lt(key) {
                key_in = key;
            }
        }
        if key_in.t == f32::INFINITY {
            return false;
        }
        // Only a near-plane crossing moves a cell; start keys (and the key
        // before everything) do not. On every other moving axis, the cell
        // the ray is in at that key; past the far side, a miss.
        let a = usize::from(key_in.axis);
        if !inside[a] {
            self.cell[a] = if self.step[a] > 0 { lo[a] } else { hi[a] - 1 };
            for b in (0..3).filter(|&b| b != a && self.step[b] != 0) {
                let s = self.step[b];
                let (near, far) = if s > 0 {
                    (lo[b], hi[b] - 1)
                } else {
                    (hi[b] - 1, lo[b])
                };
                let from = if inside[b] { start[b] } else { near };
                self.cell[b] = self.settle(b, from, far + s, key_in);
            }
            if !self.inside() {
                return false;
            }
        }
        self.key = key_in;
        true
    }

    /// The coordinate on moving axis `axis` (not the axis of `key`) that the
    /// ray is in at `key`: the first from `from` on whose exit crossing does
    /// not come before `key`, stopping at `limit`. Starts from the
    /// coordinate of the point at `key.t`, then corrects it with exact key
    /// comparisons, so the answer is the one single steps would reach.
    fn settle(&self, axis: usize, from: i32, limit: i32, key: Key) -> i32 {
        let s = self.step[axis];
        let exit = |c: i32| self.crossing(axis, self.exit_plane(axis, c));
        let span = i64::from(limit - from) * i64::from(s);
        let guess = floor_cell(self.origin[axis] + key.t * self.dir[axis]);
        let ahead = ((i64::from(guess) - i64::from(from)) * i64::from(s)).clamp(0, span);
        let mut c = from + (ahead as i32) * s;
        while c != from {
            // A cell is entered through the plane the one before it leaves by.
            let entry = if c == self.start[axis] {
                self.start_keys[axis]
            } else {
                exit(c - s)
            };
            if entry.lt(key) {
                break;
            }
            c -= s;
        }
        while c != limit && exit(c).lt(key) {
            c += s;
        }
        c
    }
}

/// 2^23: below it, casts of coordinates truncate exactly and integers and
/// their neighbours are exact floats, so origins below it on every axis
/// take the start rule on float lanes.
pub(crate) const EXACT: f32 = 8_388_608.0;

/// Where a ray's walk starts, by the start rule: the one place it is
/// computed, once per ray, for every walk of every storage.
///
/// The ray starts in the cell it is in just after `t = 0`: the floor of
/// the origin, but on an axis whose plane the origin lies on and along
/// which the ray moves down, the cell below. An axis whose direction has
/// an infinite reciprocal (a subnormal component) never reaches a plane in
/// `f32` and counts as not moving: its crossing at distance 0 would be NaN.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Start {
    /// The axes the ray moves up along.
    pub(crate) up: BVec3A,
    /// The axes the ray moves down along.
    pub(crate) down: BVec3A,
    /// The start cell.
    pub(crate) cell: IVec3,
    /// The start cell as floats: exact below 2^23, and a saturated cell of
    /// a huge origin keeps its order against every plane of a volume.
    pub(crate) cell_f: Vec3A,
    /// The moving axes whose entry plane into the start cell the origin
    /// lies on: the start key is `(0, axis)` there, else before everything.
    pub(crate) on_plane: BVec3A,
}

impl Start {
    /// The start of `ray`'s walk: on float lanes for an origin below 2^23
    /// on every axis (there the floor, and one less, are exact floats of
    /// exact integers), else by saturating integer truncation.
    #[inline]
    pub(crate) fn of(ray: &Ray) -> Start {
        let (origin, _, _) = ray.vectors();
        let (up, down) = directions(ray);
        let moving = up | down;
        if origin.abs().cmplt(Vec3A::splat(EXACT)).all() {
            // The start cell's entry plane is floor(o) moving up, ceil(o)
            // moving down: the origin lies on it exactly when it is an
            // integer, and then a ray moving down starts in the cell below.
            let floor = origin.floor();
            let on_plane = moving & floor.cmpeq(origin);
            let below = Vec3A::select(on_plane & down, Vec3A::ONE, Vec3A::ZERO);
            let cell_f = floor - below;
            return Start {
                up,
                down,
                cell: cell_f.as_ivec3(),
                cell_f,
                on_plane,
            };
        }
        // Truncation saturates as `floor_cell` does (saturated cells of huge
        // origins lie outside every volume).
        let truncated = origin.as_ivec3();
        let floor = truncated.saturating_sub(ones(truncated.as_vec3a().cmpgt(origin)));
        let on_plane = moving & floor.as_vec3a().cmpeq(origin);
        let cell = floor.saturating_sub(ones(on_plane & down));
        Start {
            up,
            down,
            cell,
            cell_f: cell.as_vec3a(),
            on_plane,
        }
    }

    /// The axes the ray moves along.
    #[inline]
    pub(crate) fn moving(&self) -> BVec3A {
        self.up | self.down
    }

    /// Per axis: +1, -1, or 0 for an axis the ray does not move along.
    #[inline]
    pub(crate) fn step(&self) -> IVec3 {
        ones(self.up) - ones(self.down)
    }

    /// The times of the start keys per axis: 0 on an axis whose entry
    /// plane the origin lies on, else before everything.
    #[inline]
    pub(crate) fn key_times(&self) -> Vec3A {
        Vec3A::select(self.on_plane, Vec3A::ZERO, Vec3A::NEG_INFINITY)
    }

    /// The start keys per axis: `(0, axis)` on an axis whose entry plane
    /// the origin lies on, else [`Key::BEFORE`].
    #[inline]
    pub(crate) fn keys(&self) -> [Key; 3] {
        let on_plane = self.on_plane.bitmask();
        core::array::from_fn(|axis| {
            if on_plane >> axis & 1 != 0 {
                Key {
                    t: 0.0,
                    axis: axis as u8,
                }
            } else {
                Key::BEFORE
            }
        })
    }

    /// [`Start::class_of`] the ray this start is of.
    #[inline]
    pub(crate) fn class(&self) -> u32 {
        self.up.bitmask() | self.down.bitmask() << 3
    }

    /// The part of a direction the start rule reads (which axes it moves
    /// up along, which down), as six bits: rays from one origin with equal
    /// classes start in the same cell. Without the rest of the start.
    #[inline]
    pub(crate) fn class_of(ray: &Ray) -> u32 {
        let (up, down) = directions(ray);
        up.bitmask() | down.bitmask() << 3
    }
}

/// The axes `ray` moves up along, and down: an axis whose direction has an
/// infinite reciprocal (a subnormal component) counts as not moving.
#[inline]
fn directions(ray: &Ray) -> (BVec3A, BVec3A) {
    let (_, dir, inv_dir) = ray.vectors();
    let moving = dir.cmpne(Vec3A::ZERO) & inv_dir.abs().cmplt(Vec3A::INFINITY);
    (
        moving & dir.cmpgt(Vec3A::ZERO),
        moving & dir.cmplt(Vec3A::ZERO),
    )
}

/// 1 on the lanes of `mask`, else 0, as integers.
#[inline]
fn ones(mask: BVec3A) -> IVec3 {
    let bits = mask.bitmask();
    IVec3::new(
        (bits & 1) as i32,
        (bits >> 1 & 1) as i32,
        (bits >> 2) as i32,
    )
}
