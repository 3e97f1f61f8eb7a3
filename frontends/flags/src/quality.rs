//! `--quality` and the sampling flags: how many samples a frame takes,
//! uniform (`--spp`) or adaptive (`--noise-threshold`, the default of
//! path-traced scenes), and the effects `--quality final` adds.

use voxtrace::{Adaptive, Occlusion, RenderOptions};

/// `--quality`: effects and samples in one word, for the scene at hand.
/// Explicit flags win over what it sets.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Quality {
    /// Today's default look, fast: one sample per face-shaded pixel,
    /// path-traced pixels sampled adaptively to [`Adaptive::DEFAULT`].
    #[default]
    Preview,
    /// A picture to keep: path-traced scenes sampled adaptively to
    /// [`Adaptive::FINAL`]; other scenes with shadows, [`FINAL_AO_RAYS`]
    /// occlusion rays and [`FINAL_SPP`] samples per pixel.
    Final,
}

/// Occlusion rays of `--quality final` on a face-shaded scene (`--ao 16`).
pub const FINAL_AO_RAYS: u16 = 16;

/// Samples per pixel of `--quality final` on a face-shaded scene
/// (`--spp 16`).
pub const FINAL_SPP: u16 = 16;

/// The sampling flags as given.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Sampling {
    /// `--spp`: uniform samples per pixel; `None` when not given.
    pub spp: Option<u16>,
    /// `--noise-threshold`: adaptive sampling to this threshold
    /// ([`voxtrace::Adaptive::threshold`]).
    pub noise_threshold: Option<f32>,
    /// `--max-spp`: adaptive sampling to at most this many samples.
    pub max_spp: Option<u16>,
    /// `--quality`.
    pub quality: Quality,
}

/// Sets the samples of `options` (and, for `--quality final` on a
/// face-shaded scene, its effects) as `sampling` asks, for a frame that is
/// `path_traced` or not. `--spp N` is exactly N uniform samples; without
/// it a path-traced frame samples adaptively, to `--noise-threshold` when
/// given and to at most `--max-spp` samples (its first round no larger),
/// and a face-shaded one takes 1 sample (16 under `final`, which
/// also turns shadows on and occlusion on, reaching `ao_distance`
/// (`--ao-distance`), unless `--ao N` gave its own); flat and debug looks
/// get no effects.
pub fn apply(
    sampling: &Sampling,
    path_traced: bool,
    ao_distance: f32,
    options: &mut RenderOptions,
) {
    let final_quality = sampling.quality == Quality::Final;
    if path_traced {
        options.samples = sampling.spp.unwrap_or(1);
        options.adaptive = match (sampling.spp, sampling.noise_threshold) {
            (Some(_), _) => None,
            (None, threshold) => {
                let base = if final_quality {
                    Adaptive::FINAL
                } else {
                    Adaptive::DEFAULT
                };
                let max = sampling.max_spp.unwrap_or(base.max_samples).max(1);
                Some(Adaptive {
                    threshold: threshold.unwrap_or(base.threshold),
                    min_samples: base.min_samples.min(max),
                    max_samples: max,
                })
            }
        };
        return;
    }
    options.adaptive = None;
    let shaded = !(options.flat || options.debug);
    if final_quality && shaded {
        options.shadows = true;
        options.occlusion = options.occlusion.or(Some(Occlusion {
            rays: FINAL_AO_RAYS,
            distance: ao_distance,
        }));
        options.samples = sampling.spp.unwrap_or(FINAL_SPP);
    } else {
        options.samples = sampling.spp.unwrap_or(1);
    }
}
