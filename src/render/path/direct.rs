//! Next-event estimation: the light a diffuse hit receives straight from
//! the sun's disk and from one emissive voxel picked from the light list,
//! each through one light ray.

use glam::Vec3;

use crate::geom::{Face, Ray};
use crate::material::MaterialKind;
use crate::math::sqrt32;
use crate::render::path::bsdf::cone;
use crate::render::path::{PathSetup, Rng};
use crate::render::rays::secondary;
use crate::render::stats::RayStats;
use crate::scene::{Hit, Reach, Scene, WalkMemory};

/// The direct light at `hit` (entered through `face`) as a factor of the
/// albedo: the outgoing radiance of a white Lambertian face there. Its
/// rays toward the lights each begin from `memory`, left at the hit by the
/// walk that found it (each takes a copy).
#[allow(clippy::too_many_arguments)]
pub(super) fn light<'s, S: Scene + ?Sized>(
    scene: &'s S,
    setup: &PathSetup<'_>,
    ray: &Ray,
    hit: &Hit,
    face: Face,
    rng: &mut Rng,
    stats: &mut RayStats,
    memory: &WalkMemory<'s>,
) -> Vec3 {
    let n = face.normal().as_vec3();
    let mut light = Vec3::ZERO;
    if let Some((sun, intensity)) = setup.sun {
        let dir = cone(sun, setup.sun_cos, rng.next());
        let cos = dir.dot(n);
        if cos > 0.0 {
            if let Some(shadow) = secondary(ray, hit, dir) {
                stats.light_rays += 1;
                if scene
                    .trace_with(&shadow, Reach::ALL, &mut memory.clone(), None)
                    .hit
                    .is_none()
                {
                    // A face of albedo c facing the sun reflects c * intensity.
                    light += Vec3::splat(intensity * cos);
                }
            }
        }
    }
    if !setup.emitters.is_empty() {
        light += emitter(scene, setup, ray, hit, n, rng, stats, memory);
    }
    light
}

/// One emissive voxel of the list, picked uniformly, and a point picked
/// uniformly on one of its faces that look toward the hit: the radiance it
/// sends, divided by the probability of the pick (an unbiased estimate of
/// all the emitters' light; faces turned away send nothing).
#[allow(clippy::too_many_arguments)]
fn emitter<'s, S: Scene + ?Sized>(
    scene: &'s S,
    setup: &PathSetup<'_>,
    ray: &Ray,
    hit: &Hit,
    n: Vec3,
    rng: &mut Rng,
    stats: &mut RayStats,
    memory: &WalkMemory<'s>,
) -> Vec3 {
    let count = setup.emitters.len();
    let pick = rng.next();
    let index = ((pick.x * count as f32) as usize).min(count - 1);
    let lamp = setup.emitters[index];
    let cell = hit.pos.as_vec3();
    let from = ray.at(hit.t).clamp(cell, cell + 1.0);
    // The faces of the lamp whose outer side holds the hit point.
    let (low, high) = (lamp.as_vec3(), lamp.as_vec3() + 1.0);
    let mut faces = [(0usize, 0.0f32, 0.0f32); 3];
    let mut visible = 0;
    for axis in 0..3 {
        if from[axis] < low[axis] {
            faces[visible] = (axis, low[axis], -1.0);
            visible += 1;
        } else if from[axis] > high[axis] {
            faces[visible] = (axis, high[axis], 1.0);
            visible += 1;
        }
    }
    if visible == 0 {
        return Vec3::ZERO;
    }
    let (axis, plane, outward) = faces[((pick.y * visible as f32) as usize).min(visible - 1)];
    let spot = rng.next();
    let mut to = low;
    to[(axis + 1) % 3] += spot.x;
    to[(axis + 2) % 3] += spot.y;
    to[axis] = plane;
    let offset = to - from;
    let distance2 = offset.dot(offset);
    if distance2 <= 0.0 {
        return Vec3::ZERO;
    }
    let dir = offset / sqrt32(distance2);
    let (cos_here, cos_there) = (dir.dot(n), -dir[axis] * outward);
    if cos_here <= 0.0 || cos_there <= 0.0 {
        return Vec3::ZERO;
    }
    let Some(shadow) = secondary(ray, hit, dir) else {
        return Vec3::ZERO;
    };
    stats.light_rays += 1;
    let seen = scene
        .trace_with(&shadow, Reach::ALL, &mut memory.clone(), None)
        .hit;
    let Some(seen) = seen.filter(|h| h.pos == lamp) else {
        return Vec3::ZERO;
    };
    let material = setup.materials.get(seen.material);
    if material.kind() != MaterialKind::Emissive {
        return Vec3::ZERO;
    }
    let radiance = seen.voxel.color.as_vec3() * (material.emission() / 255.0);
    // Lambert's 1/pi times the geometry term over the pick's probability
    // density (1 / (count * visible) per unit of face area).
    let weight =
        cos_here * cos_there / distance2 * (count * visible) as f32 * core::f32::consts::FRAC_1_PI;
    radiance * weight
}
