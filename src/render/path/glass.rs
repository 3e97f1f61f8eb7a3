//! Light through glass: Fresnel reflection or refraction where a ray meets
//! a glass voxel, then a walk voxel by voxel through the glass to where it
//! leaves (reflecting inside, total internal reflection included, until it
//! refracts out) or meets another solid voxel.
//!
//! Neighbouring glass voxels form one body: only faces between glass and
//! something else are interfaces. The walk asks the scene for the voxel
//! beyond each face with a ray of reach 0 (`trace_within`), which starts
//! inside that voxel and stops at once, so it costs one lookup.

use glam::{IVec3, Vec3};

use crate::geom::{Face, Ray};
use crate::material::{Material, MaterialKind, Materials};
use crate::render::path::bsdf::{fresnel_dielectric, microfacet, reflect, refract};
use crate::render::path::Rng;
use crate::render::rays::{nudge, secondary};
use crate::render::stats::RayStats;
use crate::scene::{Hit, Scene, WalkMemory};
use crate::storage::walk::Start;

/// The most voxels one pass through glass walks before the path is given
/// up (a bound on the loop; real panes are a few voxels thick).
const MAX_GLASS_VOXELS: u32 = 4096;

/// Where a path goes after meeting glass.
pub(super) enum Glass {
    /// Back out into empty space along `ray` (reflected off the glass, or
    /// refracted through it), its throughput times `weight`.
    Out { ray: Ray, weight: Vec3 },
    /// Inside the glass it met another solid voxel: `hit` along `ray`.
    Inside { ray: Ray, hit: Hit, weight: Vec3 },
    /// Absorbed, or out of bounces.
    Lost,
}

/// The path meeting the glass voxel of `hit` along `ray`.
#[allow(clippy::too_many_arguments)] // one caller, the path loop
pub(super) fn through_glass<S: Scene + ?Sized>(
    scene: &S,
    materials: &Materials,
    ray: &Ray,
    hit: &Hit,
    glass: Material,
    tint: Vec3,
    specular_left: &mut u8,
    rng: &mut Rng,
    stats: &mut RayStats,
) -> Glass {
    let Some(face) = hit.face else {
        return Glass::Lost;
    };
    if *specular_left == 0 {
        return Glass::Lost;
    }
    *specular_left -= 1;
    let n = face.normal().as_vec3();
    let d = ray.dir();
    let mut m = microfacet(n, glass.roughness(), rng.next());
    if d.dot(m) >= 0.0 {
        m = n;
    }
    let fresnel = fresnel_dielectric(-d.dot(m), glass.ior());
    let refracted = refract(d, m, glass.ior()).filter(|t| t.dot(n) < 0.0);
    let choice = rng.next();
    let Some(inward) = refracted.filter(|_| choice.x >= fresnel) else {
        let mut out = reflect(d, m);
        if out.dot(n) <= 0.0 {
            out = reflect(d, n);
        }
        return match secondary(ray, hit, out) {
            Some(next) => {
                stats.reflection_rays += 1;
                Glass::Out {
                    ray: next,
                    weight: Vec3::ONE,
                }
            }
            None => Glass::Lost,
        };
    };
    stats.refraction_rays += 1;
    let cell = hit.pos.as_vec3();
    let mut entry = ray.at(hit.t).clamp(cell, cell + 1.0);
    let axis = face.axis();
    entry[axis] = (hit.pos[axis] + i32::from(n[axis] > 0.0)) as f32;
    walk(
        scene,
        materials,
        hit.pos,
        entry,
        inward,
        glass,
        specular_left,
        rng,
        stats,
    )
    .with_tint(tint)
}

impl Glass {
    /// The same outcome with the throughput also times `tint` (the glass's
    /// color, applied once per pass through it).
    fn with_tint(self, tint: Vec3) -> Glass {
        match self {
            Glass::Out { ray, weight } => Glass::Out {
                ray,
                weight: weight * tint,
            },
            Glass::Inside { ray, hit, weight } => Glass::Inside {
                ray,
                hit,
                weight: weight * tint,
            },
            Glass::Lost => Glass::Lost,
        }
    }
}

/// Walks inside glass from `point` (in the voxel `cell`) along the unit
/// `dir` until the path leaves the glass or meets another voxel.
#[allow(clippy::too_many_arguments)] // one caller
fn walk<S: Scene + ?Sized>(
    scene: &S,
    materials: &Materials,
    mut cell: IVec3,
    mut point: Vec3,
    mut dir: Vec3,
    glass: Material,
    specular_left: &mut u8,
    rng: &mut Rng,
    stats: &mut RayStats,
) -> Glass {
    // The path's lookups of the cells it crosses, each beginning where
    // the last one's descent went.
    let mut cells = WalkMemory::new();
    for _ in 0..MAX_GLASS_VOXELS {
        // The face of `cell` the ray leaves through: the nearest plane
        // crossing, the lowest axis on a tie.
        let mut best = (f32::INFINITY, 0usize);
        for axis in 0..3 {
            if dir[axis] != 0.0 {
                let plane = (cell[axis] + i32::from(dir[axis] > 0.0)) as f32;
                let t = ((plane - point[axis]) / dir[axis]).max(0.0);
                if t < best.0 {
                    best = (t, axis);
                }
            }
        }
        let (t, axis) = best;
        if !t.is_finite() {
            return Glass::Lost;
        }
        let positive = dir[axis] > 0.0;
        let plane = (cell[axis] + i32::from(positive)) as f32;
        let c = cell.as_vec3();
        let mut exit = (point + dir * t).clamp(c, c + 1.0);
        exit[axis] = plane;
        let mut next = cell;
        next[axis] += if positive { 1 } else { -1 };
        // What lies beyond the face: the voxel a ray starting just inside
        // `next` meets at its start, if it starts in `next` (by the walk's
        // start rule, at an edge it may start beside it: nothing beyond).
        let step = nudge(plane);
        let mut probe_at = exit;
        probe_at[axis] = plane + if positive { step } else { -step };
        let beyond = Ray::new(probe_at, dir)
            .ok()
            .filter(|probe| Start::of(probe).cell == next)
            .and_then(|_| scene.voxel_at(next, &mut cells));
        if let Some(other) = beyond {
            let m = materials.get(other.material);
            if m.kind() == MaterialKind::Glass && m.transparency() > 0.0 {
                cell = next;
                point = exit;
                continue;
            }
            // Another solid voxel, entered through the face just crossed.
            let Ok(inner) = Ray::new(point, dir) else {
                return Glass::Lost;
            };
            let hit = Hit {
                pos: next,
                face: Some(Face::entered(axis, positive)),
                t,
                ..other
            };
            return Glass::Inside {
                ray: inner,
                hit,
                weight: Vec3::ONE,
            };
        }
        // An interface from glass into empty space.
        if *specular_left == 0 {
            return Glass::Lost;
        }
        *specular_left -= 1;
        let mut n = Vec3::ZERO;
        n[axis] = if positive { -1.0 } else { 1.0 }; // facing back inside
        let mut m = microfacet(n, glass.roughness(), rng.next());
        if dir.dot(m) >= 0.0 {
            m = n;
        }
        let eta = 1.0 / glass.ior();
        let fresnel = fresnel_dielectric(-dir.dot(m), eta);
        let out = refract(dir, m, eta).filter(|o| o.dot(n) < 0.0);
        let choice = rng.next();
        match out.filter(|_| choice.x >= fresnel) {
            Some(out) => {
                let mut origin = exit;
                origin[axis] = plane + if positive { step } else { -step };
                stats.refraction_rays += 1;
                return match Ray::new(origin, out) {
                    Ok(ray) => Glass::Out {
                        ray,
                        weight: Vec3::ONE,
                    },
                    Err(_) => Glass::Lost,
                };
            }
            None => {
                // Reflected back into the glass, total internal reflection
                // included.
                let mut back = reflect(dir, m);
                if back.dot(n) <= 0.0 {
                    back = reflect(dir, n);
                }
                stats.reflection_rays += 1;
                point = exit;
                // Nudge the point back inside the cell on the reflected axis.
                point[axis] = plane + if positive { -step } else { step };
                dir = back.normalize_or_zero();
                if dir == Vec3::ZERO {
                    return Glass::Lost;
                }
            }
        }
    }
    Glass::Lost
}
