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
/// block and sample (a copy of the kernel per set of effects saved under
/// 3% of a render's instructions: benches/README.md).
pub(super) struct Lit<'s, 'c, 'm>(pub(super) &'s FrameSetup<'c, 'm>);

impl Kernel for Lit<'_, '_, '_> {
    #[cfg(feature = "packets")]
    fn in_blocks(&self) -> bool {
        true
    }

    /// Sample by sample: the lanes' camera rays, then their hits' shadow
    /// rays ([`Lit::shadowed`]) and occlusion rays ([`Lit::open`]), then
    /// each lane shaded ([`Lit::shade`]); a pixel of one sample is packed
    /// as it is shaded, one of several is their mean ([`Mean`]). Each
    /// effect is tested once per sample of the block, not per lane, and a
    /// frame without any ([`Lit::plain`]) packs each hit's face light.
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
            stats.primary_rays += u64::from(lanes.count_ones());
            stats.packet_rays += u64::from(together.count_ones());
            if self.plain() {
                // Each pixel packed from its hit alone (4.5% of the default
                // look's render instructions: benches/README.md).
                for i in each_lane(lanes) {
                    let color = match &hits[i] {
                        None => self.0.miss(sky(rays[i].dir())),
                        Some(hit) => {
                            stats.primary_hits += 1;
                            pack(lit(hit.voxel.color, self.light(hit, false)))
                        }
                    };
                    put(i, color);
                }
                continue;
            }
            let blocked = self.shadowed(scene, (&rays, &hits), lanes, memory, &mut stats);
            let open = self.0.options.occlusion.map(|ao| {
                let rays_hits = (&rays, &hits);
                let open = self.open(scene, ao, (corner, s), rays_hits, lanes, memory, &mut stats);
                (open, u32::from(ao.rays))
            });
            for i in each_lane(lanes) {
                let color = match &hits[i] {
                    None => sky(rays[i].dir()),
                    Some(hit) => {
                        let open = open.as_ref().map(|&(ref open, rays)| (open[i], rays));
                        self.shade(hit, blocked >> i & 1 != 0, open)
                    }
                };
                let hit = hits[i].is_some();
                stats.primary_hits += u64::from(hit);
                match &mut means {
                    None => put(i, if hit { pack(color) } else { self.0.miss(color) }),
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

    /// Whether a pixel is its hit's face light alone: one sample, and no
    /// shadows, occlusion or fog (the default look).
    #[inline]
    fn plain(&self) -> bool {
        let options = &self.0.options;
        self.one_ray() && !options.shadows && options.occlusion.is_none() && options.fog.is_none()
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
    /// several together ([`trace_rays`]), a lone lane's alone. Counts in
    /// `stats` a shadow ray per hit on a sunlit face, and those answered
    /// together.
    #[inline]
    fn shadowed<'s, S: Scene + ?Sized, const N: usize>(
        &self,
        scene: &'s S,
        (rays, hits): (&[Ray; N], &[Option<Hit>; N]),
        lanes: u32,
        memory: &WalkMemory<'s>,
        stats: &mut RayStats,
    ) -> u32 {
        if !self.shadows() {
            return 0;
        }
        let shader = self.0;
        let sunlit = |hit: &&Hit| shader.sunlit[face_index(hit.face)];
        let shadow = |i: usize| secondary(&rays[i], hits[i].as_ref().filter(sunlit)?, shader.sun);
        let lit_faces = each_lane(lanes).filter(|&i| hits[i].as_ref().is_some_and(|h| sunlit(&h)));
        stats.shadow_rays += lit_faces.count() as u64;
        let memory = &mut memory.clone();
        if lanes.is_power_of_two() {
            // A lone lane: no packet to fill.
            let i = lanes.trailing_zeros() as usize;
            let blocker =
                shadow(i).and_then(|ray| scene.trace_with(&ray, Reach::ALL, memory, None).hit);
            return u32::from(blocker.is_some()) << i;
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
        stats.packet_rays += u64::from(together.count_ones());
        let blocked = |i: usize| u32::from(blockers[i].is_some()) << i;
        each_lane(sent).fold(0, |mask, i| mask | blocked(i))
    }

    /// How many occlusion rays of each lane's hit (`hits[i]`, of the camera
    /// ray `rays[i]`, sample `sample` of lane `i` of the block from
    /// `corner`) meet nothing within the reach of `ao`, one that cannot
    /// leave the face counted open (0 for a lane without a face): in
    /// packets by octant for close hits (`packets.rs`), else alone from a
    /// copy of the camera ray's memory. Counts the rays in `stats`, and
    /// those answered together.
    #[inline]
    #[allow(clippy::too_many_arguments)]
    fn open<'s, S: Scene + ?Sized, const N: usize>(
        &self,
        scene: &'s S,
        ao: Occlusion,
        (corner, sample): ((u32, u32), u32),
        (rays, hits): (&[Ray; N], &[Option<Hit>; N]),
        lanes: u32,
        memory: &WalkMemory<'s>,
        stats: &mut RayStats,
    ) -> [u32; N] {
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
            stats.ao_rays += u64::from(ao.rays);
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
        stats.packet_rays += together.iter().map(|&n| u64::from(n)).sum::<u64>();
        open
    }

    /// The light out of 256 on the face of `hit`, in shadow where its
    /// shadow ray was `blocked` (only a sunlit face's can be).
    #[inline]
    fn light(&self, hit: &Hit, blocked: bool) -> u32 {
        let face = face_index(hit.face);
        let table = if blocked {
            &self.0.shadowed
        } else {
            &self.0.light
        };
        u32::from(table[face])
    }

    /// The color of a camera ray's hit `hit` in its face's light, in
    /// shadow where its shadow ray was `blocked` ([`Lit::shadowed`]),
    /// dimmed to the share of its occlusion rays that are open (`open`:
    /// how many of how many, [`Lit::open`]; a hit without a face is not
    /// dimmed), fogged by its distance.
    #[inline]
    fn shade(&self, hit: &Hit, blocked: bool, open: Option<(u32, u32)>) -> U8Vec3 {
        let shader = self.0;
        let mut light = self.light(hit, blocked);
        if let (Some(_), Some((open, rays))) = (hit.face, open) {
            light = light * open / rays;
        }
        let color = lit(hit.voxel.color, light);
        match shader.options.fog {
            Some(fog) => fog_blend(color, hit.t, fog.distance),
            None => color,
        }
    }
}

/// The occlusion rays `--ao` with `rays` rays a hit traces from the hit
/// `hit` of the camera ray `ray`, sample `sample` of pixel `pixel`, in the
/// order [`Lit::open`] makes them ([`occlusion_ray`]): `None` for one that
/// cannot leave the face (counted open), nothing for a hit without a face.
/// Not API: the door benches/embree takes to trace the very same rays
/// through Intel Embree (`voxtrace-report embree-input --occlusion`).
#[doc(hidden)]
pub fn occlusion_rays(
    ray: Ray,
    hit: Hit,
    pixel: (u32, u32),
    sample: u32,
    rays: u16,
) -> impl Iterator<Item = Option<Ray>> {
    let (x, y) = pixel;
    let n = if hit.face.is_some() {
        u32::from(rays)
    } else {
        0
    };
    (0..n).map(move |j| occlusion_ray(&ray, &hit, hit.face?, (x, y, sample), j))
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
