//! `Placed`: where a walk is at a distance, told from the rounded point
//! there instead of from crossing keys, when the point lies far enough
//! inside a box that no rounding can move it out.

use glam::Vec3A;

/// 2^-20: sixteen units in the last place of an `f32` (2^-24 each), per
/// unit of magnitude.
const MARGIN_PER_MAGNITUDE: f32 = 1.0 / 1_048_576.0;

/// The point a ray reaches at a distance `t`, as computed (`o + d * t`,
/// rounded twice), and a margin per axis of 2^-20 (|d t| + |point|).
///
/// The point is off the exact `o + d t` by at most 2^-24 (|d t| + |point|)
/// per axis, and a crossing time `(k - o) * (1 / d)`, rounded three times,
/// is off the exact `(k - o) / d` by at most 3 * 2^-24 of itself. So a
/// plane `k` farther than the margin from the point (by the computed
/// difference, itself rounded by at most 2^-24 of its size) is more than
/// 3 * 2^-24 |d t| from the exact point, its exact crossing more than
/// 3 * 2^-24 t from `t`, and its computed crossing on the same side of `t`
/// as the exact one and never equal to it. Single steps have therefore
/// crossed it before the key `(t, x)` exactly when the point lies past it:
/// a box holding the point with the margin on every side holds the cell
/// the walk is in at that key. On an axis the ray does not move along the
/// cell is the origin's, within the same margin of the point.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Placed {
    /// The point, rounded: where the walk is, up to the margin.
    pub(crate) point: Vec3A,
    margin: Vec3A,
}

impl Placed {
    /// The point `origin + along` (`along` = the direction times the
    /// distance, rounded once) and its margin.
    #[inline]
    pub(crate) fn new(origin: Vec3A, along: Vec3A) -> Placed {
        let point = origin + along;
        Placed {
            point,
            margin: (along.abs() + point.abs()) * MARGIN_PER_MAGNITUDE,
        }
    }

    /// Whether the box `[lo, hi)` (exact floats) holds the point with the
    /// margin on every side: then it holds the cell the walk is in at the
    /// key `(t, x)` (`false` says nothing).
    #[inline]
    pub(crate) fn surely_in(&self, lo: Vec3A, hi: Vec3A) -> bool {
        ((self.point - lo).cmpgt(self.margin) & (hi - self.point).cmpgt(self.margin)).all()
    }
}

#[cfg(test)]
mod tests {
    use glam::IVec3;

    use super::Placed;
    use crate::storage::walk::test_rays::Rng;
    use crate::storage::walk::{Key, Walk};

    /// A box that holds the point at a distance with the rounding margin
    /// holds the cell single steps are in at that key, for distances at,
    /// just before and just after plane crossings too; and the margin is
    /// narrow enough to answer most boxes around the point.
    #[test]
    fn a_point_inside_by_the_margin_is_inside_for_the_walk() {
        let mut rng = Rng(0x0bad_c0de_dead_beef);
        let (mut checked, mut sure) = (0, 0);
        for _ in 0..200_000 {
            let bounds = rng.bounds();
            let Some(ray) = rng.ray_at(bounds) else {
                continue;
            };
            let t = match rng.next() % 4 {
                0 => rng.range(0.0, 90.0),
                // A crossing, or the floats either side of one.
                k => {
                    let axis = (rng.next() % 3) as usize;
                    let plane = rng.int(-40, 40) as f32;
                    let t = (plane - ray.origin()[axis]) * ray.inv_dir()[axis];
                    [t, t.next_down(), t.next_up()][k as usize - 1]
                }
            };
            if !(t > 0.0 && t.is_finite()) {
                continue;
            }
            // As `Lanes::placed_at` computes it.
            let (origin, dir, _) = ray.lanes();
            let placed = Placed::new(origin, dir * t);
            let key = Key { t, axis: 0 };
            let mut walk = Walk::unplaced(&ray, &bounds);
            let (lo_f, hi_f) = (bounds.min.as_vec3a(), bounds.max.as_vec3a());
            let inside = walk.place_from(t).is_some() && walk.key().lt(key);
            if placed.surely_in(lo_f, hi_f) {
                assert!(inside, "{ray:?} {t} {bounds:?}: not in the box");
                sure += 1;
            }
            if !inside {
                continue;
            }
            let cell = walk.cell();
            for _ in 0..8 {
                let lo = cell + IVec3::new(rng.int(-3, 2), rng.int(-3, 2), rng.int(-3, 2));
                let hi = lo + IVec3::new(rng.int(1, 4), rng.int(1, 4), rng.int(1, 4));
                let contains = cell.cmpge(lo).all() && cell.cmplt(hi).all();
                if placed.surely_in(lo.as_vec3a(), hi.as_vec3a()) {
                    assert!(contains, "{ray:?} {t} {lo} {hi}: cell {cell}");
                    sure += 1;
                }
                checked += 1;
            }
        }
        assert!(checked > 20_000, "{checked} boxes");
        assert!(sure * 10 > checked, "{sure} of {checked} answered");
    }
}
