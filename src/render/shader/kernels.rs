//! The kernels a [`Shader`] runs a frame's job with, and the one match
//! that picks them ([`Shader::dispatch`]): the unshaded look, the debug
//! view of the boxes a walk crosses, the lit look with its effects as
//! `const` switches (shadows, occlusion, fog, supersampling; its kernel
//! lives in `lit.rs`), and the path
//! tracer (whose kernel lives in `render/path/`, feature `path`) for scenes
//! with metal, glass or emitters. Without the feature `effect-kernels` the
//! lit look and the path tracer each compile one kernel, every switch on.

use glam::U8Vec3;

use crate::render::debug_view::{box_color, enters_near_edge};
#[cfg(feature = "path")]
use crate::render::path::{Path, PathSetup};
use crate::render::rays::primary;
#[cfg(feature = "path")]
use crate::render::rounds::PixelSamples;
use crate::render::shade::{pack, sky, FLAT_SKY};
use crate::render::shader::lit::Lit;
use crate::render::shader::{each_lane, lane_rays, trace_rays, LANES};
use crate::render::shader::{FrameJob, Kernel, Shader};
#[cfg(feature = "path")]
use crate::render::shader::{Resumable, RoundsJob};
use crate::render::stats::RayStats;
use crate::scene::{Hit, Reach, Scene, WalkMemory};

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

/// The unshaded look: each pixel its camera ray's voxel color.
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
        // (Too cheap a pixel to fill a block's arrays for.)
        let (ray, reach) = (self.0.camera.get_ray(x, y), Reach::after(t_start));
        self.color(scene.trace_with(&ray, reach, memory, None).hit)
    }

    #[cfg(feature = "packets")]
    fn in_blocks(&self) -> bool {
        true
    }

    /// The lanes' camera rays through their pixels' centers, traced
    /// together, each hit's color.
    #[inline]
    fn block<'s, S: Scene + ?Sized>(
        &self,
        scene: &'s S,
        corner: (u32, u32),
        lanes: u32,
        t_start: f32,
        memory: &mut WalkMemory<'s>,
        mut put: impl FnMut(usize, u32, RayStats),
    ) {
        let rays = lane_rays(self.0.camera, corner, lanes, None);
        let (reach, mut hits) = (Reach::after(t_start), [None; LANES]);
        trace_rays(scene, &rays, lanes, reach, memory, &mut hits);
        for i in each_lane(lanes) {
            let (rgba, rays) = self.color(hits[i]);
            put(i, rgba, rays);
        }
    }
}

impl Flat<'_, '_, '_> {
    /// The packed pixel of a camera ray that found `hit`, and its ray.
    #[inline]
    fn color(&self, hit: Option<Hit>) -> (u32, RayStats) {
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
