//! The lit look: face light, and the effects a frame asks for as `const`
//! switches (shadows, occlusion, fog, supersampling). A packet of its
//! camera rays sends its hits' shadow and occlusion rays in packets too
//! (`packets.rs`).

use glam::{U8Vec3, UVec3, Vec2};

use crate::geom::{Face, Ray};
#[cfg(feature = "packets")]
use crate::render::camera::{block_pixel, Camera};
use crate::render::options::Background;
use crate::render::rays::{around, primary, secondary};
use crate::render::sampling::{cosine_hemisphere, pixel_key, r2};
use crate::render::shade::{face_index, fog_blend, lit, pack, pack_mean, sky};
use crate::render::shader::{Kernel, Shader};
use crate::render::stats::RayStats;
#[cfg(feature = "packets")]
use crate::scene::PACKET;
use crate::scene::{Hit, Reach, Scene, WalkMemory};

#[cfg(feature = "packets")]
mod packets;

/// The lit look with the chosen effects: shadows, ambient occlusion, fog and
/// several samples per pixel, each compiled in only when on.
///
/// `EXACT`: the frame asks for exactly the effects compiled in (the
/// dispatch of `effect-kernels` builds). Otherwise an effect runs when it
/// is compiled in and the frame asks for it, so the kernel with every
/// switch on gives any frame its pixels: builds without `effect-kernels`
/// run every frame with that one.
pub(super) struct Lit<
    's,
    'c,
    'm,
    const SHADOWS: bool,
    const AO: bool,
    const FOG: bool,
    const AA: bool,
    const EXACT: bool,
>(pub(super) &'s Shader<'c, 'm>);

impl<const SHADOWS: bool, const AO: bool, const FOG: bool, const AA: bool, const EXACT: bool> Kernel
    for Lit<'_, '_, '_, SHADOWS, AO, FOG, AA, EXACT>
{
    #[inline]
    fn pixel<'s, S: Scene + ?Sized>(
        &self,
        scene: &'s S,
        x: u32,
        y: u32,
        t_start: f32,
        memory: &mut WalkMemory<'s>,
    ) -> (u32, RayStats) {
        if self.one_ray() {
            let ray = self.0.camera.get_ray(x, y);
            return self.ray_pixel(scene, &ray, (x, y), t_start, memory);
        }
        let mut mean = Mean::default();
        for s in 0..self.samples() {
            let offset = sample_offset((x, y), s);
            let ray = self
                .0
                .camera
                .get_ray_at(x as f32 + offset.x, y as f32 + offset.y);
            let hit = scene
                .trace_with(&ray, Reach::after(t_start), memory, None)
                .hit;
            let shaded = self.shade_sample(scene, &ray, hit, (x, y, s), memory, Found::default());
            mean.add(shaded, self.0);
        }
        mean.pixel(self.samples(), self.0)
    }

    #[cfg(feature = "packets")]
    fn in_blocks(&self) -> bool {
        true
    }

    #[inline]
    fn shade<'s, S: Scene + ?Sized>(
        &self,
        scene: &'s S,
        ray: &Ray,
        hit: Option<Hit>,
        (x, y): (u32, u32),
        memory: &mut WalkMemory<'s>,
    ) -> (u32, RayStats) {
        let shaded = self.shade_sample(scene, ray, hit, (x, y, 0), memory, Found::default());
        self.packed(shaded)
    }

    /// Sample by sample: the block's camera rays as a packet, then their
    /// hits' shadow and occlusion rays in packets
    /// ([`Lit::secondary_in_packets`]), then each lane shaded.
    #[cfg(feature = "packets")]
    #[inline]
    fn block<'s, S: Scene + ?Sized>(
        &self,
        scene: &'s S,
        camera: &Camera,
        corner: (u32, u32),
        t_start: f32,
        memory: &mut WalkMemory<'s>,
        mut put: impl FnMut(usize, u32, RayStats),
    ) {
        let at = |i| block_pixel(corner, i);
        let one_ray = self.one_ray();
        let mut means = [Mean::default(); PACKET];
        for s in 0..self.samples() {
            let rays = if one_ray {
                camera.block_rays(corner.0, corner.1)
            } else {
                camera.block_sample_rays(corner, |i| sample_offset(at(i), s))
            };
            let mut hits = [None; PACKET];
            scene.trace_lanes(&rays, u32::MAX, Reach::after(t_start), memory, &mut hits);
            let found = self.secondary_in_packets(scene, (&rays, &hits), s, &at, memory);
            for (i, (ray, &hit)) in rays.iter().zip(&hits).enumerate() {
                let (x, y) = at(i);
                let shaded = self.shade_sample(scene, ray, hit, (x, y, s), memory, found[i]);
                if one_ray {
                    let (rgba, rays) = self.packed(shaded);
                    put(i, rgba, rays);
                } else {
                    means[i].add(shaded, self.0);
                }
            }
        }
        if !one_ray {
            for (i, mean) in means.iter().enumerate() {
                let (rgba, rays) = mean.pixel(self.samples(), self.0);
                put(i, rgba, rays);
            }
        }
    }
}

/// A pixel's samples so far: their colors summed (a miss as the
/// background's, none for a transparent one) and their rays.
#[derive(Clone, Copy, Default)]
struct Mean {
    sum: UVec3,
    stats: RayStats,
}

impl Mean {
    /// Adds a sample: its color and rays ([`Lit::shade_sample`]).
    #[inline]
    fn add(&mut self, (color, rays): (U8Vec3, RayStats), shader: &Shader) {
        if rays.primary_hits > 0 {
            self.sum += color.as_uvec3();
        } else if shader.options.background != Background::Transparent {
            self.sum += shader.miss_color(color).as_uvec3();
        }
        self.stats += rays;
    }

    /// The pixel of `samples` samples: their rounded mean, in integers,
    /// packed, and their rays.
    #[inline]
    fn pixel(&self, samples: u32, shader: &Shader) -> (u32, RayStats) {
        let transparent = shader.options.background == Background::Transparent;
        let mean_of = |n: u32| ((self.sum + UVec3::splat(n / 2)) / n).as_u8vec3();
        let hits = self.stats.primary_hits as u32;
        (pack_mean(samples, hits, transparent, mean_of), self.stats)
    }
}

/// What a hit's secondary rays found, where the caller traced them (in
/// packets); `None` leaves them to [`Lit::shade_sample`].
#[derive(Clone, Copy, Default)]
pub(super) struct Found {
    /// Whether the shadow ray hits something.
    blocked: Option<bool>,
    /// How many occlusion rays meet nothing within their reach.
    open: Option<u32>,
}

impl<const SHADOWS: bool, const AO: bool, const FOG: bool, const AA: bool, const EXACT: bool>
    Lit<'_, '_, '_, SHADOWS, AO, FOG, AA, EXACT>
{
    /// One sample per pixel (occlusion and fog test their settings
    /// anyway).
    #[inline]
    fn one_ray(&self) -> bool {
        !(AA && (EXACT || self.0.options.samples > 1))
    }

    /// Camera samples per pixel.
    #[inline]
    fn samples(&self) -> u32 {
        if self.one_ray() {
            1
        } else {
            u32::from(self.0.options.samples)
        }
    }

    /// Whether the frame's hits send shadow rays.
    #[inline]
    fn shadows(&self) -> bool {
        SHADOWS && (EXACT || self.0.options.shadows)
    }

    /// The shadow ray of the camera ray `ray`'s hit `hit`, toward the sun:
    /// `None` when the frame has no shadows, the face is turned from the
    /// sun, or the hit has no face.
    #[inline]
    fn shadow_ray(&self, ray: &Ray, hit: &Hit) -> Option<Ray> {
        let shader = self.0;
        let sunlit = self.shadows() && shader.sunlit[face_index(hit.face)];
        sunlit.then(|| secondary(ray, hit, shader.sun)).flatten()
    }

    /// A one-ray pixel's packed color from its shaded sample.
    #[inline]
    fn packed(&self, (color, stats): (U8Vec3, RayStats)) -> (u32, RayStats) {
        if stats.primary_hits == 0 {
            return (self.0.miss(color), stats);
        }
        (pack(color), stats)
    }

    /// Sample `sample` of pixel `(x, y)`, of the camera ray
    /// `ray` whose hit is `hit`; its secondary rays traced here, but for
    /// what the caller `found`.
    #[inline]
    fn shade_sample<'s, S: Scene + ?Sized>(
        &self,
        scene: &'s S,
        ray: &Ray,
        hit: Option<Hit>,
        (x, y, sample): (u32, u32, u32),
        memory: &mut WalkMemory<'s>,
        found: Found,
    ) -> (U8Vec3, RayStats) {
        let shader = self.0;
        let mut stats = primary(hit.as_ref());
        let Some(hit) = hit else {
            return (sky(ray.dir()), stats);
        };
        let face = face_index(hit.face);
        let mut light = u32::from(shader.light[face]);
        if self.shadows() && shader.sunlit[face] {
            stats.shadow_rays += 1;
            let blocked = found.blocked.unwrap_or_else(|| {
                self.shadow_ray(ray, &hit).is_some_and(|shadow| {
                    scene
                        .trace_with(
                            &shadow,
                            Reach::ALL,
                            // Begun from the hit's node, known to the walk
                            // that found it (a copy: the next pixel's
                            // primary ray begins from that hit too).
                            &mut memory.clone(),
                            None,
                        )
                        .hit
                        .is_some()
                })
            });
            if blocked {
                light = u32::from(shader.shadowed[face]);
            }
        }
        if AO {
            if let (Some(entered), Some(ao)) = (hit.face, shader.options.occlusion) {
                let rays = u32::from(ao.rays);
                let open = found.open.unwrap_or_else(|| {
                    let blocked = |j| {
                        occlusion_ray(ray, &hit, entered, (x, y, sample), j).is_some_and(|r| {
                            let memory = &mut memory.clone();
                            let reach = Reach::within(ao.distance);
                            scene.trace_with(&r, reach, memory, None).hit.is_some()
                        })
                    };
                    (0..rays).map(|j| u32::from(!blocked(j))).sum()
                });
                stats.ao_rays += u64::from(rays);
                light = light * open / rays;
            }
        }
        let mut color = lit(hit.voxel.color, light);
        if FOG {
            if let Some(fog) = shader.options.fog {
                color = fog_blend(color, hit.t, fog.distance);
            }
        }
        (color, stats)
    }
}

/// The occlusion ray `j` of sample `sample` of pixel `(x, y)`, from the
/// hit `hit` of its camera ray `ray`, entered through `entered`: `None`
/// when no ray can leave the face (it then counts as open).
#[inline]
pub(super) fn occlusion_ray(
    ray: &Ray,
    hit: &Hit,
    entered: Face,
    (x, y, sample): (u32, u32, u32),
    j: u32,
) -> Option<Ray> {
    let key = pixel_key(x, y, 1 + sample);
    let dir = around(entered, cosine_hemisphere(r2(j, key)));
    secondary(ray, hit, dir)
}

/// Where sample `s` of pixel `(x, y)` goes through the pixel, in a frame
/// of several samples per pixel: a point of the pixel's own sequence.
#[inline]
fn sample_offset((x, y): (u32, u32), s: u32) -> Vec2 {
    r2(s, pixel_key(x, y, 0))
}
