//! Adaptive sampling of path-traced pixels: samples taken in rounds until
//! another sample would take less than a threshold off the pixel's
//! estimated error, or a maximum is reached.
//!
//! The decision to stop reads only the samples of the pixel it is about,
//! and a pixel's samples depend only on the pixel and the sample index, so
//! a pixel takes the same samples, and ends with the same value, on every
//! thread count, crop, tile split and target. The state is a few floats on
//! the stack: nothing allocates.

#[cfg(feature = "path")]
use glam::Vec3;

/// How adaptive sampling stops: after at least `min_samples` samples, at
/// the end of the first round (of `min_samples` samples) where one more
/// sample would lower the pixel's expected squared error by less than
/// `threshold` squared; after `max_samples` at most.
///
/// The error is the one an image shows: the bytes are the mean radiance
/// times 255, linear, so it is absolute (not relative to the pixel's
/// brightness), of the three channels alike, and of samples clamped to the
/// displayable 0 to 1. A pixel whose samples vary by `sigma` has, after
/// `n`, a squared error of `sigma^2 / n`, and the next sample takes
/// `sigma^2 / n^2` off it (to first order): the rule stops once
/// `sigma / n < threshold`, so a pixel ends with samples in proportion to
/// its `sigma`, the share of a frame's samples that leaves the least
/// squared error over the frame. (A threshold on the standard error
/// itself, `sigma / sqrt(n)`, gives samples in proportion to `sigma^2`:
/// the noisiest pixels take far more than their share. Measured against
/// it, docs/accuracy.md.)
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Adaptive {
    /// Samples every pixel takes, and the size of each later round; at
    /// least 1.
    pub min_samples: u16,
    /// Samples no pixel takes more of; at least `min_samples`.
    pub max_samples: u16,
    /// The least gain of another sample, as the square root of the
    /// squared error (in units of white) it takes off; positive and
    /// finite.
    pub threshold: f32,
}

impl Adaptive {
    /// The default of path-traced frames without `--spp`: 16 to 64
    /// samples, stopping at 0.005. Measured on the accuracy report's room
    /// and study.vox (320x180, RMSE against 1024 uniform samples,
    /// docs/accuracy.md): the error of the previous rule's default on
    /// study.vox in 0.83 times its time at 0.0065, a lower one at 0.005.
    pub const DEFAULT: Adaptive = Adaptive {
        min_samples: 16,
        max_samples: 64,
        threshold: 0.005,
    };

    /// `--quality final`: 32 to 256 samples, stopping at 0.0015 (measured
    /// as above: study.vox's error 1.53 where 128 uniform samples leave
    /// 1.86, in about the same time).
    pub const FINAL: Adaptive = Adaptive {
        min_samples: 32,
        max_samples: 256,
        threshold: 0.0015,
    };

    /// The settings with `threshold`, the default sample counts.
    #[must_use]
    pub const fn with_threshold(threshold: f32) -> Adaptive {
        Adaptive {
            threshold,
            ..Adaptive::DEFAULT
        }
    }

    /// Whether the settings can run: at least one sample, a maximum not
    /// below the minimum, a positive finite threshold.
    #[must_use]
    pub fn is_usable(&self) -> bool {
        self.min_samples >= 1
            && self.max_samples >= self.min_samples
            && self.threshold > 0.0
            && self.threshold.is_finite()
    }
}

/// One pixel's running tally of its samples, clamped to the displayable
/// 0 to 1, and the rule that stops it (the path tracer's). The count is
/// the pixel's own ([`crate::render::rounds::PixelSamples`]).
#[cfg(feature = "path")]
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Tally {
    /// Sum of the samples, per channel.
    sum: Vec3,
    /// Sum of their squares, per channel.
    sum_sq: Vec3,
}

#[cfg(feature = "path")]
impl Tally {
    /// Counts one sample's radiance.
    #[inline]
    pub(crate) fn add(&mut self, radiance: Vec3) {
        // The noise that shows: a bright path past white changes nothing
        // the pixel can display.
        let shown = radiance.clamp(Vec3::ZERO, Vec3::ONE);
        self.sum += shown;
        self.sum_sq += shown * shown;
    }

    /// Whether the pixel is done under `settings` after `taken` samples
    /// (those counted): at the maximum, or at the end of a round where
    /// another sample would gain less than the threshold.
    #[must_use]
    pub(crate) fn done(&self, taken: u32, settings: &Adaptive) -> bool {
        if taken >= u32::from(settings.max_samples) {
            return true;
        }
        let round = u32::from(settings.min_samples.max(1));
        if taken < round || taken % round != 0 {
            return false;
        }
        let n = taken as f32;
        // The unbiased sample variance per channel; rounding may make it a
        // little negative for equal samples.
        let variance = (self.sum_sq - self.sum * (self.sum / n)) / (n - 1.0).max(1.0);
        let variance = variance.max(Vec3::ZERO);
        let mean_variance = (variance.x + variance.y + variance.z) * (1.0 / 3.0);
        // sigma / n < t, squared (no square root, so every target decides
        // alike).
        let t = settings.threshold;
        mean_variance < t * t * n * n
    }
}

#[cfg(all(test, feature = "path"))]
mod tests {
    use super::*;

    /// The samples a tally takes of `sample(i)` before `settings` stop it.
    fn taken_until_done(settings: &Adaptive, sample: impl Fn(u32) -> Vec3) -> u32 {
        let mut tally = Tally::default();
        let mut taken = 0;
        while !tally.done(taken, settings) {
            tally.add(sample(taken));
            taken += 1;
        }
        taken
    }

    #[test]
    fn equal_samples_stop_at_the_first_round() {
        let settings = Adaptive::DEFAULT;
        let taken = taken_until_done(&settings, |_| Vec3::splat(0.7));
        assert_eq!(taken, u32::from(settings.min_samples));
    }

    #[test]
    fn noisy_samples_run_to_the_maximum() {
        // One sample in four is bright (clamped to white): sigma about
        // 0.43, and 0.43 / 64 is above the default's threshold.
        let settings = Adaptive::DEFAULT;
        let taken = taken_until_done(&settings, |i| {
            Vec3::splat(if i % 4 == 0 { 4.0 } else { 0.0 })
        });
        assert_eq!(taken, u32::from(settings.max_samples));
    }

    #[test]
    fn samples_end_in_proportion_to_the_noise_in_between() {
        // Samples alternating m - d and m + d: variance d^2 n / (n - 1),
        // so the rule stops at the first round with d^2 / (n - 1) < t^2 n,
        // about n = d / t: twice the noise, twice the samples.
        let settings = Adaptive {
            min_samples: 8,
            max_samples: 1024,
            threshold: 0.001,
        };
        let alternating =
            |d: f32| move |i: u32| Vec3::splat(if i % 2 == 0 { 0.5 - d } else { 0.5 + d });
        // d = 0.1: d^2 / (n - 1) < 1e-6 n from n = 101, the round of 104.
        assert_eq!(taken_until_done(&settings, alternating(0.1)), 104);
        // d = 0.2: from n = 201, the round of 208.
        assert_eq!(taken_until_done(&settings, alternating(0.2)), 208);
    }

    #[test]
    fn every_channel_counts_and_only_what_shows() {
        let settings = Adaptive::DEFAULT;
        // Noise in blue alone is noise (a luminance would weigh it 0.07).
        let blue = |i: u32| Vec3::new(0.5, 0.5, if i % 2 == 0 { 0.0 } else { 1.0 });
        assert_eq!(
            taken_until_done(&settings, blue),
            u32::from(settings.max_samples)
        );
        // Samples past white differ in nothing the pixel shows.
        let bright = |i: u32| Vec3::splat(if i % 2 == 0 { 2.0 } else { 9.0 });
        assert_eq!(
            taken_until_done(&settings, bright),
            u32::from(settings.min_samples)
        );
    }

    #[test]
    fn only_usable_settings_are_usable() {
        assert!(Adaptive::DEFAULT.is_usable() && Adaptive::FINAL.is_usable());
        let bad = |f: fn(&mut Adaptive)| {
            let mut a = Adaptive::DEFAULT;
            f(&mut a);
            a.is_usable()
        };
        assert!(!bad(|a| a.min_samples = 0));
        assert!(!bad(|a| a.max_samples = 4));
        assert!(!bad(|a| a.threshold = 0.0));
        assert!(!bad(|a| a.threshold = f32::NAN));
        assert!(!bad(|a| a.threshold = f32::INFINITY));
    }
}
