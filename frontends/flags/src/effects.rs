//! The render options the effect flags ask for, a `.vox` file's sun, sky
//! and bounces folded in.

use voxtrace::glam::Vec3;
use voxtrace::{
    Background, Bounces, EffectPlan, Fog, IAabb, Lighting, Look, Occlusion, RenderOptions,
    VoxModel, DEFAULT_SUN,
};

use crate::quality::{self, Sampling};

/// The effect flags.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Effects {
    /// `--flat`.
    pub flat: bool,
    /// `--debug`.
    pub debug: bool,
    /// `--sun`: `None` for the `.vox` file's sun or [`DEFAULT_SUN`],
    /// `Some(None)` for a scene without light (`--sun none`).
    pub sun: Option<Option<Vec3>>,
    /// `--shadows`.
    pub shadows: bool,
    /// `--ao N` with `--ao-distance`.
    pub occlusion: Option<Occlusion>,
    /// `--ao-distance`: also the reach of the occlusion `--quality final`
    /// adds to a face-shaded scene without `--ao`.
    pub ao_distance: f32,
    /// `--spp`, `--noise-threshold` and `--quality`.
    pub sampling: Sampling,
    /// `--fog`.
    pub fog: bool,
    /// `--background`.
    pub background: Background,
    /// `--bounces` (over the file's; path-traces even an all-diffuse
    /// scene).
    pub bounces: Option<u8>,
}

impl Default for Effects {
    /// No effect flag given.
    fn default() -> Self {
        let options = RenderOptions::default();
        Effects {
            flat: options.flat,
            debug: options.debug,
            sun: None,
            shadows: options.shadows,
            occlusion: options.occlusion,
            ao_distance: Occlusion::DEFAULT_DISTANCE,
            sampling: Sampling::default(),
            fog: false,
            background: options.background,
            bounces: None,
        }
    }
}

/// The light of path-traced frames: `model`'s sun (unless `--sun` was
/// given), sky and bounces where it has them, `bounces` over the file's.
#[must_use]
fn lighting(effects: &Effects, model: Option<&VoxModel>) -> Lighting {
    let mut light = Lighting::DEFAULT;
    let settings = model.map(|m| *m.settings()).unwrap_or_default();
    if let (Some(sun), None) = (settings.sun, effects.sun) {
        light.sun_intensity = sun.intensity;
        light.sun_radius = sun.radius;
    }
    light.sky = settings.sky.or(light.sky);
    if let Some((diffuse, specular)) = settings.bounces {
        light.bounces = Bounces { diffuse, specular };
    }
    if let Some(n) = effects.bounces {
        light.bounces = Bounces {
            diffuse: n,
            specular: n,
        };
        light.path_trace = true;
    }
    light
}

/// The options `effects` ask for on the scene `bounds`, lit as `model`
/// says when there is one. Fog thickens over the terrain's largest side
/// (3 x `--size`); on a model, framed from afar, it is scaled to the view
/// `view_distance` (the camera's distance to what it looks at): all fog at
/// twice the distance to the model's far side, so the model shows its
/// depth instead of the fog's color. Samples as [`quality::apply`] says
/// for the frame's look: adaptive in path-traced frames unless `--spp`.
#[must_use]
pub fn render_options(
    effects: &Effects,
    bounds: IAabb,
    model: Option<&VoxModel>,
    view_distance: f32,
) -> RenderOptions {
    let side = bounds.size().max_element() as f32;
    let file_sun = model.and_then(|m| m.settings().sun).map(|s| s.direction);
    let mut options = RenderOptions {
        flat: effects.flat,
        debug: effects.debug,
        sun: effects.sun.unwrap_or(Some(file_sun.unwrap_or(DEFAULT_SUN))),
        shadows: effects.shadows,
        occlusion: effects.occlusion,
        samples: 1,
        adaptive: None,
        fog: effects.fog.then_some(Fog {
            distance: match model {
                // 3 x --size for the terrain: one and a half times the
                // volume's side.
                None => 1.5 * side,
                Some(_) => 2.0 * (view_distance + 0.5 * side),
            },
        }),
        background: effects.background,
        lighting: lighting(effects, model),
    };
    let materials = model.map(crate::materials_of);
    let path_traced = EffectPlan::new(&options, materials).look == Look::Path;
    quality::apply(
        &effects.sampling,
        path_traced,
        effects.ao_distance,
        &mut options,
    );
    options
}
