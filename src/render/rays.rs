//! The rays a hit sends on: a secondary ray leaving the face it was
//! entered through, directions turned to a face's hemisphere, and the count
//! of one primary ray. Shared by the face-shaded kernels and the path
//! tracer.

use glam::Vec3;

use crate::geom::{Face, Ray};
use crate::render::stats::RayStats;
use crate::scene::Hit;

/// Rays counted for one primary ray and its hit.
pub(crate) fn primary(hit: Option<&Hit>) -> RayStats {
    RayStats {
        primary_rays: 1,
        primary_hits: u64::from(hit.is_some()),
        ..RayStats::default()
    }
}

/// A ray leaving `hit`'s entry face along `dir` (which points out of the
/// face): it starts in the empty cell in front of the face, a small step off
/// the face's plane, so it can never hit the voxel it leaves. `None` for a
/// hit without a face (a ray that started inside the voxel).
pub(crate) fn secondary(ray: &Ray, hit: &Hit, dir: Vec3) -> Option<Ray> {
    let face = hit.face?;
    let axis = face.axis();
    let normal = face.normal()[axis];
    // The plane of the face, and a step off it.
    let plane = (hit.pos[axis] + i32::from(normal > 0)) as f32;
    let step = nudge(plane);
    let cell = hit.pos.as_vec3();
    let mut origin = ray.at(hit.t).clamp(cell, cell + 1.0);
    origin[axis] = plane + normal as f32 * step;
    Ray::new(origin, dir).ok()
}

/// A step off a plane at coordinate `plane` that survives rounding there:
/// 1/256, or one unit in the last place far out. Every ray that leaves a
/// surface (a secondary ray, a path through glass) starts this far off it.
#[inline]
pub(crate) fn nudge(plane: f32) -> f32 {
    (1.0 / 256.0f32).max(plane.abs() * f32::EPSILON)
}

/// `local` (around `+z`) turned to the hemisphere around `face`'s normal.
pub(crate) fn around(face: Face, local: Vec3) -> Vec3 {
    let axis = face.axis();
    let mut dir = Vec3::ZERO;
    dir[axis] = local.z * face.normal()[axis] as f32;
    dir[(axis + 1) % 3] = local.x;
    dir[(axis + 2) % 3] = local.y;
    dir
}
