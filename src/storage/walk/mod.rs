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
//! `WalkRay::exit_of` is the key at which the ray leaves an empty box (the
//! earliest of its far-plane crossings, which single steps would also reach
//! there), and `WalkRay::upper_sides` says which half of a box the ray is in
//! at a key, from the same crossings, the same start rule and the same
//! order. Both backends therefore find the same first solid cell, face and
//! `t`, bit for bit.
//!
//! # The start
//! The ray starts in the cell it is in just after `t = 0`: an origin exactly on
//! a plane starts on the side the ray moves to (on an axis it does not move
//! along, in the cell above the plane). A ray leaving the surface of a solid
//! voxel therefore does not hit that voxel again. Crossings at `t = +inf` (the
//! ray never gets there in `f32`) never happen.
//!
//! # Where a walk begins
//! Three routes, each in one place: the start rule and the scalar walk's
//! entry into its volume, the definition ([`Start`], [`Walk::start`],
//! `start.rs`); the route both storages take, in SIMD form, from the start or
//! from a clear distance ([`WalkRay::begin`], `begin.rs`, with [`placed`]);
//! and the octree's descent from the node a `WalkMemory` recalls
//! (`octree/memory.rs`).
//!
//! # The bound
//! Every step, or move out of a box, crosses a new plane of the volume, and
//! the walk stops once it leaves the volume, so a walk takes at most
//! `size.x + size.y + size.z` moves ([`max_steps`]).

use glam::{BVec3A, IVec3, Vec3, Vec3A};

use crate::geom::{Face, IAabb};

mod begin;
pub(crate) mod placed;
mod start;
#[cfg(test)]
pub(crate) mod test_rays;
mod walk_ray;

pub(crate) use begin::{Begin, AXES};
pub(crate) use start::{Start, EXACT};
pub(crate) use walk_ray::WalkRay;

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

    /// The face this crossing enters a cell through, for a walk moving up
    /// the axes of `up`, and its distance: `None` and 0 before every
    /// crossing (a start cell the ray is strictly inside of). The one
    /// place a hit's face and `t` come from.
    #[inline]
    pub(crate) fn entered(self, up: BVec3A) -> (Option<Face>, f32) {
        if self.t == f32::NEG_INFINITY {
            (None, 0.0)
        } else {
            let up = up.bitmask() >> self.axis & 1 != 0;
            (Some(Face::entered(usize::from(self.axis), up)), self.t)
        }
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

/// The latest of three keys, one per axis lane (times `t`), ties to the
/// highest axis as [`Key::lt`] orders them; all `-inf` is before
/// everything.
#[inline]
pub(crate) fn latest(t: Vec3A) -> Key {
    let latest = t.max_element();
    if latest == f32::NEG_INFINITY {
        Key::BEFORE
    } else {
        let ties = t.cmpeq(Vec3A::splat(latest)).bitmask();
        Key {
            t: latest,
            axis: (u32::BITS - 1 - ties.leading_zeros()) as u8,
        }
    }
}

/// A ray's walk through the cells of one volume.
#[derive(Clone, Debug)]
pub(crate) struct Walk {
    // The ray's, as the walker keeps them.
    origin: Vec3A,
    dir: Vec3A,
    inv_dir: Vec3A,
    /// +1, -1, or 0 for an axis the ray does not move along.
    step: IVec3,
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
    /// Moves made so far.
    steps: u32,
}

impl Walk {
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

    fn inside(&self) -> bool {
        self.cell.cmpge(self.lo).all() && self.cell.cmplt(self.hi).all()
    }

    /// The current cell (inside the volume).
    #[inline]
    pub(crate) fn cell(&self) -> IVec3 {
        self.cell
    }

    /// Crossing time of each axis' exit plane from the current cell (+inf
    /// on an axis the ray does not move along): the state a specialised
    /// loop continues single steps from. Computed from the cell on each
    /// call, so walks that never step (the octree's) never pay for it.
    #[inline]
    pub(crate) fn next_t(&self) -> [f32; 3] {
        core::array::from_fn(|axis| {
            if self.step[axis] == 0 {
                f32::INFINITY
            } else {
                self.crossing(axis, self.exit_plane(axis, self.cell[axis]))
                    .t
            }
        })
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
    /// is strictly inside of) and the distance to it ([`Key::entered`]).
    pub(crate) fn entry(&self) -> (Option<Face>, f32) {
        let up = self.step.cmpgt(IVec3::ZERO);
        self.key.entered(BVec3A::new(up.x, up.y, up.z))
    }

    /// The first crossing out of the box `[lo, hi)` for a ray that is
    /// inside it: the earliest key among the far planes of the moving axes
    /// (`+inf` if none is ever reached). The same arithmetic as single steps,
    /// on three lanes at once: the definition the octree's four-lane
    /// `WalkRay::exit_of` is tested against.
    #[cfg(test)]
    pub(crate) fn exit_of(&self, lo: IVec3, hi: IVec3) -> Key {
        let far = IVec3::select(self.step.cmpgt(IVec3::ZERO), hi, lo).as_vec3a();
        let t = Vec3::select(
            self.step.cmpne(IVec3::ZERO),
            ((far - self.origin) * self.inv_dir).into(),
            Vec3::INFINITY,
        );
        earliest(t)
    }

    /// Steps to the next cell. Returns `false` when the ray leaves the volume
    /// (or never reaches another plane).
    #[inline]
    pub(crate) fn step(&mut self) -> bool {
        let key = earliest(Vec3::from_array(self.next_t()));
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
        true
    }
}
