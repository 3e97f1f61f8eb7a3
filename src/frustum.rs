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
}

/// The least slack of the side-plane tests, relative to the distance from
/// the apex: normals and box corners are rounded to about 1e-7 of their
/// length, and this is a hundred times that.
const SLACK: f32 = 2e-5;

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
