//! The lit look: face light, and the effects a frame asks for (shadows,
//! occlusion, fog, supersampling).
//!
//! One route makes every pixel, [`Lit`]'s [`Kernel::block`]: the lanes
//! of an 8x4 block a mask picks (a lone pixel is lane 0 alone), sample by
//! sample their camera, shadow and occlusion rays, each kind traced for
//! all the lanes at once (in packets where the storage walks them,
//! occlusion rays by octant in `packets.rs`), then each lane shaded.

use glam::{U8Vec3, UVec3};

use crate::geom::{Face, Ray};
use crate::render::camera::block_pixel;
use crate::render::options::{Background, Occlusion};
use crate::render::rays::{around, secondary};
use crate::render::sampling::{cosine_hemisphere, pixel_key, r2};
use crate::render::shade::{face_index, fog_blend, lit, pack, pack_mean, sky};
use crate::render::shader::{
    each_lane, lane_rays, trace_rays, Block, BlockSamples, FrameSetup, Kernel,
};
use crate::render::stats::RayStats;
use crate::scene::{Hit, Reach, Scene, WalkMemory};

#[cfg(feature = "packets")]
mod packets;

#[cfg(feature = "packets")]
use packets::{close, put, Bin};

/// The lit look with the effects the frame asks for: shadows, ambient
/// occlusion, fog and several samples per pixel, each tested once per
/// sample (a copy of the kernel per set of effects saved under 3% of a
/// render's instructions: benches/README.md).
pub(super) struct Lit<'s, 'c, 'm>(pub(super) &'s FrameSetup<'c, 'm>);

impl Kernel for Lit<'_, '_, '_> {
    #[cfg(feature = "packets")]
    fn in_blocks(&self) -> bool {
        true
    }

    /// Sample by sample: the lanes' camera rays, then their hits' shadow
    /// rays ([`Lit::shadowed`]) and occlusion rays ([`Lit::open`]), then
    /// each lane shaded ([`Lit::shade`]); a pixel of one sample is packed
    /// as it is shaded, one of several is their mean ([`Mean`]).
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
        let (one_ray, reach) = (self.one_ray(), Reach::after(clear));
        let mut stats = RayStats::default();
        // A pixel of several samples is their mean, summed as they come.
        let mut means = (!one_ray).then(|| [Mean::default(); N]);
        for s in 0..self.samples() {
            let rays = lane_rays(self.0.camera, corner, lanes, (!one_ray).then_some(s));
            let mut hits = [None; N];
            let together = trace_rays(scene, &rays, lanes, reach, memory, &mut hits);
            let (blocked, shadows_together) = self.shadowed(scene, (&rays, &hits), lanes, memory);
            let (open, open_together) = match self.0.options.occlusion {
                Some(ao) => self.open(scene, ao, (corner, s), (&rays, &hits), lanes, memory),
                None => ([0; N], [0; N]),
            };
            stats.primary_rays += u64::from(lanes.count_ones());
            let paired = together.count_ones() + shadows_together.count_ones();
            stats.packet_rays += u64::from(paired);
            for i in each_lane(lanes) {
                let open = (open[i], open_together[i]);
                let blocked = blocked >> i & 1 != 0;
                let color = self.shade(&rays[i], hits[i].as_ref(), blocked, open, &mut stats);
                let hit = hits[i].is_some();
                match &mut means {
                    None => put(i, self.packed(color, hit)),
                    Some(means) => means[i].add(color, hit, self.0),
                }
            }
        }
        if let Some(means) = &means {
            for i in each_lane(lanes) {
                put(i, means[i].pixel(self.samples(), self.0));
            }
        }
        stats
    }
}

/// A pixel's samples so far: their colors summed (a miss as the
/// background's, none for a transparent one) and how many hit.
#[derive(Clone, Copy, Default)]
struct Mean {
    sum: UVec3,
    hits: u32,
}

impl Mean {
    /// Adds a sample: its color ([`Lit::shade`]) and whether it hit.
    #[inline]
    fn add(&mut self, color: U8Vec3, hit: bool, shader: &FrameSetup) {
        if hit {
            self.sum += color.as_uvec3();
            self.hits += 1;
        } else if shader.options.background != Background::Transparent {
            self.sum += shader.miss_color(color).as_uvec3();
        }
    }

    /// The pixel of `samples` samples: their rounded mean, in integers,
    /// packed.
    #[inline]
    fn pixel(&self, samples: u32, shader: &FrameSetup) -> u32 {
        let transparent = shader.options.background == Background::Transparent;
        let mean_of = |n: u32| ((self.sum + UVec3::splat(n / 2)) / n).as_u8vec3();
        pack_mean(samples, self.hits, transparent, mean_of)
    }
}

impl Lit<'_, '_, '_> {
    /// One sample per pixel (occlusion and fog test their settings
    /// anyway).
    #[inline]
    fn one_ray(&self) -> bool {
        self.0.options.samples <= 1
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
        self.0.options.shadows
    }

    /// The lanes of `lanes` whose hit (`hits[i]`, of the camera ray
    /// `rays[i]`) sends a shadow ray toward the sun that meets a voxel. A
    /// hit sends one when the frame has shadows and its face is turned to
    /// the sun and known ([`secondary`]). The rays walk from a copy of the
    /// camera rays' memory (the next pixels' camera rays begin from it):
    /// several together ([`trace_rays`]), a lone lane's alone. Also
    /// returns the lanes whose shadow ray was answered together.
    #[inline]
    fn shadowed<'s, S: Scene + ?Sized, const N: usize>(
        &self,
        scene: &'s S,
        (rays, hits): (&[Ray; N], &[Option<Hit>; N]),
        lanes: u32,
        memory: &WalkMemory<'s>,
    ) -> (u32, u32) {
        if !self.shadows() {
            return (0, 0);
        }
        let shader = self.0;
        let sunlit = |hit: &&Hit| shader.sunlit[face_index(hit.face)];
        let shadow = |i: usize| secondary(&rays[i], hits[i].as_ref().filter(sunlit)?, shader.sun);
        let memory = &mut memory.clone();
        if lanes.is_power_of_two() {
            // A lone lane: no packet to fill.
            let i = lanes.trailing_zeros() as usize;
            let blocker =
                shadow(i).and_then(|ray| scene.trace_with(&ray, Reach::ALL, memory, None).hit);
            return (u32::from(blocker.is_some()) << i, 0);
        }
        let (mut shadows, mut sent) = (*rays, 0u32);
        for i in each_lane(lanes) {
            if let Some(ray) = shadow(i) {
                shadows[i] = ray;
                sent |= 1 << i;
            }
        }
        let mut blockers = [None; N];
        let together = trace_rays(scene, &shadows, sent, Reach::ALL, memory, &mut blockers);
        let blocked = |i: usize| u32::from(blockers[i].is_some()) << i;
        (
            each_lane(sent).fold(0, |mask, i| mask | blocked(i)),
            together,
        )
    }

    /// How many occlusion rays of each lane's hit (`hits[i]`, of the camera
    /// ray `rays[i]`, sample `sample` of lane `i` of the block from
    /// `corner`) meet nothing within the reach of `ao`, one that cannot
    /// leave the face counted open (0 for a lane without a face): in
    /// packets by octant for close hits (`packets.rs`), else alone from a
    /// copy of the camera ray's memory. Also returns how many of each
    /// lane's rays were answered together.
    #[inline]
    fn open<'s, S: Scene + ?Sized, const N: usize>(
        &self,
        scene: &'s S,
        ao: Occlusion,
        (corner, sample): ((u32, u32), u32),
        (rays, hits): (&[Ray; N], &[Option<Hit>; N]),
        lanes: u32,
        memory: &WalkMemory<'s>,
    ) -> ([u32; N], [u32; N]) {
        let mut open = [0u32; N];
        // Rays answered together: only packets answer any.
        #[cfg_attr(not(feature = "packets"), allow(unused_mut))]
        let mut together = [0u32; N];
        let reach = Reach::within(ao.distance);
        #[cfg(feature = "packets")]
        let mut bins =
            (!lanes.is_power_of_two() && close(hits, ao.distance)).then(|| Bin::octants(rays[0]));
        for i in each_lane(lanes) {
            let Some((hit, entered)) = hits[i].as_ref().and_then(|h| Some((h, h.face?))) else {
                continue;
            };
            let (x, y) = block_pixel(corner, i);
            for j in 0..u32::from(ao.rays) {
                let Some(ray) = occlusion_ray(&rays[i], hit, entered, (x, y, sample), j) else {
                    open[i] += 1;
                    continue;
                };
                #[cfg(feature = "packets")]
                if let Some(bins) = &mut bins {
                    if let Some(full) = put(bins, ray, i) {
                        full.trace(scene, reach, memory, (&mut open, &mut together));
                    }
                    continue;
                }
                let hit = scene.trace_with(&ray, reach, &mut memory.clone(), None).hit;
                open[i] += u32::from(hit.is_none());
            }
        }
        #[cfg(feature = "packets")]
        for bin in bins.iter_mut().flatten() {
            bin.trace(scene, reach, memory, (&mut open, &mut together));
        }
        (open, together)
    }

    /// A one-ray pixel's packed color from its shaded sample, which hit
    /// a voxel or not.
    #[inline]
    fn packed(&self, color: U8Vec3, hit: bool) -> u32 {
        if hit {
            pack(color)
        } else {
            self.0.miss(color)
        }
    }

    /// A sample's color: the camera ray `ray`'s hit `hit` in its face's
    /// light, in shadow where its shadow ray was `blocked`
    /// ([`Lit::shadowed`]), dimmed to the share of its occlusion rays that
    /// are open (`open`: how many, and how many were answered together,
    /// [`Lit::open`]), fogged by its distance; a miss is the sky in the
    /// ray's direction. Its hit and secondary rays are counted in `stats`.
    #[inline]
    fn shade(
        &self,
        ray: &Ray,
        hit: Option<&Hit>,
        blocked: bool,
        (open, together): (u32, u32),
        stats: &mut RayStats,
    ) -> U8Vec3 {
        let shader = self.0;
        let Some(hit) = hit else {
            return sky(ray.dir());
        };
        stats.primary_hits += 1;
        let face = face_index(hit.face);
        let mut light = u32::from(shader.light[face]);
        if self.shadows() && shader.sunlit[face] {
            stats.shadow_rays += 1;
            if blocked {
                light = u32::from(shader.shadowed[face]);
            }
        }
        if let (Some(_), Some(ao)) = (hit.face, shader.options.occlusion) {
            let rays = u32::from(ao.rays);
            stats.ao_rays += u64::from(rays);
            stats.packet_rays += u64::from(together);
            light = light * open / rays;
        }
        let mut color = lit(hit.voxel.color, light);
        if let Some(fog) = shader.options.fog {
            color = fog_blend(color, hit.t, fog.distance);
        }
        color
    }
}

/// The occlusion ray `j` of sample `sample` of pixel `(x, y)`, from the
/// hit `hit` of its camera ray `ray`, entered through `entered`: `None`
/// when no ray can leave the face (it then counts as open).
#[inline]
fn occlusion_ray(
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
