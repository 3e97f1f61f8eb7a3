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
//! there), and the octree's `Lanes::upper_sides` says which half of a box
//! the ray is in at a key, from the same crossings, the same start rule and
//! the same order. Both backends
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
use crate::math::floor_cell;

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
        let mut step = [0; 3];
        let mut start = [0; 3];
        let mut start_keys = [Key::BEFORE; 3];
        for axis in 0..3 {
            let (o, d) = (origin[axis], dir[axis]);
            // An infinite reciprocal (a subnormal component) would turn a
            // crossing at distance 0 into NaN; such an axis never reaches a
            // plane in f32 anyway, so it counts as not moving.
            let moving = d != 0.0 && inv_dir[axis].is_finite();
            let s = i32::from(moving && d > 0.0) - i32::from(moving && d < 0.0);
            // The start cell's entry plane is floor(o) moving up, ceil(o)
            // moving down: the origin lies on it exactly when it is an
            // integer, and then a ray moving down starts in the cell below.
            // (Saturated cells of huge origins lie outside every volume.)
            let floor = floor_cell(o);
            let on_plane = moving && floor as f32 == o;
            start[axis] = floor.saturating_sub(i32::from(on_plane && s < 0));
            if on_plane {
                start_keys[axis] = Key {
                    t: 0.0,
                    axis: axis as u8,
                };
            }
            step[axis] = s;
        }
        let step = IVec3::from_array(step);
        let start = IVec3::from_array(start);
        // Built where it is returned (no copy of the walk on the way out).
        let mut walk = Some(Walk {
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
        });
        walk.as_mut()?.enter()?;
        walk
    }

    /// Moves the walk from its start cell to the first cell inside the volume.
    #[inline]
    fn enter(&mut self) -> Option<()> {
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
                return None; // outside on an axis and not moving toward it
            };
            if key_in.lt(key) {
                key_in = key;
                entry_axis = axis;
            }
        }
        if key_in.t == f32::INFINITY {
            return None;
        }
        // Only a near-plane crossing moves a cell; start keys do not.
        if entry_axis < 3 && !inside[entry_axis] {
            let a = entry_axis;
            // Missed: another axis' far plane comes first. (What settling
            // would find, cheaper: half the rays of a frame miss.)
            for b in (0..3).filter(|&b| b != a && self.step[b] != 0) {
                let far = if self.step[b] > 0 { hi[b] } else { lo[b] };
                if self.crossing(b, far).lt(key_in) {
                    return None;
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

    /// The ray's origin, reciprocal direction, start cell and per-axis
    /// steps (+1, -1, or 0): what a caller needs to ask the walk's
    /// questions in another form (the octree's four-lane `Lanes`).
    #[inline]
    pub(crate) fn parts(&self) -> (Vec3, Vec3, IVec3, IVec3) {
        (self.origin, self.inv_dir, self.start, self.step)
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
