//! Where a walk begins: the start cell and its keys (the start rule), the
//! entry into the volume by the robust slab test in key form, and the
//! placement at a later key for a walk that begins at a known clear
//! distance. Every coordinate is settled by exact key comparisons, so a
//! walk begun anywhere is in the cell single steps from the start reach.

use glam::{BVec3A, IVec3, Vec3A};

use crate::geom::{IAabb, Ray};
use crate::math::floor_cell;
use crate::storage::walk::guess::Guess;
use crate::storage::walk::{Key, Missed, Walk};

impl Walk {
    /// Starts a walk of `ray` through the volume `bounds`, or `None` when the
    /// ray misses it. Implements the robust slab test of Williams et al.
    /// 2005 in key form: the ray is inside once it has crossed the near plane
    /// of every axis, and misses if it crosses a far plane first.
    pub(crate) fn start(ray: &Ray, bounds: &IAabb) -> Option<Walk> {
        Walk::begin(ray, bounds, Key::BEFORE)
    }

    /// The walk of `ray` through `bounds` in its start cell, not yet
    /// entered: what [`Walk::place_from`] moves to where the walk begins.
    /// Inlined, so that a caller builds it in place instead of receiving a
    /// copy.
    #[inline(always)]
    pub(crate) fn unplaced(ray: &Ray, bounds: &IAabb) -> Walk {
        let (origin, dir, inv_dir) = ray.lanes();
        let begins = Start::of(ray);
        let (step, start, start_keys) = (begins.step(), begins.cell, begins.keys());
        Walk {
            origin,
            dir,
            inv_dir,
            step,
            start,
            start_keys,
            lo: bounds.min,
            hi: bounds.max,
            cell: start,
            key: Key::BEFORE,
            steps: 0,
        }
    }

    /// Places a walk from [`Walk::unplaced`] for a finite `t_start` as
    /// [`Walk::start`] does, but where the ray is at the key `(t_start, x)`
    /// if it enters the volume before that: in the cell reached after
    /// every crossing strictly before that key, entered by the latest of
    /// its per-axis entry crossings, as single steps would leave it.
    /// [`Missed`] when the ray misses the volume or has left it by then.
    /// Walking on from there finds the same hit as walking from the start,
    /// provided no solid cell is entered before `t_start`.
    pub(crate) fn place_from(&mut self, t_start: f32) -> Result<(), Missed> {
        // At 0 or before, the start is already where the ray is.
        let not_before = if t_start > 0.0 {
            Key {
                t: t_start,
                axis: 0,
            }
        } else {
            Key::BEFORE
        };
        self.enter(not_before)
    }

    /// The walk in its first cell inside `bounds` at or after `not_before`.
    fn begin(ray: &Ray, bounds: &IAabb, not_before: Key) -> Option<Walk> {
        let mut walk = Walk::unplaced(ray, bounds);
        walk.enter(not_before).ok()?;
        Some(walk)
    }

    /// Moves the walk from its start cell to the first cell inside the
    /// volume, or to the cell the ray is in at `not_before` if it enters
    /// earlier.
    #[inline]
    fn enter(&mut self, not_before: Key) -> Result<(), Missed> {
        let (lo, hi, start) = (self.lo, self.hi, self.start);
        // The key of entering the volume: the latest of the per-axis entries.
        let mut key_in = Key::BEFORE;
        let mut entry_axis = 3;
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
                return Err(Missed); // outside on an axis and not moving toward it
            };
            if key_in.lt(key) {
                key_in = key;
                entry_axis = axis;
            }
        }
        if key_in.t == f32::INFINITY {
            return Err(Missed);
        }
        if key_in.lt(not_before) {
            return self.settle_all(not_before);
        }
        // Only a near-plane crossing moves a cell; start keys do not.
        if entry_axis < 3 && !inside[entry_axis] {
            let a = entry_axis;
            // Missed: another axis' far plane comes first. (What settling
            // would find, cheaper: half the rays of a frame miss.)
            for b in (0..3).filter(|&b| b != a && self.step[b] != 0) {
                let far = if self.step[b] > 0 { hi[b] } else { lo[b] };
                if self.crossing(b, far).lt(key_in) {
                    return Err(Missed);
                }
            }
            self.cell[a] = if self.step[a] > 0 { lo[a] } else { hi[a] - 1 };
            for b in (0..3).filter(|&b| b != a && self.step[b] != 0) {
                let s = self.step[b];
                let (near, far) = if s > 0 {
                    (lo[b], hi[b] - 1)
                } else {
                    (hi[b] - 1, lo[b])
                };
                let from = if inside[b] { start[b] } else { near };
                self.cell[b] = self.settle(b, from, far + s, key_in).0;
            }
            if !self.inside() {
                return Err(Missed);
            }
        }
        self.key = key_in;
        Ok(())
    }

    /// Places the walk, inside the volume by `key`, in the cell it is in at
    /// `key`: each moving axis settled from its first coordinate inside the
    /// volume, the cell's key the latest of their entry crossings. `None`
    /// when the ray has left the volume by `key`. Guessed on three lanes
    /// first (`guess.rs`), searched step by step when a guess is off.
    fn settle_all(&mut self, key: Key) -> Result<(), Missed> {
        match self.place_by_guess(key) {
            Guess::Placed => Ok(()),
            Guess::Left => Err(Missed),
            Guess::Unsure => self.settle_stepwise(key),
        }
    }

    /// [`Walk::settle_all`] by the search of each axis from its first
    /// coordinate inside the volume: what decides when a guess is off.
    pub(super) fn settle_stepwise(&mut self, key: Key) -> Result<(), Missed> {
        let mut entered = Key::BEFORE;
        for axis in 0..3 {
            let s = self.step[axis];
            if s == 0 {
                continue;
            }
            let (lo, hi) = (self.lo[axis], self.hi[axis]);
            let (near, far) = if s > 0 { (lo, hi - 1) } else { (hi - 1, lo) };
            let from = if (lo..hi).contains(&self.start[axis]) {
                self.start[axis]
            } else {
                near
            };
            let (c, _) = self.settle(axis, from, far + s, key);
            if c == far + s {
                return Err(Missed);
            }
            self.cell[axis] = c;
            let entry = self.entry_key(axis, c);
            if entered.lt(entry) {
                entered = entry;
            }
        }
        self.key = entered;
        Ok(())
    }

    /// Key of the crossing that enters coordinate `c` on a moving `axis`:
    /// the start key for the start coordinate, else the plane behind `c`.
    fn entry_key(&self, axis: usize, c: i32) -> Key {
        if c == self.start[axis] {
            self.start_keys[axis]
        } else {
            self.crossing(axis, self.exit_plane(axis, c) - self.step[axis])
        }
    }

    /// The coordinate on moving axis `axis` (not the axis of `key`) that the
    /// ray is in at `key`: the one with `entry < key < exit`, searched from
    /// `from` forward, stopping at `limit`; and the time of its exit
    /// crossing. Starts from the coordinate of the point at `key.t`, then
    /// corrects it with exact key comparisons, so the answer is the one
    /// single steps would reach.
    fn settle(&self, axis: usize, from: i32, limit: i32, key: Key) -> (i32, f32) {
        if self.step[axis] > 0 {
            self.settle_toward::<1>(axis, from, limit, key)
        } else {
            self.settle_toward::<-1>(axis, from, limit, key)
        }
    }

    /// [`Walk::settle`] for a ray moving toward `S` (+1 or -1) on `axis`.
    #[inline]
    fn settle_toward<const S: i32>(
        &self,
        axis: usize,
        from: i32,
        limit: i32,
        key: Key,
    ) -> (i32, f32) {
        let (o, inv) = (self.origin[axis], self.inv_dir[axis]);
        let crossing = |plane: i32| Key {
            t: (plane as f32 - o) * inv,
            axis: axis as u8,
        };
        // Moving up a cell is entered through its lower plane and left
        // through its upper one; moving down the other way round.
        let exit_plane = |c: i32| if S > 0 { c + 1 } else { c };
        let entry_plane = |c: i32| if S > 0 { c } else { c + 1 };
        let span = i64::from(limit - from) * i64::from(S);
        let guess = floor_cell(o + key.t * self.dir[axis]);
        let ahead = ((i64::from(guess) - i64::from(from)) * i64::from(S)).clamp(0, span);
        let mut c = from + (ahead as i32) * S;
        while c != from {
            let entry = if c == self.start[axis] {
                self.start_keys[axis]
            } else {
                crossing(entry_plane(c))
            };
            if entry.lt(key) {
                break;
            }
            c -= S;
        }
        let mut exit = crossing(exit_plane(c));
        while c != limit && exit.lt(key) {
            c += S;
            exit = crossing(exit_plane(c));
        }
        (c, exit.t)
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
        let (origin, _, _) = ray.lanes();
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

    /// The key the walk is in its start cell by: the latest start key,
    /// that of the highest axis whose plane the origin lies on (before
    /// everything when there is none).
    #[inline]
    pub(crate) fn key(&self) -> Key {
        let on_plane = self.on_plane.bitmask();
        if on_plane == 0 {
            Key::BEFORE
        } else {
            Key {
                t: 0.0,
                axis: (u32::BITS - 1 - on_plane.leading_zeros()) as u8,
            }
        }
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
    let (_, dir, inv_dir) = ray.lanes();
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
