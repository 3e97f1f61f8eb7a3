//! `WalkRay`: a ray's walk (`storage/walk/`) in SIMD form, the one
//! form every storage's walk keeps its ray in. Built once per ray from the
//! ray and its [`Start`]; it answers the questions a walk asks with
//! exactly the crossings, start rule and order of [`Walk`]: where its walk
//! of a box begins (`begin.rs`), where it leaves a box, which key enters a
//! cell, and on which side of three midplanes it is at a key.

use glam::{BVec3A, Vec3A};

use crate::geom::Ray;
#[cfg(doc)]
use crate::storage::walk::Walk;
use crate::storage::walk::{latest, Key, Start, AXES};

/// A ray's walk in SIMD vectors: the ray, where it starts, and its steps.
#[derive(Clone, Copy, Debug)]
pub(crate) struct WalkRay {
    pub(crate) origin: Vec3A,
    pub(crate) dir: Vec3A,
    pub(crate) inv_dir: Vec3A,
    /// Where the walk starts, by the start rule.
    pub(crate) start: Start,
    /// The walk's steps as floats: +1, -1, or 0 on an axis it does not
    /// move along.
    pub(crate) step: Vec3A,
    /// The axes the walk moves along.
    pub(crate) moving: BVec3A,
}

impl WalkRay {
    /// The walk of `ray`: its start ([`Start::of`]) and its
    /// crossings.
    #[inline]
    pub(crate) fn of(ray: &Ray) -> WalkRay {
        let (origin, dir, inv_dir) = ray.vectors();
        let start = Start::of(ray);
        let one = |mask| Vec3A::select(mask, Vec3A::ONE, Vec3A::ZERO);
        WalkRay {
            origin,
            dir,
            inv_dir,
            start,
            step: one(start.up) - one(start.down),
            moving: start.moving(),
        }
    }

    /// The key at which the ray enters `cell` (exact floats): the latest
    /// of its moving axes' entry crossings, the start key on an axis where
    /// it is the start cell's coordinate. What the walk's key is in every
    /// cell it reaches by crossings.
    #[inline]
    pub(crate) fn entry_key_of(&self, cell: Vec3A) -> Key {
        // Moving up a cell is entered through its lower plane.
        let entry_plane = Vec3A::select(self.start.up, cell, cell + 1.0);
        let crossed = (entry_plane - self.origin) * self.inv_dir;
        let t = Vec3A::select(
            cell.cmpeq(self.start.cell_f),
            self.start.key_times(),
            crossed,
        );
        latest(Vec3A::select(self.moving, t, Vec3A::NEG_INFINITY))
    }

    /// Whether the cell the walk is in at `key` lies in the box `[lo, hi)`
    /// (exact floats), by [`WalkRay::upper_sides`] of its faces, for a `key`
    /// that is no crossing of those planes.
    #[inline]
    pub(crate) fn holds(&self, lo: Vec3A, hi: Vec3A, key: Key) -> bool {
        self.upper_sides(lo, key).all() && !self.upper_sides(hi, key).any()
    }

    /// `Walk::exit_of` for the box `[lo, hi)` given as exact floats: the
    /// earliest far-plane crossing, ties to the lowest axis.
    #[inline]
    pub(crate) fn exit_of(&self, lo: Vec3A, hi: Vec3A) -> Key {
        let far = Vec3A::select(self.start.up, hi, lo);
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

    /// The cube of side `side` next to the one at `cube` (exact floats)
    /// across its far plane on `axis`, the one an exit on that axis enters.
    #[inline]
    pub(crate) fn neighbour(&self, cube: Vec3A, side: f32, axis: u8) -> Vec3A {
        let on_axis = AXES.cmpeq(Vec3A::splat(f32::from(axis)));
        cube + Vec3A::select(on_axis, self.step * side, Vec3A::ZERO)
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
        let behind_start = planes.cmple(self.start.cell_f);
        // Moving up: above once crossed; moving down: above until crossed;
        // not moving: where the start is.
        (behind_start & !(self.start.down & crossed)) | (self.start.up & crossed)
    }

    /// Which half of the cube at `corner` (side 2^(half_log + 1)) holds the
    /// position: its corner and octant (`x | y << 1 | z << 2`). A position
    /// known only to that cube (`known_log` above `half_log`) is narrowed to
    /// the half by the side of the midplanes the ray is on at `key`; a finer
    /// one already lies in one half. `half` is 2^half_log on every lane: the
    /// descent carries it, halving it a level at a time.
    #[inline(always)]
    pub(crate) fn half_of(
        &self,
        key: Key,
        corner: Vec3A,
        (half, half_log): (Vec3A, u32),
        at: &mut Vec3A,
        known_log: &mut u32,
    ) -> (Vec3A, u32) {
        debug_assert_eq!(half, Vec3A::splat((1u64 << half_log) as f32));
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

#[cfg(test)]
mod tests {
    use glam::Vec3A;

    use super::WalkRay;
    use crate::storage::walk::test_rays::Rng;
    use crate::storage::walk::{Begin, Key, Walk};

    /// The box's corners as the exact floats the octree keeps.
    fn lanes_of(b: crate::geom::IAabb) -> (Vec3A, Vec3A) {
        (b.min.as_vec3a(), b.max.as_vec3a())
    }

    /// A walk begins, in SIMD form, where single steps from the start are: at
    /// 0 in the walk's entry cell with its key (from inside and outside);
    /// at a clear distance, there when the walk has entered the box before
    /// it and not left, else at the entry; nowhere when the walk misses
    /// the box or has left it by then. The box's exit is the walk's.
    #[test]
    fn walks_begin_where_single_steps_are() {
        let mut rng = Rng(0x2545_f491_4f6c_dd1d);
        let (mut outside, mut later) = (0, 0);
        for _ in 0..80_000 {
            let bounds = rng.bounds();
            let Some(ray) = rng.ray_at(bounds) else {
                continue;
            };
            let walker = WalkRay::of(&ray);
            let (lo, hi) = lanes_of(bounds);
            let walk = Walk::start(&ray, &bounds);
            let t = match rng.next() % 3 {
                0 => 0.0,
                _ => rng.distance_along(&ray),
            };
            if !(t >= 0.0 && t.is_finite()) {
                continue;
            }
            let key = Key { t, axis: 0 };
            let stepped = Walk::at(&ray, &bounds, key);
            match walker.begin(&ray, &bounds, t) {
                Begin::At { cell, key: entered } => {
                    let walk = walk.as_ref().expect("the walk enters the box");
                    let walks_at = (walk.cell(), walk.key());
                    assert_eq!(
                        (cell.as_ivec3(), entered),
                        walks_at,
                        "{ray:?} {bounds:?} {t}"
                    );
                    assert!(t == 0.0 || !entered.lt(key), "{ray:?} {bounds:?} {t}");
                    outside += usize::from(!bounds.contains(ray.origin().floor().as_ivec3()));
                }
                Begin::Later(_) => {
                    let inside = stepped.is_some_and(|w| w.key().lt(key));
                    assert!(inside, "{ray:?} {bounds:?} {t}: not inside");
                    later += 1;
                }
                Begin::Misses => assert!(stepped.is_none(), "{ray:?} {bounds:?} {t}"),
            }
            if let Some(walk) = walk {
                assert_eq!(walker.exit_of(lo, hi), walk.exit_of(bounds.min, bounds.max));
            }
        }
        assert!(
            outside > 5_000 && later > 2_000,
            "{outside} from outside, {later} later"
        );
    }

    /// Every cell a walk reaches by single steps is entered at the key the
    /// walker computes for it, and the face and distance the walk reports.
    #[test]
    fn entry_keys_agree_with_single_steps() {
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
        let mut cells = 0;
        for _ in 0..4_000 {
            let bounds = rng.bounds();
            let Some(ray) = rng.ray_at(bounds) else {
                continue;
            };
            let walker = WalkRay::of(&ray);
            let Some(mut walk) = Walk::start(&ray, &bounds) else {
                continue;
            };
            loop {
                let key = walker.entry_key_of(walk.cell().as_vec3a());
                assert_eq!(key, walk.key(), "{ray:?} {bounds:?} {:?}", walk.cell());
                assert_eq!(key.entered(walker.start.up), walk.entry());
                cells += 1;
                if !walk.step() {
                    break;
                }
            }
        }
        assert!(cells > 20_000, "{cells} cells");
    }

    /// A walk at a key that is no crossing is in exactly the boxes that
    /// hold the cell single steps are in there, at keys that tie with
    /// plane crossings too.
    #[test]
    fn a_key_is_held_by_the_boxes_around_its_cell() {
        let mut rng = Rng(0x1234_5678_9abc_def1);
        let mut checked = 0;
        for _ in 0..40_000 {
            let bounds = rng.bounds();
            let Some(ray) = rng.ray_at(bounds) else {
                continue;
            };
            let walker = WalkRay::of(&ray);
            // Random, or exactly a crossing (the key (t, x) ties with it),
            // or next to one.
            let t = rng.distance_along(&ray);
            if !(t > 0.0 && t.is_finite()) {
                continue;
            }
            let key = Key { t, axis: 0 };
            let Some(walk) = Walk::at(&ray, &bounds, key).filter(|w| w.key().lt(key)) else {
                continue;
            };
            let cell = walk.cell();
            for _ in 0..8 {
                let (lo, hi) = rng.box_near(cell);
                let contains = cell.cmpge(lo).all() && cell.cmplt(hi).all();
                let (lo_f, hi_f) = (lo.as_vec3a(), hi.as_vec3a());
                assert_eq!(
                    walker.holds(lo_f, hi_f, key),
                    contains,
                    "{ray:?} {t} {lo} {hi}"
                );
                checked += 1;
            }
        }
        assert!(checked > 20_000, "{checked} boxes");
    }
}
