//! A frame's kernels: the frame's setup ([`FrameSetup`]: the effects it
//! asked for and the light, resolved once), and the kernel of its look.
//!
//! [`FrameSetup::dispatch`] picks the look's kernel once per frame and runs a
//! job with it; every render is one job (`render/frame.rs`), so every
//! target, crop and pass computes pixels with the same code. This file
//! holds what a frame's pixels need, the traits of jobs and kernels, and
//! what the kernels share to make a block of pixels (its lanes, its
//! camera rays, their tracing); the kernels and the dispatch are in
//! [`kernels`], the lit look's kernel in [`lit`].
//!
//! Scenes whose voxels use metal, glass or emitters (the [`EffectPlan`]
//! says) get the path tracer instead (feature `path`); the face-shaded
//! kernels above are untouched by it, so all-diffuse scenes render as
//! they always did. A kernel tests the frame's effects as it goes: a copy
//! per set of effects saved under 3% of a render's instructions
//! (benches/README.md).

#[cfg(not(feature = "path"))]
use core::marker::PhantomData;
use core::num::NonZeroU32;

use glam::{U8Vec3, Vec3};

use crate::geom::Ray;
#[cfg(feature = "path")]
use crate::material::Materials;
use crate::material::SceneMaterials;
use crate::render::camera::{block_pixel, Camera, BLOCK_WIDTH};
use crate::render::options::{Background, RenderOptions};
#[cfg(feature = "path")]
use crate::render::path::PathSetup;
#[cfg(feature = "path")]
use crate::render::plan::{EffectPlan, Look};
use crate::render::rounds::PixelSamples;
#[cfg(feature = "packets")]
use crate::render::sampling::sample_offset;
use crate::render::sampling::sample_ray;
use crate::render::shade::{face_weights, pack};
use crate::render::stats::RayStats;
#[cfg(feature = "packets")]
use crate::scene::PACKET;
use crate::scene::{Hit, Reach, Scene, WalkMemory};

mod kernels;
mod lit;

pub use lit::occlusion_rays;

/// How wide the debug view's edges are: a fraction of a pixel's footprint
/// each side of the edge.
const EDGE_PIXELS: f32 = 0.75;

/// The table of a path-traced frame whose scene has no materials.
#[cfg(feature = "path")]
static ALL_DIFFUSE: Materials = Materials::all_diffuse();

/// Everything a frame's pixels need, computed once per frame.
pub(crate) struct FrameSetup<'c, 'm> {
    camera: &'c Camera,
    options: RenderOptions,
    /// Brightness out of 256 per face (index [`face_index`]) in full light.
    light: [u16; 7],
    /// Brightness per face when the sun is blocked.
    shadowed: [u16; 7],
    /// Faces the sun shines on (`n . sun > 0`): only they cast shadow rays.
    sunlit: [bool; 7],
    /// Unit direction toward the sun.
    sun: Vec3,
    /// The debug view's edge half-width: at distance 0, and its growth per
    /// unit of distance.
    edge: (f32, f32),
    /// The path tracer's setup, when the plan is to path-trace.
    #[cfg(feature = "path")]
    path: Option<PathSetup<'m>>,
    /// (Without the path tracer, nothing reads the materials.)
    #[cfg(not(feature = "path"))]
    materials: PhantomData<SceneMaterials<'m>>,
}

impl<'c, 'm> FrameSetup<'c, 'm> {
    /// The shader of `options` for `camera`'s frame of a scene with
    /// `materials` (`None`: all diffuse). Settings
    /// [`RenderOptions::validate`] rejects are turned off, never a panic.
    pub(crate) fn new(
        options: &RenderOptions,
        camera: &'c Camera,
        materials: Option<SceneMaterials<'m>>,
    ) -> Self {
        #[cfg(feature = "path")]
        let path = {
            let plan = EffectPlan::new(options, materials);
            (plan.look == Look::Path).then(|| {
                let (table, emitters) =
                    materials.map_or((&ALL_DIFFUSE, &[][..]), |m| (m.table, m.emitters));
                // Voxels of an emitter without emission light nothing: no
                // kernel samples them (the plan counts no lights).
                let emitters = if plan.kinds.emissive { emitters } else { &[] };
                PathSetup::new(&plan.options, table, emitters)
            })
        };
        // (The face-shaded looks shade every material as diffuse.)
        #[cfg(not(feature = "path"))]
        let _ = materials;
        let options = options.sanitized();
        let (light, shadowed, sunlit, sun) = face_weights(options.sun);
        FrameSetup {
            camera,
            options,
            light,
            shadowed,
            sunlit,
            sun,
            edge: if camera.is_orthographic() {
                (EDGE_PIXELS * camera.pixel_spread(), 0.0)
            } else {
                (0.0, EDGE_PIXELS * camera.pixel_spread())
            },
            #[cfg(feature = "path")]
            path,
            #[cfg(not(feature = "path"))]
            materials: PhantomData,
        }
    }
}

/// Something done to a frame's pixels with one kernel: every render is
/// one (`render/frame.rs`).
pub(crate) trait Job {
    /// What the job returns.
    type Output;
    /// Does the job with `kernel`, which computes each pixel.
    fn run<K: Kernel>(self, kernel: &K) -> Self::Output;
}

/// The pixels a kernel makes in one call: the lanes set in `lanes` of
/// the 8x4 block from `corner` (lane `i` at [`block_pixel`]`(corner, i)`;
/// a lone pixel is lane 0 alone). Their camera rays hit nothing before
/// their clear distance `clear` (0 when unknown), so they may start
/// walking there.
#[derive(Clone, Copy)]
pub(crate) struct Block {
    pub(crate) corner: (u32, u32),
    pub(crate) lanes: u32,
    pub(crate) clear: f32,
}

/// The samples a block's pixels keep between rounds of a render in
/// rounds, and the round to take them to: lane `i`'s at
/// `cells[(i / 8) * stride + i % 8]` (the block's rows in the caller's
/// row-major state). Only the path tracer reads them.
#[cfg_attr(not(feature = "path"), allow(dead_code))]
pub(crate) struct BlockSamples<'a> {
    pub(crate) round: u32,
    pub(crate) cells: &'a mut [PixelSamples],
    pub(crate) stride: usize,
}

#[cfg_attr(not(feature = "path"), allow(dead_code))]
impl BlockSamples<'_> {
    /// Lane `i`'s samples so far.
    #[inline]
    pub(crate) fn lane(&mut self, i: usize) -> &mut PixelSamples {
        let (dx, dy) = (i % BLOCK_WIDTH as usize, i / BLOCK_WIDTH as usize);
        &mut self.cells[dy * self.stride + dx]
    }
}

/// Computes the pixels of one look.
pub(crate) trait Kernel: Sync {
    /// The pixels of `block`, handed to `put(i, rgba)`, lowest lane
    /// first, and the rays they traced. They are made in arrays of `N`
    /// lanes: [`crate::PACKET`] for an 8x4 block, 1 for a lone pixel
    /// (lane 0 alone), so that a lone pixel fills no block's arrays. The
    /// walks may begin from what the previous block's left in `memory`;
    /// a pixel is the same for any clear distance it is given and any
    /// memory. `samples` is `None` in one pass (each pixel takes all its
    /// samples); in a render in rounds, which only the path tracer takes
    /// ([`Kernel::RESUMES`]), it holds each lane's samples so far, and a
    /// lane that is done is not handed out.
    fn block<'s, S: Scene + ?Sized, const N: usize>(
        &self,
        scene: &'s S,
        block: Block,
        memory: &mut WalkMemory<'s>,
        samples: Option<&mut BlockSamples<'_>>,
        put: impl FnMut(usize, u32),
    ) -> RayStats;

    /// Whether the kernel's pixels take their samples in rounds (the
    /// path tracer); the face-shaded looks' take theirs in one pass.
    const RESUMES: bool = false;

    /// Whether the kernel's camera rays use a tile's clear distance (the
    /// debug view walks from the camera to show every box).
    fn uses_beam(&self) -> bool {
        true
    }

    /// Whether the kernel traces a block's camera rays together: then
    /// tiles hand it 8x4 blocks where packets pay, else lone pixels.
    #[cfg(feature = "packets")]
    fn in_blocks(&self) -> bool {
        false
    }
}

/// The set bits of `lanes`, lowest first.
#[inline]
pub(crate) fn each_lane(mut lanes: u32) -> impl Iterator<Item = usize> {
    core::iter::from_fn(move || {
        let lane = NonZeroU32::new(lanes)?.trailing_zeros() as usize;
        lanes &= lanes - 1;
        Some(lane)
    })
}

/// The camera rays of the lanes `lanes` of the 8x4 block from `corner`,
/// in arrays of `N` lanes (`PACKET`, or 1 for a lone pixel): lane `i`'s
/// through its pixel ([`block_pixel`]) as [`sample_ray`] makes it for
/// `sample`, bit for bit. The other lanes hold some camera ray, which no
/// one traces. Several lanes are made four at a time.
#[inline(always)]
fn lane_rays<const N: usize>(
    camera: &Camera,
    corner: (u32, u32),
    lanes: u32,
    sample: Option<u32>,
) -> [Ray; N] {
    #[cfg(feature = "packets")]
    if N == PACKET && !lanes.is_power_of_two() {
        return match sample {
            None => camera.block_rays(corner.0, corner.1),
            Some(s) => {
                camera.block_sample_rays(corner, |i| sample_offset(block_pixel(corner, i), s))
            }
        };
    }
    // A lone lane's ray, in every lane.
    let lane = lanes.trailing_zeros() as usize;
    [sample_ray(camera, block_pixel(corner, lane), sample); N]
}

/// The hits of the lanes `lanes` of `rays` over `reach`, into `hits`
/// (other lanes untouched), exactly [`Scene::trace_with`]'s: several by
/// [`Scene::trace_lanes`], a lone lane by its own walk (a packet of one
/// shares nothing). Returns the lanes answered together, without a walk
/// of their own ([`RayStats::packet_rays`] counts them).
#[inline(always)]
pub(crate) fn trace_rays<'s, S: Scene + ?Sized, const N: usize>(
    scene: &'s S,
    rays: &[Ray; N],
    lanes: u32,
    reach: Reach,
    memory: &mut WalkMemory<'s>,
    hits: &mut [Option<Hit>; N],
) -> u32 {
    #[cfg(feature = "packets")]
    if let (Ok(packet), Ok(answers)) = (
        <&[Ray; PACKET]>::try_from(&rays[..]),
        <&mut [Option<Hit>; PACKET]>::try_from(&mut hits[..]),
    ) {
        if !lanes.is_power_of_two() {
            return scene.trace_lanes(packet, lanes, reach, memory, answers);
        }
    }
    for i in each_lane(lanes) {
        hits[i] = scene.trace_with(&rays[i], reach, memory, None).hit;
    }
    0
}

impl FrameSetup<'_, '_> {
    /// The packed pixel of a primary ray that missed: `sky` is the sky's
    /// color in this look.
    #[inline]
    fn miss(&self, sky: U8Vec3) -> u32 {
        match self.options.background {
            Background::Sky => pack(sky),
            Background::Transparent => 0,
            Background::Color(c) => pack(c),
        }
    }

    /// The opaque color a missed sample adds to a pixel's mean (`sky` in
    /// this look); unused for a transparent background.
    #[inline]
    fn miss_color(&self, sky: U8Vec3) -> U8Vec3 {
        match self.options.background {
            Background::Color(c) => c,
            Background::Sky | Background::Transparent => sky,
        }
    }
}
