//! `Placed`: where a walk is at a distance, told from the rounded point
//! there instead of from crossing keys, when the point lies far enough
//! inside a box that no rounding can move it out.

use glam::{BVec3A, Vec3A};

/// 2^-20: sixteen units in the last place of an `f32` (2^-24 each), per
/// unit of magnitude.
const MARGIN_PER_MAGNITUDE: f32 = 1.0 / 1_048_576.0;

/// The point a ray reaches at a distance `t`, as computed (`o + d * t`,
/// rounded twice, with `d` taken as 0 on an axis the walk does not move
/// along), and a margin per axis of 2^-20 (|d t| + |point|) plus the least
/// normal `f32`.
///
/// The point is off the exact `o + d t` by at most 2^-24 (|d t| + |point|)
/// per axis, and a crossing time `(k - o) * (1 / d)`, rounded three times,
/// is off the exact `(k - o) / d` by at most 3 * 2^-24 of itself; below
/// the normal range each rounding adds at most 2^-150 more, which the
/// least normal float (2^-126) covers. So a plane `k` farther than the
/// margin from the point (by the computed difference: rounding is
/// monotone, so it is never larger than the true one) is more than
/// 3 * 2^-24 |d t| from the exact point, its exact crossing more than
/// 3 * 2^-24 t from `t`, and its computed crossing on the same side of `t`
/// as the exact one and never equal to it. Single steps have therefore
/// crossed it before the key `(t, x)` exactly when the point lies past it:
/// a box holding the point with the margin on every side holds the cell
/// the walk is in at that key. On an axis the walk does not move along
/// (a direction component 0, or one so small that its inverse is
/// infinite) the walk stays in the origin's cell, and the point there is
/// the origin itself.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Placed {
    /// The point, rounded: where the walk is, up to the margin.
    pub(crate) point: Vec3A,
    margin: Vec3A,
}

impl Placed {
    /// The point at distance `t` of the ray from `origin` along `dir`,
    /// whose walk moves along the axes of `moving`, and its margin.
    #[inline]
    pub(crate) fn at(origin: Vec3A, dir: Vec3A, moving: BVec3A, t: f32) -> Placed {
        let along = Vec3A::select(moving, dir * t, Vec3A::ZERO);
        let point = origin + along;
        Placed {
            point,
            margin: (along.abs() + point.abs()) * MARGIN_PER_MAGNITUDE + f32::MIN_POSITIVE,
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
    use crate::geom::{IAabb, Ray};
    use crate::storage::walk::test_rays::Rng;
    use crate::storage::walk::{Key, Start, Walk};

    /// The placed point as `WalkRay::begin` computes it.
    fn placed_at(ray: &Ray, t: f32) -> Placed {
        let (origin, dir, _) = ray.vectors();
        Placed::at(origin, dir, Start::of(ray).moving(), t)
    }

    /// Whether the claim holds for `ray` at `t` and the box `[lo, hi)`:
    /// when the margin answers, the walk's cell at `(t, x)` is inside.
    /// Returns whether the margin answered.
    fn check(ray: &Ray, t: f32, volume: IAabb, lo: IVec3, hi: IVec3) -> bool {
        if !placed_at(ray, t).surely_in(lo.as_vec3a(), hi.as_vec3a()) {
            return false;
        }
        let key = Key { t, axis: 0 };
        let walk = Walk::at(ray, &volume, key).filter(|w| w.key().lt(key));
        let cell = walk.map(|w| w.cell());
        assert!(
            cell.is_some_and(|c| c.cmpge(lo).all() && c.cmplt(hi).all()),
            "{ray:?} at {t}: walk in {cell:?}, box {lo}..{hi}"
        );
        true
    }

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
            let t = rng.distance_along(&ray);
            if !(t > 0.0 && t.is_finite()) {
                continue;
            }
            let placed = placed_at(&ray, t);
            let key = Key { t, axis: 0 };
            let walk = Walk::at(&ray, &bounds, key).filter(|w| w.key().lt(key));
            let (lo_f, hi_f) = (bounds.min.as_vec3a(), bounds.max.as_vec3a());
            if placed.surely_in(lo_f, hi_f) {
                assert!(walk.is_some(), "{ray:?} {t} {bounds:?}: not in the box");
                sure += 1;
            }
            let Some(walk) = walk else {
                continue;
            };
            let cell = walk.cell();
            for _ in 0..8 {
                let (lo, hi) = rng.box_near(cell);
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

    /// Axes whose direction is too small to have a finite inverse do not
    /// move, whatever `d * t` is; tiny origins and distances round below
    /// the normal range. Neither moves the point's answer off the walk's.
    #[test]
    fn tiny_directions_and_distances_keep_the_claim() {
        let volume = IAabb::new(IVec3::splat(-8), IVec3::splat(8));
        let tiny = [0.0, f32::from_bits(1), -f32::from_bits(1), 1e-40, -1e-40];
        let small_dirs = [2f32.powi(-128), -(2f32.powi(-128)), 1e-39, -1e-39, 1e-30];
        let mut answered = 0;
        for &oy in &tiny {
            for &dy in &small_dirs {
                for &(dx, ox) in &[(1.0, 0.5), (-0.99, 0.25), (0.3, f32::from_bits(7))] {
                    let origin = glam::Vec3::new(ox, oy, 0.5);
                    let Ok(ray) = Ray::new(origin, glam::Vec3::new(dx, dy, 0.0)) else {
                        continue;
                    };
                    let ts = [3.0, 1.0, 2.5, 1e-38, 1e-44, f32::from_bits(0x8011e), 7.0];
                    for t in ts {
                        for (lo, hi) in [
                            (IVec3::new(3, 0, 0), IVec3::new(4, 1, 1)),
                            (IVec3::new(-8, 0, -8), IVec3::new(8, 8, 8)),
                            (IVec3::new(-8, -1, 0), IVec3::new(8, 0, 1)),
                            (IVec3::new(-1, -1, 0), IVec3::new(0, 0, 1)),
                            (IVec3::new(0, -1, 0), IVec3::new(1, 1, 1)),
                        ] {
                            answered += usize::from(check(&ray, t, volume, lo, hi));
                        }
                    }
                }
            }
        }
        assert!(answered > 50, "{answered} boxes answered");
    }

    /// Origins, directions and distances below the normal range: `t` at
    /// plane 0's crossing (or next to it) from a subnormal origin, where
    /// the relative bounds alone would allow a margin of 0 (without the
    /// least normal float in the margin this finds such walks: a point
    /// past plane 0 where the walk has not crossed it). The points lie
    /// within the floor of plane 0, so here the margin must refuse.
    #[test]
    fn subnormal_crossings_keep_the_claim() {
        let mut rng = Rng(0x7777_1234_abcd_0001);
        let volume = IAabb::new(IVec3::splat(-8), IVec3::splat(8));
        for _ in 0..200_000 {
            let ox = f32::from_bits((rng.next() % 0x7f_ffff) as u32 + 1);
            let ox = if rng.next() % 2 == 0 { ox } else { -ox };
            let dir = rng.direction();
            let origin = glam::Vec3::new(ox, 0.5, 0.5);
            let Ok(ray) = Ray::new(origin, dir) else {
                continue;
            };
            let t = (0.0 - ray.origin().x) * ray.inv_dir().x;
            for t in [t, t.next_up(), t.next_down()] {
                if !(t > 0.0 && t.is_finite()) {
                    continue;
                }
                for lo in [-1, 0] {
                    let lo = IVec3::new(lo, 0, 0);
                    assert!(!check(&ray, t, volume, lo, lo + 1), "{ray:?} at {t}");
                }
            }
        }
    }
}
