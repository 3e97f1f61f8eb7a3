//! Adaptive sampling of path-traced pixels: samples taken in rounds until
//! the pixel's own estimate of its noise is below a threshold, or a
//! maximum is reached.
//!
//! The decision to stop reads only the samples of the pixel it is about,
//! and a pixel's samples depend only on the pixel and the sample index, so
//! a pixel takes the same samples, and ends with the same value, on every
//! thread count, crop, tile split and target. The state is a few floats on
//! the stack: nothing allocates.

#[cfg(feature = "path")]
use glam::Vec3;

/// How adaptive sampling stops: after at least `min_samples` samples, at
/// the end of the first round (of `min_samples` samples) where the
/// standard error of the mean luminance (of samples clamped to the
/// displayable 0 to 1), relative to the square root of the mean plus
/// [`Adaptive::FLOOR`], is below `threshold`; after `max_samples` at most.
///
/// Relative to the square root, between an absolute and a relative error
/// (as Blender Cycles does): a bright pixel may keep more absolute noise
/// than a dark one, but not in proportion to its brightness. Measured on
/// study.vox at 480x270 against 256 uniform samples, a relative error
/// spent its samples on dark pixels and stopped bright ones early, an RMSE
/// well above uniform sampling's for the same time; this form comes
/// closer, and ahead at [`Adaptive::FINAL`] (docs/accuracy.md).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Adaptive {
    /// Samples every pixel takes, and the size of each later round; at
    /// least 1.
    pub min_samples: u16,
    /// Samples no pixel takes more of; at least `min_samples`.
    pub max_samples: u16,
    /// The relative standard error a pixel stops at; positive and finite.
    pub threshold: f32,
}

impl Adaptive {
    /// The default of path-traced frames without `--spp`: 16 to 64
    /// samples, stopping at 0.05. Measured on study.vox (480x270, RMSE
    /// against 1024 uniform samples): a minimum of 8 stopped too many
    /// pixels whose rare bright paths its samples had all missed (RMSE 3.6
    /// against 2.9); a maximum of 128 spent 17% more time for an error
    /// of 2.80 against 2.87 on pixels whose noise does not settle.
    pub const DEFAULT: Adaptive = Adaptive {
        min_samples: 16,
        max_samples: 64,
        threshold: 0.05,
    };

    /// `--quality final`: 32 to 256 samples, stopping at 0.025 (on
    /// study.vox, measured as above: RMSE 1.15 for 17.4 s of CPU, where
    /// 128 uniform samples gave 1.43 for 13.8 s; a minimum of 16 ended at
    /// 1.71).
    pub const FINAL: Adaptive = Adaptive {
        min_samples: 32,
        max_samples: 256,
        threshold: 0.025,
    };

    /// The luminance added to a pixel's mean before the error is taken
    /// relative to its square root: black pixels, whose relative error
    /// is large while their absolute error is invisible, stop without the
    /// maximum (0.05 is 13 of 255).
    pub const FLOOR: f32 = 0.05;

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

/// Rec. 709 luminance of a linear radiance.
#[cfg(feature = "path")]
#[inline]
fn luminance(radiance: Vec3) -> f32 {
    radiance.dot(Vec3::new(0.2126, 0.7152, 0.0722))
}

/// One pixel's running tally of its samples' luminance, and the rule that
/// stops it (the path tracer's).
#[cfg(feature = "path")]
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Tally {
    /// Samples counted.
    count: u32,
    /// Sum of their luminances.
    sum: f32,
    /// Sum of their squares.
    sum_sq: f32,
}

#[cfg(feature = "path")]
impl Tally {
    /// Counts one sample's radiance.
    #[inline]
    pub(crate) fn add(&mut self, radiance: Vec3) {
        let l = luminance(radiance);
        self.count += 1;
        self.sum += l;
        self.sum_sq += l * l;
    }

    /// Whether the pixel is done under `settings`: at the maximum, or at
    /// the end of a round with its relative standard error below the
    /// threshold.
    #[must_use]
    pub(crate) fn done(&self, settings: &Adaptive) -> bool {
        let n = self.count;
        if n >= u32::from(settings.max_samples) {
            return true;
        }
        let round = u32::from(settings.min_samples.max(1));
        if n < round || n % round != 0 {
            return false;
        }
        let n = n as f32;
        let mean = self.sum / n;
        // The unbiased sample variance; rounding may make it a little
        // negative for equal samples.
        let variance = ((self.sum_sq - self.sum * mean) / (n - 1.0).max(1.0)).max(0.0);
        // stderr / sqrt(mean + floor) < threshold, squared (no square root,
        // so every target decides alike): variance / n < t^2 (mean + floor).
        let t = settings.threshold;
        variance < t * t * (mean.max(0.0) + Adaptive::FLOOR) * n
    }
}

#[cfg(all(test, feature = "path"))]
mod tests {
    use super::*;

    #[test]
    fn equal_samples_stop_at_the_first_round() {
        let settings = Adaptive::DEFAULT;
        let mut tally = Tally::default();
        for i in 0..settings.min_samples {
            assert!(!tally.done(&settings), "stopped after {i}");
            tally.add(Vec3::splat(0.7));
        }
        assert!(tally.done(&settings));
    }

    #[test]
    fn noisy_samples_run_to_the_maximum() {
        let settings = Adaptive::DEFAULT;
        let mut tally = Tally::default();
        let mut taken = 0;
        while !tally.done(&settings) {
            // One sample in four is bright: a relative error near 1/sqrt(n).
            let bright = taken % 4 == 0;
            tally.add(Vec3::splat(if bright { 4.0 } else { 0.0 }));
            taken += 1;
        }
        assert_eq!(taken, u32::from(settings.max_samples));
    }

    #[test]
    fn the_error_falls_below_the_threshold_in_between() {
        // Samples alternating 0.2 and 0.8: variance 0.09 n / (n - 1), mean
        // 0.5; 0.09 / (n - 1) < 0.05^2 * 0.55 from n = 67, so at the round
        // of 80.
        let settings = Adaptive {
            max_samples: 256,
            ..Adaptive::DEFAULT
        };
        let mut tally = Tally::default();
        let mut taken = 0;
        while !tally.done(&settings) {
            tally.add(Vec3::splat(if taken % 2 == 0 { 0.2 } else { 0.8 }));
            taken += 1;
        }
        assert_eq!(taken, 80);
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
