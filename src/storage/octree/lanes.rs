//! `Lanes`: the octree's two questions of a ray's walk (`storage/walk/`)
//! in four-lane form, answered with exactly the crossings, start rule and
//! order of the walk: where the ray leaves a box ([`Walk::exit_of`]) and on
//! which side of three midplanes it is at a key. Built once per ray.

use glam::{BVec3A, Vec3A};

use crate::storage::octree::grid::pow2;
use crate::storage::walk::{Key, Walk};

/// A ray's walk, reduced to what the octree asks of it.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Lanes {
    origin: Vec3A,
    inv_dir: Vec3A,
    /// The start cell, as floats: exact below 2^24, and a saturated cell of
    /// a huge origin keeps its order against every plane of a volume.
    start: Vec3A,
    /// The walk's steps as floats: +1, -1, or 0 on an axis it does not
    /// move along.
    pub(crate) step: Vec3A,
    pub(crate) up: BVec3A,
    pub(crate) down: BVec3A,
    moving: BVec3A,
}

impl Lanes {
    /// The lanes of `walk`.
    #[inline]
    pub(crate) fn of(walk: &Walk) -> Lanes {
        let (origin, inv_dir, start, step) = walk.parts();
        let step = step.as_vec3a();
        Lanes {
            origin,
            inv_dir,
            start: start.as_vec3a(),
            step,
            up: step.cmpgt(Vec3A::ZERO),
            down: step.cmplt(Vec3A::ZERO),
            moving: step.cmpne(Vec3A::ZERO),
        }
    }

    /// [`Walk::exit_of`] for the box `[lo, hi)` given as exact floats: the
    /// earliest far-plane crossing, ties to the lowest axis.
    #[inline]
    pub(crate) fn exit_of(&self, lo: Vec3A, hi: Vec3A) -> Key {
        let far = Vec3A::select(self.up, hi, lo);
        let t = Vec3A::select(
            self.moving,
            (far - self.origin) * self.inv_dir,
            Vec3A::INFINITY,
        );
        // Without branches: which of the three comes first is what the
        // walk cannot predict.
        let (x, y, z) = (t.x, t.y, t.z);
        let x_before_y = x <= y;
        let first = x_before_y && x <= z;
        let second = !x_before_y && y <= z;
        let axis = u8::from(!first) * (2 - u8::from(second));
        let t = if first {
            x
        } else if second {
            y
        } else {
            z
        };
        Key { t, axis }
    }

    /// For each axis, whether the cell the walk is in just after crossing
    /// `key` lies at or above that axis' lane of `planes` (exact floats), as
    /// a lane mask, for planes strictly inside a box
    /// the walk entered at `key` (never the plane of `key` itself). Planes
    /// behind the start are decided by the start cell, as the start rule
    /// says; planes ahead are crossed when their key comes strictly first.
    /// (A plane of `key`'s own axis with an equal key lies beyond the entry
    /// plane: single steps reach it only after entering.)
    #[inline]
    pub(crate) fn upper_sides(&self, planes: Vec3A, key: Key) -> BVec3A {
        let t = (planes - self.origin) * self.inv_dir;
        let kt = Vec3A::splat(key.t);
        let lane = Vec3A::new(0.0, 1.0, 2.0).cmplt(Vec3A::splat(f32::from(key.axis)));
        let crossed = t.cmplt(kt) | (t.cmpeq(kt) & lane);
        let behind_start = planes.cmple(self.start);
        // Moving up: above once crossed; moving down: above until crossed;
        // not moving: where the start is.
        (behind_start & !(self.down & crossed)) | (self.up & crossed)
    }

    /// Which half of the cube at `corner` (side 2^(half_log + 1)) holds the
    /// position: its corner and octant (`x | y << 1 | z << 2`). A position
    /// known only to that cube (`known_log` above `half_log`) is narrowed to
    /// the half by the side of the midplanes the ray is on at `key`; a finer
    /// one already lies in one half.
    #[inline(always)]
    pub(crate) fn half_of(
        &self,
        key: Key,
        corner: Vec3A,
        half_log: u32,
        at: &mut Vec3A,
        known_log: &mut u32,
    ) -> (Vec3A, u32) {
        let half = Vec3A::splat(pow2(half_log));
        let planes = corner + half;
        let narrow = *known_log > half_log;
        let upper = if narrow {
            self.upper_sides(planes, key)
        } else {
            at.cmpge(planes)
        };
        let child = corner + Vec3A::select(upper, half, Vec3A::ZERO);
        if narrow {
            *at = child;
            *known_log = half_log;
        }
        (child, upper.bitmask())
    }
}
