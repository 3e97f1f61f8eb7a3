//! Samples taken in rounds over the whole frame, for a render that may be
//! stopped between rounds (a time budget): what a round is, the state a
//! pixel keeps from one round to the next, and the options whose ordinary
//! render is the frame after a given number of rounds.
//!
//! A path-traced pixel takes its samples `0, 1, ...` in order whatever
//! the rounds (the adaptive rule stops it only at the end of a round of
//! [`Adaptive::min_samples`]), so the frame after `n` rounds depends on
//! `n` alone: it is the frame of [`Rounds::options_after`], on any thread
//! count, crop and target. A caller that stops on a clock therefore
//! stops between frames that are each reproducible. Nothing here
//! allocates: the caller holds one [`PixelSamples`] per pixel.

#[cfg(feature = "path")]
use glam::Vec3;

use crate::render::adaptive::Adaptive;
#[cfg(feature = "path")]
use crate::render::adaptive::Tally;
use crate::render::options::RenderOptions;
use crate::render::plan::{EffectPlan, Look};
use crate::render::stats::RayStats;

/// Samples per round of a path-traced frame with a fixed sample count (an
/// adaptive frame's round is its [`Adaptive::min_samples`]): the default
/// adaptive round, so that both take rounds of the same size by default.
pub const UNIFORM_ROUND: u16 = Adaptive::DEFAULT.min_samples;

/// The samples per round of a path-traced pixel under `adaptive` (its
/// minimum) or, without it, `samples` fixed ([`UNIFORM_ROUND`]).
#[must_use]
pub(crate) fn samples_per_round(adaptive: Option<&Adaptive>, samples: u16) -> u16 {
    match adaptive {
        Some(a) => a.min_samples.max(1),
        None => UNIFORM_ROUND.min(samples.max(1)),
    }
}

/// How a frame's samples divide into rounds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Rounds {
    /// Samples a pixel takes per round (the last round may take fewer).
    pub samples_per_round: u16,
    /// Rounds a complete frame takes at most: every pixel is done after
    /// them. 1 for every look but the path tracer, which takes its
    /// samples in one pass of the frame.
    pub most: u32,
    /// Samples a pixel takes at most over every round.
    pub samples: u16,
}

impl Rounds {
    /// The rounds of a frame with `plan` ([`EffectPlan::new`] of the
    /// options and the scene's materials).
    #[must_use]
    pub fn of(plan: &EffectPlan) -> Rounds {
        let options = &plan.options;
        if plan.look != Look::Path {
            return Rounds {
                samples_per_round: options.samples.max(1),
                most: 1,
                samples: options.samples.max(1),
            };
        }
        let per_round = samples_per_round(options.adaptive.as_ref(), options.samples);
        let total = match &options.adaptive {
            Some(a) => a.max_samples.max(1),
            None => options.samples.max(1),
        };
        Rounds {
            samples_per_round: per_round,
            most: u32::from(total.div_ceil(per_round)),
            samples: total,
        }
    }

    /// The options (those of `plan`) whose ordinary render, in one pass,
    /// is byte for byte the frame after `rounds` rounds (at least 1): the
    /// same options with at most `rounds` x [`Rounds::samples_per_round`]
    /// samples per pixel (the adaptive maximum, or the fixed count). A
    /// frame that is not path-traced keeps its options.
    #[must_use]
    pub fn options_after(&self, plan: &EffectPlan, rounds: u32) -> RenderOptions {
        let mut options = plan.options;
        if plan.look != Look::Path {
            return options;
        }
        let cap = self.samples_after(rounds);
        match &mut options.adaptive {
            Some(a) => a.max_samples = a.max_samples.min(cap),
            None => options.samples = options.samples.min(cap),
        }
        options
    }

    /// The most samples a pixel has taken after `rounds` rounds (at least
    /// one round): `rounds` rounds' samples, no more than
    /// [`Rounds::samples`].
    #[must_use]
    pub fn samples_after(&self, rounds: u32) -> u16 {
        let cap = u32::from(self.samples_per_round).saturating_mul(rounds.max(1));
        u16::try_from(cap).map_or(self.samples, |cap| cap.min(self.samples))
    }
}

/// One pixel's samples so far, kept by the caller between rounds: the sum
/// of their radiance, the adaptive tally, the primary rays that hit, and
/// whether the pixel is done. Start every pixel at the default.
#[derive(Clone, Copy, Debug, Default)]
pub struct PixelSamples {
    /// No further round takes a sample of this pixel.
    pub(crate) done: bool,
    /// Samples taken.
    #[cfg(feature = "path")]
    pub(crate) taken: u32,
    /// Their camera rays that hit a voxel.
    #[cfg(feature = "path")]
    pub(crate) hits: u32,
    /// The sum of their radiance, in the order they were taken, in `f64`:
    /// exact for equal samples (a 24-bit mantissa times fewer than 2^29
    /// samples fits in 53 bits), so a pixel whose samples agree has their
    /// value as its mean (in `f32`, a sky of 0.7 summed 1024 times came
    /// to a mean a rounding above 178.5 / 255, and its byte to 179 where
    /// one sample gives 178).
    #[cfg(feature = "path")]
    pub(crate) sum: [f64; 3],
    /// The adaptive tally of their displayable values.
    #[cfg(feature = "path")]
    pub(crate) tally: Tally,
}

impl PixelSamples {
    /// A pixel no round samples: one rendered in one pass.
    pub(crate) fn finished() -> PixelSamples {
        PixelSamples {
            done: true,
            #[cfg(feature = "path")]
            taken: 0,
            #[cfg(feature = "path")]
            hits: 0,
            #[cfg(feature = "path")]
            sum: [0.0; 3],
            #[cfg(feature = "path")]
            tally: Tally::default(),
        }
    }

    /// The mean radiance of the pixel's path-traced samples, linear and
    /// unrounded, not clamped to white (a sample is capped at 16 times
    /// white, as always): what its packed color rounds and clamps, and
    /// what a denoiser reads best. Over all the samples taken, so with a
    /// transparent background, where misses count as black, it is the
    /// color times its coverage. `None` when no path-traced sample was
    /// taken (a face-shaded frame's pixel).
    #[cfg(feature = "path")]
    #[must_use]
    pub fn mean_radiance(&self) -> Option<Vec3> {
        (self.taken > 0).then(|| self.mean_over(self.taken))
    }

    /// Counts one more sample, of `radiance`.
    #[cfg(feature = "path")]
    pub(crate) fn add(&mut self, radiance: Vec3) {
        for (sum, value) in self.sum.iter_mut().zip(radiance.to_array()) {
            *sum += f64::from(value);
        }
        self.taken += 1;
    }

    /// The sum divided by `n` (at least one: all the samples taken, or
    /// those that hit), rounded once to `f32`: the value of the samples
    /// when `n` of them are all equal and the rest are zero.
    #[cfg(feature = "path")]
    pub(crate) fn mean_over(&self, n: u32) -> Vec3 {
        let n = f64::from(n);
        Vec3::from_array(self.sum.map(|sum| (sum / n) as f32))
    }

    /// Whether the pixel has all its samples: no later round changes it.
    #[must_use]
    pub fn is_done(&self) -> bool {
        self.done
    }
}

/// What a render in rounds did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RoundsDone {
    /// Rays traced over every round, by kind.
    pub rays: RayStats,
    /// Rounds taken, at least 1: the frame is the one-pass frame of
    /// [`Rounds::options_after`] this many rounds.
    pub rounds: u32,
    /// Every pixel is done: the frame is also the one-pass frame of the
    /// options as given.
    pub complete: bool,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[cfg(feature = "path")]
    proptest::proptest! {
        /// A pixel whose samples are all equal has that value as its mean
        /// (and so the byte one sample gives), for any value a sample can
        /// take and any count a pixel can reach.
        #[test]
        fn equal_samples_have_their_value_as_mean(
            value in proptest::array::uniform3(0.0f32..=16.0),
            taken in 1u32..=4096,
        ) {
            let mut pixel = PixelSamples::default();
            let sample = Vec3::from_array(value);
            for _ in 0..taken {
                pixel.add(sample);
            }
            proptest::prop_assert_eq!(pixel.taken, taken);
            proptest::prop_assert_eq!(pixel.mean_radiance(), Some(sample));
        }
    }

    fn path_plan(options: RenderOptions) -> EffectPlan {
        let mut options = options;
        options.lighting.path_trace = true;
        EffectPlan::new(&options, None)
    }

    #[test]
    fn adaptive_rounds_are_its_minimum_up_to_its_maximum() {
        let plan = path_plan(RenderOptions {
            adaptive: Some(Adaptive::DEFAULT),
            ..RenderOptions::default()
        });
        let rounds = Rounds::of(&plan);
        assert_eq!((rounds.samples_per_round, rounds.most), (16, 4));
        let after = |n| rounds.options_after(&plan, n).adaptive.unwrap().max_samples;
        assert_eq!(
            [after(1), after(2), after(3), after(4), after(9)],
            [16, 32, 48, 64, 64]
        );
    }

    #[test]
    fn fixed_samples_take_rounds_of_sixteen_and_a_short_last_one() {
        let plan = path_plan(RenderOptions {
            samples: 40,
            ..RenderOptions::default()
        });
        let rounds = Rounds::of(&plan);
        assert_eq!((rounds.samples_per_round, rounds.most), (16, 3));
        let after = |n| rounds.options_after(&plan, n).samples;
        assert_eq!([after(1), after(2), after(3)], [16, 32, 40]);
        let cap = |n| rounds.samples_after(n);
        assert_eq!([cap(1), cap(2), cap(3), cap(4)], [16, 32, 40, 40]);
        // Few samples are one round.
        let few = path_plan(RenderOptions {
            samples: 5,
            ..RenderOptions::default()
        });
        assert_eq!(Rounds::of(&few).most, 1);
    }

    #[test]
    fn a_face_shaded_frame_is_one_round_and_keeps_its_options() {
        let options = RenderOptions {
            samples: 64,
            ..RenderOptions::default()
        };
        let plan = EffectPlan::new(&options, None);
        let rounds = Rounds::of(&plan);
        assert_eq!(rounds.most, 1);
        assert_eq!(rounds.options_after(&plan, 1), plan.options);
    }
}
