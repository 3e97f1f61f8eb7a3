//! The kernels a [`FrameSetup`] runs a frame's job with, one per look, and
//! the one choice between them ([`FrameSetup::dispatch`]): the unshaded look,
//! the debug view of the boxes a walk crosses, the lit look (its kernel
//! in `lit.rs`) and the path tracer for scenes with metal, glass or
//! emitters (its kernel in `render/path/`, feature `path`).

use glam::U8Vec3;

use crate::render::camera::block_pixel;
use crate::render::debug_view::{box_color, enters_near_edge};
#[cfg(feature = "path")]
use crate::render::path::Path;
use crate::render::rays::primary;
#[cfg(feature = "path")]
use crate::render::rounds::PixelSamples;
use crate::render::shade::{pack, sky, FLAT_SKY};
use crate::render::shader::lit::Lit;
use crate::render::shader::{each_lane, lane_rays, trace_rays};
use crate::render::shader::{Block, BlockSamples, FrameSetup, Job, Kernel};
use crate::render::stats::RayStats;
use crate::scene::{Reach, Scene, WalkMemory};

impl FrameSetup<'_, '_> {
    /// Runs `job` with the kernel of this frame's look: the flat look, the
    /// debug view, the path tracer (when the plan path-traces) or the lit
    /// look.
    pub(crate) fn dispatch<J: Job>(&self, job: J) -> J::Output {
        if self.options.flat {
            return job.run(&Flat(self));
        }
        if self.options.debug {
            return job.run(&DebugView(self));
        }
        #[cfg(feature = "path")]
        if let Some(setup) = &self.path {
            return job.run(&Path {
                camera: self.camera,
                setup,
            });
        }
        job.run(&Lit(self))
    }
}

#[cfg(feature = "path")]
impl Kernel for Path<'_, '_> {
    const RESUMES: bool = true;

    #[cfg(feature = "packets")]
    fn in_blocks(&self) -> bool {
        true
    }

    /// The lanes' samples in order ([`Path::resume_block`]): all of them
    /// in one pass, else from each lane's samples so far to the end of
    /// the round.
    #[inline]
    fn block<'s, S: Scene + ?Sized, const N: usize>(
        &self,
        scene: &'s S,
        block: Block,
        memory: &mut WalkMemory<'s>,
        samples: Option<&mut BlockSamples<'_>>,
        put: impl FnMut(usize, u32),
    ) -> RayStats {
        let mut states = [PixelSamples::default(); N];
        let Some(kept) = samples else {
            return self.resume_block(scene, block, memory, &mut states, u32::MAX, put);
        };
        for i in each_lane(block.lanes) {
            states[i] = *kept.lane(i);
        }
        let stats = self.resume_block(scene, block, memory, &mut states, kept.round, put);
        for i in each_lane(block.lanes) {
            *kept.lane(i) = states[i];
        }
        stats
    }
}

/// The unshaded look: each pixel its camera ray's voxel color.
pub(super) struct Flat<'s, 'c, 'm>(pub(super) &'s FrameSetup<'c, 'm>);

impl Kernel for Flat<'_, '_, '_> {
    #[cfg(feature = "packets")]
    fn in_blocks(&self) -> bool {
        true
    }

    /// The lanes' camera rays through their pixels' centers, traced
    /// together, each hit's color.
    #[inline]
    fn block<'s, S: Scene + ?Sized, const N: usize>(
        &self,
        scene: &'s S,
        Block {
            corner,
            lanes,
            clear,
        }: Block,
        memory: &mut WalkMemory<'s>,
        _: Option<&mut BlockSamples<'_>>,
        mut put: impl FnMut(usize, u32),
    ) -> RayStats {
        let rays = lane_rays(self.0.camera, corner, lanes, None);
        let mut hits = [None; N];
        let together = trace_rays(scene, &rays, lanes, Reach::after(clear), memory, &mut hits);
        let mut stats = RayStats {
            primary_rays: u64::from(lanes.count_ones()),
            packet_rays: u64::from(together.count_ones()),
            ..RayStats::default()
        };
        for i in each_lane(lanes) {
            let rgba = hits[i].map_or_else(|| self.0.miss(FLAT_SKY), |h| pack(h.voxel.color));
            stats.primary_hits += u64::from(hits[i].is_some());
            put(i, rgba);
        }
        stats
    }
}

/// The debug view: box edges over black voxels and the sky.
pub(super) struct DebugView<'s, 'c, 'm>(pub(super) &'s FrameSetup<'c, 'm>);

impl Kernel for DebugView<'_, '_, '_> {
    /// Each lane's camera ray walked from the camera, stopped at the
    /// first box it enters near an edge.
    fn block<'s, S: Scene + ?Sized, const N: usize>(
        &self,
        scene: &'s S,
        block: Block,
        _: &mut WalkMemory<'s>,
        _: Option<&mut BlockSamples<'_>>,
        mut put: impl FnMut(usize, u32),
    ) -> RayStats {
        let mut stats = RayStats::default();
        for i in each_lane(block.lanes) {
            let (x, y) = block_pixel(block.corner, i);
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
            stats += primary(traced.hit.as_ref());
            put(i, rgba);
        }
        stats
    }

    fn uses_beam(&self) -> bool {
        false
    }
}
