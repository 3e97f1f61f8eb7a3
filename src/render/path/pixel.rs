//! Path-traced pixels: a block's lanes take their camera samples in
//! order, each averaged in as it comes, resumed round by round from the
//! [`PixelSamples`] the caller keeps; one pass is one round to the last
//! sample. Sample by sample, the camera rays of the lanes still sampling
//! are traced together (in packets where the storage walks them), then
//! each lane's path is followed alone. Every lane runs the same steps on
//! the same numbers whatever its neighbours do, so a pixel finished in
//! rounds, in a block or alone is the pixel of one pass.

use glam::Vec3;

use crate::geom::Ray;
use crate::render::camera::block_pixel;
use crate::render::options::Background;
use crate::render::rounds::{samples_per_round, PixelSamples};
use crate::render::sampling::sample_ray;
use crate::render::shade::{pack_mean, to_u8};
use crate::render::shader::{each_lane, trace_rays, Block};
use crate::render::stats::RayStats;
use crate::scene::{Reach, Scene, WalkMemory};

use super::{Path, Rng, MAX_RADIANCE};

impl Path<'_, '_> {
    /// The lanes of `block` continued from their samples so far
    /// (`states`, lane `i`'s at `states[i]`) to the end of round `round`
    /// (from 1; `u32::MAX` for every sample, one pass), each lane not
    /// done at the start handed to `put(i, rgba)`; returns the rays
    /// traced. After round `n` a pixel is the one-pass pixel of at most
    /// `n` rounds' samples ([`crate::render::rounds::Rounds`]). With
    /// adaptive sampling a pixel takes the samples `0, 1, ...` of the
    /// uniform sequence until its own tally says it is done, so it is the
    /// uniform render's pixel when that takes as many samples. The camera
    /// rays walk with `memory`, shared with the neighbouring blocks'; each
    /// later ray of a path begins from the hit before it (where a walk
    /// begins, never what it hits).
    pub(crate) fn resume_block<'s, S: Scene + ?Sized, const N: usize>(
        &self,
        scene: &'s S,
        block: Block,
        memory: &mut WalkMemory<'s>,
        states: &mut [PixelSamples; N],
        round: u32,
        mut put: impl FnMut(usize, u32),
    ) -> RayStats {
        let setup = self.setup;
        let per_round = samples_per_round(setup.adaptive.as_ref(), setup.samples);
        let until = u32::from(per_round).saturating_mul(round.max(1));
        let samples = self.samples();
        let end = samples.min(until);
        let adaptive = setup.adaptive;
        // A single uniform sample is the pixel's center; adaptive samples
        // are all offset, as a uniform frame's of several.
        let centered = samples == 1 && adaptive.is_none();
        // The background rules of the face-shaded look: a camera sample
        // that misses shows the sky (the environment's radiance), the
        // --background color, or nothing (alpha covers the hits).
        let background = match setup.background {
            Background::Color(c) => Some(c.as_vec3() * (1.0 / 255.0)),
            Background::Sky | Background::Transparent => None,
        };
        let transparent = setup.background == Background::Transparent;
        let mut stats = RayStats::default();
        let lanes = each_lane(block.lanes).filter(|&i| !states[i].done);
        let fresh = lanes.fold(0u32, |mask, i| mask | 1 << i);
        let mut hits_of = [0u32; N];
        let sampling = |states: &[PixelSamples; N]| {
            let taking = |&i: &usize| !states[i].done && states[i].taken < end;
            each_lane(fresh)
                .filter(taking)
                .fold(0u32, |mask, i| mask | 1 << i)
        };
        let ray_of = |state: &PixelSamples, i: usize| {
            let s = (!centered).then_some(state.taken);
            sample_ray(self.camera, block_pixel(block.corner, i), s)
        };
        loop {
            let taking = sampling(states);
            if taking == 0 {
                break;
            }
            // Each sampling lane's next camera ray (the others hold one
            // no one traces).
            let first = taking.trailing_zeros() as usize;
            let mut rays: [Ray; N] = [ray_of(&states[first], first); N];
            for i in each_lane(taking & (taking - 1)) {
                rays[i] = ray_of(&states[i], i);
            }
            let mut hits = [None; N];
            let reach = Reach::after(block.clear);
            let together = trace_rays(scene, &rays, taking, reach, memory, &mut hits);
            stats.packet_rays += u64::from(together.count_ones());
            for i in each_lane(taking) {
                let pixel = &mut states[i];
                let (x, y) = block_pixel(block.corner, i);
                let mut rng = Rng {
                    x,
                    y,
                    sample: pixel.taken,
                    event: 0,
                };
                hits_of[i] += u32::from(hits[i].is_some());
                let radiance =
                    self.radiance(scene, &rays[i], hits[i], memory, &mut rng, &mut stats);
                let radiance = match (hits[i].is_none(), background) {
                    (true, Some(color)) => color,
                    (true, None) if transparent => Vec3::ZERO,
                    _ => radiance,
                };
                // A NaN from degenerate geometry is dropped, never
                // averaged in.
                let counted = if radiance.is_finite() {
                    radiance.clamp(Vec3::ZERO, Vec3::splat(MAX_RADIANCE))
                } else {
                    Vec3::ZERO
                };
                pixel.add(counted);
                if let Some(settings) = &adaptive {
                    pixel.tally.add(counted);
                    pixel.done = pixel.tally.done(pixel.taken, settings);
                }
            }
        }
        for i in each_lane(fresh) {
            let pixel = &mut states[i];
            pixel.done |= pixel.taken >= samples;
            pixel.hits += hits_of[i];
            put(i, self.packed(pixel));
        }
        stats
    }

    /// The samples the pixel has total: the adaptive maximum or the fixed
    /// count.
    fn samples(&self) -> u32 {
        match self.setup.adaptive {
            Some(a) => u32::from(a.max_samples.max(1)),
            None => u32::from(self.setup.samples.max(1)),
        }
    }

    /// The pixel's packed color: the mean of its samples (alpha the share
    /// that hit, on a transparent background).
    fn packed(&self, pixel: &PixelSamples) -> u32 {
        let transparent = self.setup.background == Background::Transparent;
        // The mean of the samples counted: all of them, or on a
        // transparent background those that hit (`pack_mean` asks for one
        // or the other).
        let mean_of = |n: u32| to_u8(pixel.mean_over(n) * 255.0);
        pack_mean(pixel.taken, pixel.hits, transparent, mean_of)
    }
}
