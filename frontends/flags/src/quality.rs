//! `--quality` and the sampling flags: how many samples a frame takes,
//! uniform (`--spp`) or adaptive (`--noise-threshold`, the default of
//! path-traced scenes), and the effects each quality adds to a
//! face-shaded scene.

use voxtrace::{Adaptive, Occlusion, RenderOptions};

/// `--quality`: effects and samples in one word, for the scene at hand.
/// Explicit flags win over what it sets.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Quality {
    /// Fast: one sample per face-shaded pixel and no effects (the
    /// editor's flat preview, the terrain's default look), path-traced
    /// pixels sampled adaptively to [`Adaptive::DEFAULT`].
    Draft,
    /// A model's default look, a render in about a second: face-shaded
    /// scenes with shadows, [`STANDARD_AO_RAYS`] occlusion rays and
    /// [`STANDARD_SPP`] samples per pixel; path-traced ones as `Draft`.
    Standard,
    /// A picture to keep: path-traced scenes sampled adaptively to
    /// [`Adaptive::FINAL`]; other scenes with shadows, [`FINAL_AO_RAYS`]
    /// occlusion rays and [`FINAL_SPP`] samples per pixel.
    Final,
}

impl Quality {
    /// The quality of a frame without `--quality`: [`Quality::Standard`]
    /// for a model (what MagicaVoxel's render shows: shadows, soft
    /// occlusion, smooth edges), [`Quality::Draft`] for the terrain (the
    /// paper's look).
    #[must_use]
    pub fn default_for(model: bool) -> Quality {
        if model {
            Quality::Standard
        } else {
            Quality::Draft
        }
    }
}

/// Occlusion rays of `--quality standard` on a face-shaded scene (`--ao 8`).
pub const STANDARD_AO_RAYS: u16 = 8;

/// Samples per pixel of `--quality standard` on a face-shaded scene
/// (`--spp 4`).
pub const STANDARD_SPP: u16 = 4;

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
    /// `--quality`; `None` when not given ([`Quality::default_for`]).
    pub quality: Option<Quality>,
}

/// Sets the samples of `options` (and, on a face-shaded scene, the
/// effects of its quality) as `sampling` asks, for a frame that is
/// `path_traced` or not, of a `model` or the terrain. `--spp N` is
/// exactly N uniform samples; without it a path-traced frame samples
/// adaptively, to `--noise-threshold` when given and to at most
/// `--max-spp` samples (its first round no larger), and a face-shaded one
/// takes its quality's samples, and shadows and occlusion reaching
/// `ao_distance` (`--ao-distance`) under `standard` and `final` (unless
/// `--ao N` gave its own); flat and debug looks get no effects.
pub fn apply(
    sampling: &Sampling,
    path_traced: bool,
    model: bool,
    ao_distance: f32,
    options: &mut RenderOptions,
) {
    let quality = sampling.quality.unwrap_or(Quality::default_for(model));
    if path_traced {
        options.samples = sampling.spp.unwrap_or(1);
        options.adaptive = match (sampling.spp, sampling.noise_threshold) {
            (Some(_), _) => None,
            (None, threshold) => {
                let base = if quality == Quality::Final {
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
    let effects = match quality {
        Quality::Draft => None,
        Quality::Standard => Some((STANDARD_AO_RAYS, STANDARD_SPP)),
        Quality::Final => Some((FINAL_AO_RAYS, FINAL_SPP)),
    };
    match effects.filter(|_| shaded) {
        Some((rays, spp)) => {
            options.shadows = true;
            options.occlusion = options.occlusion.or(Some(Occlusion {
                rays,
                distance: ao_distance,
            }));
            options.samples = sampling.spp.unwrap_or(spp);
        }
        None => options.samples = sampling.spp.unwrap_or(1),
    }
}
