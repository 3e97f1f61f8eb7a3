//! A path-traced pixel: its camera samples taken in order, each averaged
//! in as it comes, resumed round by round from the [`PixelSamples`] the
//! caller keeps; one pass is one round to the last sample. Both run the
//! same steps on the same numbers, so a pixel finished in rounds is the
//! pixel of one pass.

use glam::Vec3;

use crate::render::options::Background;
use crate::render::rounds::{samples_per_round, PixelSamples};
use crate::render::sampling::sample_ray;
use crate::render::shade::{pack_mean, to_u8};
use crate::render::stats::RayStats;
use crate::scene::{Scene, WalkMemory};

use super::{Path, Rng, MAX_RADIANCE};

impl Path<'_, '_> {
    /// Pixel `(x, y)` continued from `pixel` to the end of round `round`
    /// (from 1; `u32::MAX` for every sample, one pass): its packed color
    /// and the rays traced, `None` when it was already done. After round
    /// `n` the pixel is the one-pass pixel of at most `n` rounds' samples
    /// ([`crate::render::rounds::Rounds`]). With adaptive sampling the
    /// pixel takes the samples `0, 1, ...` of the uniform sequence until
    /// its own tally says it is done, so it is the uniform render's pixel
    /// when that takes as many samples. Its camera rays walk with
    /// `memory`, shared with the neighbouring pixels' camera rays; each
    /// later ray of a path begins from the hit before it (where a walk
    /// begins, never what it hits).
    pub(crate) fn resume_pixel<'s, S: Scene + ?Sized>(
        &self,
        scene: &'s S,
        (x, y): (u32, u32),
        clear: f32,
        memory: &mut WalkMemory<'s>,
        pixel: &mut PixelSamples,
        round: u32,
    ) -> Option<(u32, RayStats)> {
        if pixel.done {
            return None;
        }
        let setup = self.setup;
        let per_round = samples_per_round(setup.adaptive.as_ref(), setup.samples);
        let until = u32::from(per_round).saturating_mul(round.max(1));
        let stats = self.take_samples(scene, (x, y), clear, memory, pixel, until);
        Some((self.packed(pixel), stats))
    }

    /// The samples the pixel has total: the adaptive maximum or the fixed
    /// count.
    fn samples(&self) -> u32 {
        match self.setup.adaptive {
            Some(a) => u32::from(a.max_samples.max(1)),
            None => u32::from(self.setup.samples.max(1)),
        }
    }

    /// Takes the pixel's next samples, in order, until it has `until` of
    /// them or is done (all its samples, or the adaptive rule says so),
    /// counting each into `pixel`; returns the rays traced. Not inlined:
    /// one copy of the sampling loop per kernel and storage (a call per
    /// pixel, against a path per sample).
    #[inline(never)]
    fn take_samples<'s, S: Scene + ?Sized>(
        &self,
        scene: &'s S,
        (x, y): (u32, u32),
        clear: f32,
        memory: &mut WalkMemory<'s>,
        pixel: &mut PixelSamples,
        until: u32,
    ) -> RayStats {
        let adaptive = self.setup.adaptive;
        let samples = self.samples();
        // A single uniform sample is the pixel's center; adaptive samples
        // are all offset, as a uniform frame's of several.
        let centered = samples == 1 && adaptive.is_none();
        let mut stats = RayStats::default();
        // The background rules of the face-shaded look: a camera sample
        // that misses shows the sky (the environment's radiance), the
        // --background color, or nothing (alpha covers the hits).
        let background = match self.setup.background {
            Background::Color(c) => Some(c.as_vec3() * (1.0 / 255.0)),
            Background::Sky | Background::Transparent => None,
        };
        let transparent = self.setup.background == Background::Transparent;
        let end = samples.min(until);
        while !pixel.done && pixel.taken < end {
            let s = pixel.taken;
            // The anti-aliasing offsets of the face-shaded look.
            let ray = sample_ray(self.camera, (x, y), (!centered).then_some(s));
            let mut rng = Rng {
                x,
                y,
                sample: s,
                event: 0,
            };
            let hits = stats.primary_hits;
            let radiance = self.radiance(scene, &ray, clear, memory, &mut rng, &mut stats);
            let missed = stats.primary_hits == hits;
            let radiance = match (missed, background) {
                (true, Some(color)) => color,
                (true, None) if transparent => Vec3::ZERO,
                _ => radiance,
            };
            // A NaN from degenerate geometry is dropped, never averaged in.
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
        pixel.done |= pixel.taken >= samples;
        pixel.hits += stats.primary_hits as u32;
        stats
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
