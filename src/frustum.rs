//! `Frustum`: the pyramid of rays through a rectangle of pixels, which a
//! storage can ask "how far is everything you could hit?".

use glam::Vec3;

/// The rays from one apex through a convex quadrilateral: the four side
/// planes through the apex, each given by its inward normal. Every ray of a
/// tile of pixels, at any point of their area, lies inside the frustum of
/// that tile (`Camera::tile_frustum`).
///
/// A storage may answer [`crate::Scene::clear_distance`] for it: a distance
/// before which no ray inside the frustum hits anything.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frustum {
    /// Where every ray of the frustum starts.
    pub apex: Vec3,
    /// Inward normals of the four side planes through the apex: a direction
    /// `d` is inside when `n . d >= 0` for all four.
    pub normals: [Vec3; 4],
    /// How far (radians, small-angle) the planes are widened: a direction
    /// up to this much outside a plane still counts as inside.
    pub slack: f32,
    /// For each axis, a bound on that component's size for the unit
    /// direction of every ray through the quadrilateral, turned by up to
    /// the slack; at most 1, and all ones is always true. A ray that gets
    /// `g` away from the apex along an axis has gone at least
    /// `g / steepest` along itself.
    pub steepest: Vec3,
}

/// The least slack of the side-plane tests, relative to the distance from
/// the apex: normals and box corners are rounded to about 1e-7 of their
/// length, and this is a hundred times that.
const SLACK: f32 = 2e-5;

/// For each axis, a bound on that component's size for every unit direction
/// through the quadrilateral with the given corners, turned by up to `turn`
/// radians, at most 1. A point `p` of the quadrilateral is a mean of its
/// corners with nonnegative weights: no component is larger than the
/// corners' largest, and against the unit direction `w` of the corners'
/// mean, `|p| >= p . w`, which is linear, so at least the corners' least.
/// Turning a unit vector moves each component by at most the angle. Only
/// corners are used, never the planes: where rounding leaves a tiny tile's
/// planes meaningless (and the slack alone keeps the frustum's test true),
/// the corners still bound the rays.
fn steepest(corners: [Vec3; 4], turn: f32) -> Vec3 {
    let Some(w) = (corners[0] + corners[1] + corners[2] + corners[3]).try_normalize() else {
        return Vec3::ONE;
    };
    let nearest = corners
        .iter()
        .map(|c| c.dot(w))
        .fold(f32::INFINITY, f32::min);
    let largest = corners.iter().fold(Vec3::ZERO, |m, c| m.max(c.abs()));
    let bound = largest / nearest + Vec3::splat(turn);
    // Also when a corner lies behind the apex or nothing is finite (then
    // the comparisons fail): nothing is known.
    if nearest > 0.0 && bound.is_finite() {
        bound.min(Vec3::ONE)
    } else {
        Vec3::ONE
    }
}

impl Frustum {
    /// The frustum of the rays from `apex` through the quadrilateral whose
    /// corners lie along `corners` (directions, in order around it),
    /// widened by `stray` radians for rays that may stray that far from
    /// the exact ones; `None` when the corners do not span one (parallel or
    /// non-finite directions, a quadrilateral wider than a half-space), or
    /// for a negative or non-finite `stray`.
    #[must_use]
    pub fn through(apex: Vec3, corners: [Vec3; 4], stray: f32) -> Option<Frustum> {
        if !(stray.is_finite() && stray >= 0.0) {
            return None;
        }
        let slack = SLACK + stray;
        let center = corners[0] + corners[1] + corners[2] + corners[3];
        let mut normals = [Vec3::ZERO; 4];
        for (i, normal) in normals.iter_mut().enumerate() {
            let n = corners[i].cross(corners[(i + 1) % 4]);
            // Pointing toward the middle of the quadrilateral.
            let n = if n.dot(center) < 0.0 { -n } else { n };
            let length = n.length();
            if !(length > 0.0 && length.is_finite()) {
                return None;
            }
            *normal = n / length;
        }
        // Each corner must lie inside the planes it is not on: else the
        // quadrilateral is not convex as seen from the apex.
        let convex = (0..4).all(|i| {
            [corners[(i + 2) % 4], corners[(i + 3) % 4]]
                .iter()
                .all(|c| normals[i].dot(*c) >= -slack * c.abs().element_sum())
        });
        convex.then_some(Frustum {
            apex,
            normals,
            slack,
            steepest: steepest(corners, slack),
        })
    }

    /// Whether the box `[min, max]` may meet the frustum: `false` only when
    /// the whole box lies outside one side plane, by more than the slack.
    /// (A box outside the frustum near an edge may still answer `true`.)
    #[must_use]
    pub fn may_meet_box(&self, min: Vec3, max: Vec3) -> bool {
        self.normals.iter().all(|n| {
            // The box corner farthest along the normal.
            let corner = Vec3::select(n.cmpge(Vec3::ZERO), max, min) - self.apex;
            n.dot(corner) >= -self.slack * corner.abs().element_sum()
        })
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec3;
    use proptest::prelude::*;

    use super::Frustum;

    fn unit() -> impl Strategy<Value = Vec3> {
        (-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0)
            .prop_filter_map("not a direction", |(x, y, z)| {
                Vec3::new(x, y, z).try_normalize()
            })
    }

    /// The corners of a jittered rectangle around `view`, of half-size up
    /// to `spread` in the image plane at distance 1.
    fn corners_around(view: Vec3, jitter: [f32; 8], spread: f32) -> [Vec3; 4] {
        let u = view.any_orthonormal_vector();
        let v = view.cross(u);
        let signs = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
        core::array::from_fn(|k| {
            let (su, sv) = signs[k];
            view + u * (su * spread * jitter[2 * k]) + v * (sv * spread * jitter[2 * k + 1])
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(2000))]

        /// Every direction through the quadrilateral, turned by up to the
        /// slack, has components within the bounds; for a narrow frustum
        /// the bounds are close to the corners' own components.
        #[test]
        fn steepest_bounds_every_direction_through_the_corners(
            view in unit(),
            jitter in proptest::array::uniform8(0.2f32..1.0),
            spread in 1e-4f32..1.5,
            stray in 0.0f32..1e-3,
            weights in proptest::array::uniform4(0.0f32..1.0),
            turn in unit(),
        ) {
            let corners = corners_around(view, jitter, spread);
            let Some(frustum) = Frustum::through(Vec3::new(3.0, -7.0, 11.0), corners, stray)
            else {
                return Ok(());
            };
            let bounds = frustum.steepest;
            prop_assert!(bounds.cmple(Vec3::ONE).all() && bounds.cmpgt(Vec3::ZERO).all());
            let corners = corners.map(Vec3::normalize);
            let inside = corners
                .iter()
                .zip(weights)
                .fold(Vec3::ZERO, |sum, (c, w)| sum + *c * w);
            let Some(inside) = inside.try_normalize() else {
                return Ok(());
            };
            // Turned by at most the slack (the chord is shorter than the
            // angle).
            let turned = (inside + turn * frustum.slack).normalize();
            for d in [inside, turned] {
                prop_assert!(
                    d.abs().cmple(bounds + 1e-6).all(),
                    "direction {d} outside the bounds {bounds}"
                );
            }
            if spread < 0.05 {
                let largest = corners.iter().fold(Vec3::ZERO, |m, c| m.max(c.abs()));
                prop_assert!(
                    bounds.cmple(largest + 0.01).all(),
                    "bounds {bounds} loose against the corners' {largest}"
                );
            }
        }
    }
}
