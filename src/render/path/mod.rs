//! The path tracer: the kernel of frames whose scene has metal, glass or
//! emitters (or that ask for path tracing). It follows each camera sample
//! through the bounces the frame's [`Bounces`] allow, with next-event
//! estimation toward the sun's disk and the emissive voxels at every
//! diffuse hit (`direct.rs`), GGX reflection off metal (`bsdf.rs`) and
//! Fresnel reflection and refraction through glass, walked voxel by voxel
//! inside (`glass.rs`). A pixel takes its samples in order, in one pass
//! or resumed round by round (`pixel.rs`).
//!
//! One kernel serves every set of material kinds: a kind the scene lacks
//! never comes up, and a scene without emitters samples none (a copy per
//! set saved at most 2.3% of a render's instructions: benches/README.md).
//! Every random number is keyed by pixel, sample and path event
//! ([`Rng`]), so a pixel is the same on every thread count, crop, backend
//! and target. Only camera rays start at the tile's clear distance; every
//! later ray walks from its own origin. Camera rays share a walk memory
//! with the neighbouring pixels' camera rays; every later ray begins from
//! the walk that found the hit it leaves (a memory moves where walks
//! begin, never what they hit).
//!
//! Radiance is linear in the units of the face-shaded look (1 is a color's
//! full 255, colors are albedos as they are), so a diffuse voxel under a
//! uniform sky of radiance `L` with nothing above it converges to
//! `color * L`.

pub(crate) mod bsdf;
mod direct;
mod glass;
mod pixel;
mod sobol;

use glam::{IVec3, Vec3};

use crate::geom::Ray;
use crate::material::{MaterialKind, Materials};
use crate::render::adaptive::Adaptive;
use crate::render::camera::Camera;
use crate::render::options::{Background, Bounces, Fog, RenderOptions};
use crate::render::rays::{around, primary, secondary};
use crate::render::sampling::{cosine_hemisphere, pixel_key};
use crate::render::shade::{sky, SKY_HORIZON};
use crate::render::stats::RayStats;
use crate::scene::{Hit, WalkMemory};
use crate::scene::{Reach, Scene};

use bsdf::{glossy, microfacet};
use glass::{through_glass, Glass};
use sobol::scrambled_sobol;

/// The most a sample's radiance may be, per channel: a cap on the rare
/// path that finds a small bright emitter (a firefly), at 16 times white.
const MAX_RADIANCE: f32 = 16.0;

/// The first key stream of path events, apart from the streams of
/// anti-aliasing (0) and ambient occlusion (1 + sample).
const PATH_STREAM: u32 = 0x8000_0000;

/// The random numbers of one camera sample: point `sample` of the pixel's
/// scrambled Sobol sequence for each path event (each bounce, light choice
/// and Fresnel choice is one event, with its own scramble), so samples of
/// one event are stratified, events are independent of each other, and
/// every number depends only on pixel, sample and event.
pub(crate) struct Rng {
    x: u32,
    y: u32,
    sample: u32,
    event: u32,
}

impl Rng {
    /// The next two numbers in `[0, 1)`.
    #[inline]
    pub(crate) fn next(&mut self) -> glam::Vec2 {
        let key = pixel_key(self.x, self.y, PATH_STREAM.wrapping_add(self.event));
        self.event = self.event.wrapping_add(1);
        scrambled_sobol(self.sample, key)
    }
}

/// What the path tracer needs of a frame, computed once per frame.
pub(crate) struct PathSetup<'m> {
    /// One material per palette index.
    pub(crate) materials: &'m Materials,
    /// The emissive voxels next-event estimation samples.
    pub(crate) emitters: &'m [IVec3],
    /// Uniform sky radiance, or the gradient when `None`.
    pub(crate) sky: Option<Vec3>,
    /// Unit direction toward the sun and its strength, when it lights.
    pub(crate) sun: Option<(Vec3, f32)>,
    /// Cosine of the sun's angular radius.
    pub(crate) sun_cos: f32,
    /// Bounce limits.
    pub(crate) bounces: Bounces,
    /// Samples per pixel, without `adaptive`.
    pub(crate) samples: u16,
    /// Adaptive sampling: when to stop each pixel's samples.
    pub(crate) adaptive: Option<Adaptive>,
    /// Distance fog on the first hit.
    pub(crate) fog: Option<Fog>,
    /// What a camera sample that hits nothing shows.
    pub(crate) background: Background,
}

impl<'m> PathSetup<'m> {
    /// The setup of `options` (already sanitized) for `materials`.
    pub(crate) fn new(
        options: &RenderOptions,
        materials: &'m Materials,
        emitters: &'m [IVec3],
    ) -> Self {
        let light = &options.lighting;
        let sun = options
            .sun
            .and_then(|s| s.try_normalize())
            .filter(|_| light.sun_intensity > 0.0)
            .map(|s| (s, light.sun_intensity));
        PathSetup {
            materials,
            emitters,
            sky: light.sky,
            sun,
            sun_cos: libm::cosf(light.sun_radius),
            bounces: light.bounces,
            samples: options.samples,
            adaptive: options.adaptive,
            fog: options.fog,
            background: options.background,
        }
    }

    /// The radiance arriving from the sky along `dir` (the sun's disk is
    /// reached by next-event estimation only).
    #[inline]
    fn environment(&self, dir: Vec3) -> Vec3 {
        self.sky
            .unwrap_or_else(|| sky(dir).as_vec3() * (1.0 / 255.0))
    }
}

/// The path-traced look: one kernel for every set of material kinds.
pub(crate) struct Path<'s, 'm> {
    pub(crate) camera: &'s Camera,
    pub(crate) setup: &'s PathSetup<'m>,
}

impl Path<'_, '_> {
    /// The radiance along one camera ray, whose hit is `hit`.
    fn radiance<'s, S: Scene + ?Sized>(
        &self,
        scene: &'s S,
        camera_ray: &Ray,
        mut hit: Option<Hit>,
        memory: &WalkMemory<'s>,
        rng: &mut Rng,
        stats: &mut RayStats,
    ) -> Vec3 {
        let setup = self.setup;
        let mut ray = *camera_ray;
        // The path's rays each begin from the hit before them, known to the
        // walk that found it: one memory follows the path (the camera's
        // stays with the camera's walks, for the next pixels).
        let path_memory = &mut memory.clone();
        *stats += primary(hit.as_ref());
        let first_t = hit.map(|h| h.t);
        let mut beta = Vec3::ONE;
        let mut sum = Vec3::ZERO;
        // Emitters are counted where a ray meets them unless next-event
        // estimation already did (after a diffuse bounce, with a light list).
        let mut count_emission = true;
        let Bounces {
            diffuse: mut diffuse_left,
            specular: mut specular_left,
        } = setup.bounces;
        loop {
            let Some(h) = hit else {
                sum += beta * setup.environment(ray.dir());
                break;
            };
            let material = setup.materials.get(h.material);
            let albedo = h.voxel.color.as_vec3() * (1.0 / 255.0);
            let choice = rng.next();
            match material.kind() {
                MaterialKind::Emissive if material.emission() > 0.0 => {
                    if count_emission || setup.emitters.is_empty() {
                        sum += beta * albedo * material.emission();
                    }
                    break;
                }
                MaterialKind::Metal if choice.x < material.metalness() => {
                    let Some(face) = h.face else { break };
                    if specular_left == 0 {
                        break;
                    }
                    specular_left -= 1;
                    let n = face.normal().as_vec3();
                    let m = microfacet(n, material.roughness(), rng.next());
                    let Some((dir, weight)) = glossy(ray.dir(), n, m, albedo, material.roughness())
                    else {
                        break;
                    };
                    let Some(next) = secondary(&ray, &h, dir) else {
                        break;
                    };
                    beta *= weight;
                    count_emission = true;
                    stats.reflection_rays += 1;
                    ray = next;
                    hit = scene.trace_with(&ray, Reach::ALL, path_memory, None).hit;
                    continue;
                }
                MaterialKind::Glass if choice.x < material.transparency() => {
                    match through_glass(
                        scene,
                        setup.materials,
                        &ray,
                        &h,
                        material,
                        albedo,
                        &mut specular_left,
                        rng,
                        stats,
                    ) {
                        Glass::Out { ray: next, weight } => {
                            beta *= weight;
                            count_emission = true;
                            ray = next;
                            hit = scene.trace_with(&ray, Reach::ALL, path_memory, None).hit;
                            continue;
                        }
                        Glass::Inside {
                            ray: inner,
                            hit: other,
                            weight,
                        } => {
                            beta *= weight;
                            ray = inner;
                            hit = Some(other);
                            continue;
                        }
                        Glass::Lost => break,
                    }
                }
                _ => {}
            }
            // Diffuse: direct light, then one cosine-weighted bounce.
            let Some(face) = h.face else { break };
            sum += beta
                * albedo
                * direct::light(scene, setup, &ray, &h, face, rng, stats, path_memory);
            if diffuse_left == 0 {
                break;
            }
            diffuse_left -= 1;
            let dir = around(face, cosine_hemisphere(rng.next()));
            let Some(next) = secondary(&ray, &h, dir) else {
                break;
            };
            beta *= albedo;
            count_emission = false;
            stats.reflection_rays += 1;
            ray = next;
            hit = scene.trace_with(&ray, Reach::ALL, path_memory, None).hit;
        }
        match (setup.fog, first_t) {
            (Some(fog), Some(t)) => {
                let f = (t / fog.distance).min(1.0);
                sum + (SKY_HORIZON.as_vec3() * (1.0 / 255.0) - sum) * f
            }
            _ => sum,
        }
    }
}
