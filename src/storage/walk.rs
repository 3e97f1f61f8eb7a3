//! The cell walk shared by every backend: Amanatides & Woo's traversal with
//! plane crossings recomputed from the origin, one tie rule, and the two
//! questions a hierarchy asks of it: where does the ray leave a box, and on
//! which side of a plane is it.
//!
//! # The model
//! A ray crosses the integer planes of each axis at the times
//! `t = (plane - origin) * inv_dir` (one `f32` subtraction and one
//! multiplication, never accumulated, so a 4096-cell walk is as exact as a
//! 1-cell one). Every crossing gets a key `(t, axis)`, and the ray visits the
//! cells in the order of those keys: **a tie in `t` is decided by the lowest
//! axis index first** (x before y before z). A ray through an edge or corner
//! therefore steps into the x-neighbour first, then the y-neighbour, and so on.
//!
//! The walk's state after any number of steps is exactly "the cell reached
//! after processing every crossing in key order up to the current one". The
//! dense backend steps one cell at a time. The octree moves from box to box:
//! [`Walk::exit_of`] is the key at which the ray leaves an empty box (the
//! earliest of its far-plane crossings, which single steps would also reach
//! there), and [`Walk::upper_sides`] says which half of a box the ray is in
//! at a key, from the same crossings and the same order. Both backends
//! therefore find the same first solid cell, face and `t`, bit for bit.
//!
//! # The start
//! The ray starts in the cell it is in just after `t = 0`: an origin exactly on
//! a plane starts on the side the ray moves to (on an axis it does not move
//! along, in the cell above the plane). A ray leaving the surface of a solid
//! voxel therefore does not hit that voxel again. Crossings at `t = +inf` (the
//! ray never gets there in `f32`) never happen.
//!
//! # The bound
//! Every step, or move out of a box, crosses a new plane of the volume, and
//! the walk stops once it leaves the volume, so a walk takes at most
//! `size.x + size.y + size.z` moves ([`max_steps`]).

use glam::{BVec3, IVec3, Vec3};

use crate::geom::{Face, IAabb, Ray};
use crate::math::{ceil32, floor32, floor_cell, to_cell};

/// A crossing's place in the ray's visiting order: by time, then by axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Key {
    pub(crate) t: f32,
    pub(crate) axis: u8,
}

impl Key {
    /// Before every crossing: the key of a start cell entered at no plane.
    const BEFORE: Key = Key {
        t: f32::NEG_INFINITY,
        axis: 0,
    };

    /// The visiting order: smaller time first, then smaller axis.
    #[inline]
    pub(crate) fn lt(self, other: Key) -> bool {
        self.t < other.t || (self.t == other.t && self.axis < other.axis)
    }
}

/// Most moves (single cell steps or jumps over empty boxes) any ray makes in `bounds`.
#[must_use]
pub fn max_steps(bounds: &IAabb) -> u32 {
    let s = bounds.size().max(IVec3::ZERO).as_uvec3();
    s.x + s.y + s.z
}

/// The earliest of three crossings, one per axis; ties go to the lowest
/// axis. All `+inf` gives `+inf` (on axis 2).
#[inline]
fn earliest(t: Vec3) -> Key {
    let axis = if t.x <= t.y {
        if t.x <= t.z {
            0
        } else {
            2
        }
    } else if t.y <= t.z {
        1
    } else {
        2
    };
    Key {
        t: t[axis],
        axis: axis as u8,
    }
}

/// A ray's walk through the cells of one volume.
#[derive(Clone, Debug)]
pub(crate) struct Walk {
    origin: Vec3,
    dir: Vec3,
    inv_dir: Vec3,
    /// +1, -1, or 0 for an axis the ray does not move along.
    step: IVec3,
    /// Lanes of `step` that are +1, and that are not 0.
    up: BVec3,
    moving: BVec3,
    /// The cell the ray is in just after t = 0.
    start: IVec3,
    /// Key of the crossing into `start` on each axis: `(0, axis)` when the
    /// origin lies exactly on that entry plane, else before everything.
    start_keys: [Key; 3],
    /// Volume: cells `lo..hi` per axis.
    lo: IVec3,
    hi: IVec3,
    /// Current cell, always inside the volume while the walk runs.
    cell: IVec3,
    /// Key of the crossing that entered `cell`.
    key: Key,
    /// Crossing time of each axis' exit plane from `cell` (+inf if the ray
    /// does not move along that axis).
    next_t: [f32; 3],
    /// Moves made so far.
    steps: u32,
}

impl Walk {
    /// Starts a walk of `ray` through the volume `bounds`, or `None` when the
    /// ray misses it. Implements the robust slab test of Williams et al.
    /// 2005 in key form: the ray is inside once it has crossed the near plane
    /// of every axis, and misses if it crosses a far plane first.
    pub(crate) fn start(ray: &Ray, bounds: &IAabb) -> Option<Walk> {
        let (origin, dir, inv_dir) = (ray.origin(), ray.dir(), ray.inv_dir());
        let mut step = IVec3::ZERO;
        let mut start = IVec3::ZERO;
        let mut start_keys = [Key::BEFORE; 3];
        for axis in 0..3 {
            let (o, d) = (origin[axis], dir[axis]);
            // An infinite reciprocal (a subnormal component) would turn a
            // crossing at distance 0 into NaN; such an axis never reaches a
            // plane in f32 anyway, so it counts as not moving.
            let moving = d != 0.0 && inv_dir[axis].is_finite();
            step[axis] = if !moving {
                0
            } else if d > 0.0 {
                1
            } else {
                -1
            };
            start[axis] = if step[axis] < 0 {
                to_cell(ceil32(o) - 1.0)
            } else {
                floor_cell(o)
            };
            // The start cell's entry plane is floor(o) moving up, ceil(o)
            // moving down: the origin lies on it exactly when it is an
            // integer. (Compared in f32: the saturated cell of a huge origin
            // must not be incremented.)
            if step[axis] != 0 && floor32(o) == o {
                start_keys[axis] = Key {
                    t: 0.0,
                    axis: axis as u8,
                };
            }
        }
        let mut walk = Walk {
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
            next_t: [f32::INFINITY; 3],
            steps: 0,
            up: step.cmpgt(IVec3::ZERO),
            moving: step.cmpne(IVec3::ZERO),
        };
        walk.enter()?;
        Some(walk)
    }

    /// Moves the walk from its start cell to the first cell inside the volume.
    fn enter(&mut self) -> Option<()> {
        // The key of entering the volume: the latest of the per-axis entries.
        let mut key_in = Key::BEFORE;
        let mut entry_axis = None;
        for axis in 0..3 {
            let (s, c) = (self.step[axis], self.start[axis]);
            let (lo, hi) = (self.lo[axis], self.hi[axis]);
            let key = if (lo..hi).contains(&c) {
                self.start_keys[axis]
            } else if s > 0 && c < lo {
                self.crossing(axis, lo)
            } else if s < 0 && c >= hi {
                self.crossing(axis, hi)
            } else {
                return None; // outside on an axis and not moving toward it
            };
            if key_in.lt(key) {
                key_in = key;
                entry_axis = Some(axis);
            }
        }
        if key_in.t == f32::INFINITY {
            return None;
        }
        // Only a near-plane crossing moves a cell; start keys do not.
        let entry_axis = entry_axis.filter(|&a| !(self.lo[a]..self.hi[a]).contains(&self.start[a]));
        if let Some(a) = entry_axis {
            self.cell[a] = if self.step[a] > 0 {
                self.lo[a]
            } else {
                self.hi[a] - 1
            };
            for b in (0..3).filter(|&b| b != a && self.step[b] != 0) {
                let s = self.step[b];
                let (near, far) = if s > 0 {
                    (self.lo[b], self.hi[b] - 1)
                } else {
                    (self.hi[b] - 1, self.lo[b])
                };
                let inside = (self.lo[b]..self.hi[b]).contains(&self.start[b]);
                let from = if inside { self.start[b] } else { near };
                self.cell[b] = self.settle(b, from, far + s, key_in).0;
            }
            if !self.inside() {
                return None;
            }
        }
        self.key = key_in;
        self.refresh_next();
        Some(())
    }

    /// The crossing of `plane` on `axis` as a key.
    #[inline]
    fn crossing(&self, axis: usize, plane: i32) -> Key {
        Key {
            t: (plane as f32 - self.origin[axis]) * self.inv_dir[axis],
            axis: axis as u8,
        }
    }

    /// The plane through which the ray leaves cell coordinate `c` on `axis`.
    #[inline]
    fn exit_plane(&self, axis: usize, c: i32) -> i32 {
        if self.step[axis] > 0 {
            c + 1
        } else {
            c
        }
    }

    /// Key of the crossing that enters coordinate `c` on a moving `axis`.
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
        let s = self.step[axis];
        let span = i64::from(limit - from) * i64::from(s);
        let guess = floor_cell(self.origin[axis] + key.t * self.dir[axis]);
        let ahead = ((i64::from(guess) - i64::from(from)) * i64::from(s)).clamp(0, span);
        let mut c = from + (ahead as i32) * s;
        while c != from && !self.entry_key(axis, c).lt(key) {
            c -= s;
        }
        let mut exit = self.crossing(axis, self.exit_plane(axis, c));
        while c != limit && exit.lt(key) {
            c += s;
            exit = self.crossing(axis, self.exit_plane(axis, c));
        }
        (c, exit.t)
    }

    fn inside(&self) -> bool {
        self.cell.cmpge(self.lo).all() && self.cell.cmplt(self.hi).all()
    }

    fn refresh_next(&mut self) {
        for axis in 0..3 {
            self.next_t[axis] = if self.step[axis] == 0 {
                f32::INFINITY
            } else {
                self.crossing(axis, self.exit_plane(axis, self.cell[axis]))
                    .t
            };
        }
    }

    /// The current cell (inside the volume).
    #[inline]
    pub(crate) fn cell(&self) -> IVec3 {
        self.cell
    }

    /// Per axis: +1, -1, or 0 for an axis the ray does not move along.
    #[inline]
    pub(crate) fn step_dir(&self) -> IVec3 {
        self.step
    }

    /// Crossing time of each axis' exit plane from the current cell (+inf
    /// on an axis the ray does not move along): the state a specialised
    /// loop continues single steps from.
    #[inline]
    pub(crate) fn next_t(&self) -> [f32; 3] {
        self.next_t
    }

    /// Moves made so far.
    #[inline]
    pub(crate) fn steps(&self) -> u32 {
        self.steps
    }

    /// The key of the crossing that entered the current cell.
    #[inline]
    pub(crate) fn key(&self) -> Key {
        self.key
    }

    /// The entry face of the current cell (`None` for a start cell the ray
    /// is strictly inside of) and the distance to it.
    pub(crate) fn entry(&self) -> (Option<Face>, f32) {
        self.entry_at(self.key)
    }

    /// The face and distance of the crossing `key` (`None` and 0 for
    /// [`Key::BEFORE`]).
    #[inline]
    pub(crate) fn entry_at(&self, key: Key) -> (Option<Face>, f32) {
        if key.t == f32::NEG_INFINITY {
            (None, 0.0)
        } else {
            let axis = key.axis as usize;
            (Some(Face::entered(axis, self.step[axis] > 0)), key.t)
        }
    }

    /// The first crossing out of the box `[lo, hi)` for a ray that is
    /// inside it: the earliest key among the far planes of the moving axes
    /// (`+inf` if none is ever reached). The same arithmetic as single steps,
    /// on three lanes at once.
    #[inline]
    pub(crate) fn exit_of(&self, lo: IVec3, hi: IVec3) -> Key {
        let far = IVec3::select(self.up, hi, lo).as_vec3();
        let t = Vec3::select(
            self.moving,
            (far - self.origin) * self.inv_dir,
            Vec3::INFINITY,
        );
        earliest(t)
    }

    /// Whether the ray moves toward `+axis`.
    #[inline]
    pub(crate) fn moves_up(&self, axis: usize) -> bool {
        self.step[axis] > 0
    }

    /// For each axis, whether the cell the walk is in just after crossing
    /// `key` lies at or above that axis' lane of `planes`, for planes
    /// strictly inside a box the walk entered at `key` (never the plane of
    /// `key` itself). Planes behind the start are decided by the start cell,
    /// as the start rule says; planes ahead are crossed when their key comes
    /// strictly first. (A plane of `key`'s own axis with an equal key lies
    /// beyond the entry plane: single steps reach it only after entering.)
    #[inline]
    pub(crate) fn upper_sides(&self, planes: IVec3, key: Key) -> BVec3 {
        let t = (planes.as_vec3() - self.origin) * self.inv_dir;
        let lane = IVec3::new(0, 1, 2).cmplt(IVec3::splat(i32::from(key.axis)));
        let crossed = t.cmplt(Vec3::splat(key.t)) | (t.cmpeq(Vec3::splat(key.t)) & lane);
        let behind_start = planes.cmple(self.start);
        // Moving up: above once crossed; moving down: above until crossed;
        // not moving: where the start is.
        let down = self.moving & !self.up;
        (self.up & (behind_start | crossed))
            | (down & behind_start & !crossed)
            | (!self.moving & behind_start)
    }

    /// Steps to the next cell. Returns `false` when the ray leaves the volume
    /// (or never reaches another plane).
    #[inline]
    pub(crate) fn step(&mut self) -> bool {
        let key = earliest(Vec3::from_array(self.next_t));
        if key.t == f32::INFINITY {
            return false;
        }
        self.steps += 1;
        self.key = key;
        let axis = usize::from(key.axis);
        let c = self.cell[axis] + self.step[axis];
        if c < self.lo[axis] || c >= self.hi[axis] {
            return false;
        }
        self.cell[axis] = c;
        self.next_t[axis] = self.crossing(axis, self.exit_plane(axis, c)).t;
        true
    }
}
