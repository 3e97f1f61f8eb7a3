//! The kernels a [`Shader`] runs a frame's job with, and the one match
//! that picks them ([`Shader::dispatch`]): the unshaded look, the debug
//! view of the boxes a walk crosses, the lit look with its effects as
//! `const` switches (shadows, occlusion, fog, supersampling), and the path
//! tracer (whose kernel lives in `render/path/`, feature `path`) for scenes
//! with metal, glass or emitters. Without the feature `effect-kernels` the
//! lit look and the path tracer each compile one kernel, every switch on.

use glam::{U8Vec3, UVec3};

use crate::geom::Ray;
use crate::render::debug_view::{box_color, enters_near_edge};
use crate::render::options::Background;
#[cfg(feature = "path")]
use crate::render::path::{Path, PathSetup};
use crate::render::rays::{around, primary, secondary};
#[cfg(feature = "path")]
use crate::render::rounds::PixelSamples;
use crate::render::sampling::{cosine_hemisphere, pixel_key, r2};
use crate::render::shade::{face_index, fog_blend, lit, pack, pack_mean, sky, FLAT_SKY};
use crate::render::shader::{FrameJob, Kernel, Shader};
#[cfg(feature = "path")]
use crate::render::shader::{Resumable, RoundsJob};
use crate::render::stats::RayStats;
use crate::scene::WalkMemory;
use crate::scene::{Hit, Reach, Scene};

impl<'m> Shader<'_, 'm> {
    /// Runs `job` with the kernel compiled for this frame's effects.
    pub(crate) fn dispatch<J: FrameJob>(&self, job: J) -> J::Output {
        let o = &self.options;
        if o.flat {
            return job.run(&Flat(self));
        }
        if o.debug {
            return job.run(&DebugView(self));
        }
        #[cfg(feature = "path")]
        if let Some(setup) = &self.path {
            return self.dispatch_path(setup, job);
        }
        if !cfg!(feature = "effect-kernels") {
            return job.run(&Lit::<true, true, true, true, false>(self));
        }
        let set = (
            o.shadows,
            o.occlusion.is_some(),
            o.fog.is_some(),
            o.samples > 1,
        );
        macro_rules! lit_kernels {
            ($(($sh:literal, $ao:literal, $fog:literal, $aa:literal)),* $(,)?) => {
                match set {
                    $(($sh, $ao, $fog, $aa) => job.run(&Lit::<$sh, $ao, $fog, $aa, true>(self)),)*
                }
            };
        }
        lit_kernels!(
            (false, false, false, false),
            (false, false, false, true),
            (false, false, true, false),
            (false, false, true, true),
            (false, true, false, false),
            (false, true, false, true),
            (false, true, true, false),
            (false, true, true, true),
            (true, false, false, false),
            (true, false, false, true),
            (true, false, true, false),
            (true, false, true, true),
            (true, true, false, false),
            (true, true, false, true),
            (true, true, true, false),
            (true, true, true, true),
        )
    }

    /// Runs `job` with the path tracer when the frame is path-traced;
    /// hands the job back
    /// otherwise (a face-shaded frame is one pass: its caller renders it
    /// as usual, and no round code is compiled for its kernels). One
    /// kernel with every material kind on serves every scene (the kinds
    /// a scene lacks never match: the same pixels), so the round code is
    /// compiled once, not once per set of kinds (a megabyte of the CLI's
    /// binary, for a mode a user opts into).
    #[cfg(feature = "path")]
    pub(crate) fn dispatch_rounds<J: RoundsJob>(&self, job: J) -> Result<J::Output, J> {
        if let Some(setup) = &self.path {
            let camera = self.camera;
            return Ok(job.run(&Path::<true, true, true> { camera, setup }));
        }
        Err(job)
    }

    /// Runs `job` with the path tracer compiled for the material kinds
    /// the scene holds.
    #[cfg(feature = "path")]
    fn dispatch_path<J: FrameJob>(&self, setup: &PathSetup<'m>, job: J) -> J::Output {
        let camera = self.camera;
        if !cfg!(feature = "effect-kernels") {
            // The kinds a scene lacks never match: the same pixels.
            return job.run(&Path::<true, true, true> { camera, setup });
        }
        let kinds = setup.materials.kinds();
        macro_rules! path_kernels {
            ($(($g:literal, $m:literal, $e:literal)),* $(,)?) => {
                match (kinds.glass, kinds.metal, kinds.emissive) {
                    $(($g, $m, $e) => job.run(&Path::<$g, $m, $e> { camera, setup }),)*
                }
            };
        }
        path_kernels!(
            (false, false, false),
            (false, false, true),
            (false, true, false),
            (false, true, true),
            (true, false, false),
            (true, false, true),
            (true, true, false),
            (true, true, true),
        )
    }
}

#[cfg(feature = "path")]
impl<const GLASS: bool, const METAL: bool, const EMIT: bool> Kernel
    for Path<'_, '_, GLASS, METAL, EMIT>
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
        self.trace_pixel(scene, x, y, t_start, memory)
    }
}

#[cfg(feature = "path")]
impl<const GLASS: bool, const METAL: bool, const EMIT: bool> Resumable
    for Path<'_, '_, GLASS, METAL, EMIT>
{
    #[inline]
    fn resume<'s, S: Scene + ?Sized>(
        &self,
        scene: &'s S,
        x: u32,
        y: u32,
        t_start: f32,
        memory: &mut WalkMemory<'s>,
        pixel: &mut PixelSamples,
        round: u32,
    ) -> (Option<u32>, RayStats) {
        self.resume_pixel(scene, (x, y), t_start, memory, pixel, round)
    }
}

/// The unshaded look.
pub(super) struct Flat<'s, 'c, 'm>(pub(super) &'s Shader<'c, 'm>);

impl Kernel for Flat<'_, '_, '_> {
    #[inline]
    fn pixel<'s, S: Scene + ?Sized>(
        &self,
        scene: &'s S,
        x: u32,
        y: u32,
        t_start: f32,
        memory: &mut WalkMemory<'s>,
    ) -> (u32, RayStats) {
        let ray = self.0.camera.get_ray(x, y);
        self.ray_pixel(scene, &ray, (x, y), t_start, memory)
    }

    fn one_ray(&self) -> bool {
        true
    }

    #[inline]
    fn shade<'s, S: Scene + ?Sized>(
        &self,
        _: &'s S,
        _: &Ray,
        hit: Option<Hit>,
        _: (u32, u32),
        _: &mut WalkMemory<'s>,
    ) -> (u32, RayStats) {
        let rgba = hit.map_or_else(|| self.0.miss(FLAT_SKY), |h| pack(h.voxel.color));
        (rgba, primary(hit.as_ref()))
    }
}

/// The debug view: box edges over black voxels and the sky.
pub(super) struct DebugView<'s, 'c, 'm>(pub(super) &'s Shader<'c, 'm>);

impl Kernel for DebugView<'_, '_, '_> {
    fn pixel<'s, S: Scene + ?Sized>(
        &self,
        scene: &'s S,
        x: u32,
        y: u32,
        _: f32,
        _: &mut WalkMemory<'s>,
    ) -> (u32, RayStats) {
        let ray = self.0.camera.get_ray(x, y);
        let mut edge = None;
        let traced = scene.trace_visiting(&ray, &mut |cube| {
            if enters_near_edge(&ray, cube, self.0.edge.0, self.0.edge.1) {
                edge = Some(box_color(cube));
            }
            edge.is_none()
        });
        let rgba = match (edge, traced.hit) {
            (Some(color), _) => pack(color),
            (None, Some(_)) => pack(U8Vec3::ZERO),
            (None, None) => self.0.miss(sky(ray.dir())),
        };
        // A ray stopped at an edge still counts as one primary ray.
        (rgba, primary(traced.hit.as_ref()))
    }

    fn uses_beam(&self) -> bool {
        false
    }
}

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
        let camera = self.0.camera;
        if self.one_ray() {
            let ray = camera.get_ray(x, y);
            return self.ray_pixel(scene, &ray, (x, y), t_start, memory);
        }
        let samples = u32::from(self.0.options.samples);
        let transparent = self.0.options.background == Background::Transparent;
        let key = pixel_key(x, y, 0);
        let mut sum = UVec3::ZERO;
        let mut stats = RayStats::default();
        for s in 0..samples {
            let offset = r2(s, key);
            let ray = camera.get_ray_at(x as f32 + offset.x, y as f32 + offset.y);
            let (color, rays) = self.sample(scene, &ray, t_start, x, y, s, memory);
            if rays.primary_hits > 0 {
                sum += color.as_uvec3();
            } else if !transparent {
                sum += self.0.miss_color(color).as_uvec3();
            }
            stats += rays;
        }
        // The rounded mean, in integers.
        let mean_of = |n: u32| ((sum + UVec3::splat(n / 2)) / n).as_u8vec3();
        let hits = stats.primary_hits as u32;
        (pack_mean(samples, hits, transparent, mean_of), stats)
    }

    /// One sample per pixel (occlusion and fog test their settings
    /// anyway).
    fn one_ray(&self) -> bool {
        !(AA && (EXACT || self.0.options.samples > 1))
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
        let (color, stats) = self.shade_sample(scene, ray, hit, x, y, 0, memory);
        if stats.primary_hits == 0 {
            return (self.0.miss(color), stats);
        }
        (pack(color), stats)
    }
}

impl<const SHADOWS: bool, const AO: bool, const FOG: bool, const AA: bool, const EXACT: bool>
    Lit<'_, '_, '_, SHADOWS, AO, FOG, AA, EXACT>
{
    /// One camera sample, its walk starting at `t_start`: its color (the
    /// sky's when it misses: `primary_hits` is then 0) and rays.
    #[allow(clippy::too_many_arguments)]
    #[inline]
    fn sample<'s, S: Scene + ?Sized>(
        &self,
        scene: &'s S,
        ray: &Ray,
        t_start: f32,
        x: u32,
        y: u32,
        sample: u32,
        memory: &mut WalkMemory<'s>,
    ) -> (U8Vec3, RayStats) {
        let hit = scene
            .trace_with(ray, Reach::after(t_start), memory, None)
            .hit;
        self.shade_sample(scene, ray, hit, x, y, sample, memory)
    }

    /// [`Lit::sample`] of the camera ray `ray` whose hit is `hit`.
    #[allow(clippy::too_many_arguments)]
    #[inline]
    fn shade_sample<'s, S: Scene + ?Sized>(
        &self,
        scene: &'s S,
        ray: &Ray,
        hit: Option<Hit>,
        x: u32,
        y: u32,
        sample: u32,
        memory: &mut WalkMemory<'s>,
    ) -> (U8Vec3, RayStats) {
        let shader = self.0;
        let mut stats = primary(hit.as_ref());
        let Some(hit) = hit else {
            return (sky(ray.dir()), stats);
        };
        let face = face_index(hit.face);
        let mut light = u32::from(shader.light[face]);
        if SHADOWS && (EXACT || shader.options.shadows) && shader.sunlit[face] {
            stats.shadow_rays += 1;
            if let Some(shadow) = secondary(ray, &hit, shader.sun) {
                let blocker = scene
                    .trace_with(
                        &shadow,
                        Reach::ALL,
                        // Begun from the hit's node, known to the walk
                        // that found it (a copy: the next pixel's primary
                        // ray begins from that hit too).
                        &mut memory.clone(),
                        None,
                    )
                    .hit;
                if blocker.is_some() {
                    light = u32::from(shader.shadowed[face]);
                }
            }
        }
        if AO {
            if let (Some(entered), Some(ao)) = (hit.face, shader.options.occlusion) {
                let rays = u32::from(ao.rays);
                let key = pixel_key(x, y, 1 + sample);
                let mut open = 0;
                for j in 0..rays {
                    let dir = around(entered, cosine_hemisphere(r2(j, key)));
                    let blocked = secondary(ray, &hit, dir)
                        .and_then(|r| {
                            scene
                                .trace_with(
                                    &r,
                                    Reach::within(ao.distance),
                                    &mut memory.clone(),
                                    None,
                                )
                                .hit
                        })
                        .is_some();
                    open += u32::from(!blocked);
                }
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
