//! The render options the effect flags ask for, a `.vox` file's sun, sky
//! and bounces folded in.

use voxtrace::glam::Vec3;
use voxtrace::{
    Background, Bounces, CameraSettings, EffectPlan, Fog, IAabb, Lighting, Look, Occlusion,
    RenderOptions, VoxModel, DEFAULT_SUN,
};

use crate::quality::{self, Sampling};

/// The effect flags.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Effects {
    /// `--flat`.
    pub flat: bool,
    /// `--debug`.
    pub debug: bool,
    /// `--sun`: `None` for the `.vox` file's sun, else a model's
    /// [`shoulder_sun`] or the terrain's [`DEFAULT_SUN`]; `Some(None)` for
    /// a scene without light (`--sun none`).
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

/// The sun of a model whose file has none, seen from `view`: over the
/// viewer's right shoulder, 30 degrees to the side of the way back from
/// what the camera looks at and 45 degrees above the horizon, so the
/// faces the camera sees are the lit ones (a fixed sun left the front and
/// one side of most models in shade). A camera looking straight up or
/// down has no "back": it takes [`DEFAULT_SUN`].
#[must_use]
pub fn shoulder_sun(view: &CameraSettings) -> Vec3 {
    let back = view.lookfrom - view.lookat;
    let Some(back) = Vec3::new(back.x, 0.0, back.z).try_normalize() else {
        return DEFAULT_SUN;
    };
    // The camera's right (its image's), on the ground plane: it looks
    // along -back, and right is forward x up.
    let right = Vec3::Y.cross(back);
    let (side, above) = (30f32.to_radians(), 45f32.to_radians());
    let level = back * side.cos() + right * side.sin();
    level * above.cos() + Vec3::Y * above.sin()
}

/// The options `effects` ask for on the scene `bounds`, lit as `model`
/// says when there is one, seen from `view` (the first frame's camera).
/// A model without a sun of its own is lit from over the camera's
/// shoulder ([`shoulder_sun`]), the terrain by the paper's sun. Fog
/// thickens over the terrain's largest side (3 x `--size`); on a model,
/// framed from afar, it is scaled to the view (the camera's distance to
/// what it looks at): all fog at twice the distance to the model's far
/// side, so the model shows its depth instead of the fog's color. Samples
/// as [`quality::apply`] says for the frame's look: adaptive in
/// path-traced frames unless `--spp`.
#[must_use]
pub fn render_options(
    effects: &Effects,
    bounds: IAabb,
    model: Option<&VoxModel>,
    view: &CameraSettings,
) -> RenderOptions {
    let side = bounds.size().max_element() as f32;
    let view_distance = (view.lookfrom - view.lookat).length();
    let default_sun = match model {
        Some(model) => model
            .settings()
            .sun
            .map_or_else(|| shoulder_sun(view), |s| s.direction),
        None => DEFAULT_SUN,
    };
    let mut options = RenderOptions {
        flat: effects.flat,
        debug: effects.debug,
        sun: effects.sun.unwrap_or(Some(default_sun)),
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
        model.is_some(),
        effects.ao_distance,
        &mut options,
    );
    options
}

#[cfg(test)]
mod tests {
    use voxtrace::glam::Vec3;
    use voxtrace::{CameraSettings, DEFAULT_SUN};

    use super::shoulder_sun;

    /// From every side and height a camera looks at a model from, the
    /// sun is a unit vector 45 degrees above the horizon, from behind the
    /// camera (so every face the camera sees that faces it squarely is
    /// lit) and 30 degrees toward its image's right, as the camera's own
    /// rays tell right from left; looking straight down or up, the
    /// paper's sun.
    #[test]
    fn the_sun_comes_over_the_cameras_right_shoulder() {
        for yaw in (0..360).step_by(15) {
            for pitch in [-60.0f32, -10.0, 0.0, 20.0, 45.0, 80.0] {
                let (yaw_r, pitch_r) = ((yaw as f32).to_radians(), pitch.to_radians());
                let back = Vec3::new(yaw_r.sin(), 0.0, yaw_r.cos());
                let offset = back * pitch_r.cos() * 50.0 + Vec3::Y * pitch_r.sin() * 50.0;
                let lookat = Vec3::new(3.0, -2.0, 7.5);
                let view = CameraSettings {
                    lookfrom: lookat + offset,
                    lookat,
                    ..CameraSettings::default()
                };
                let sun = shoulder_sun(&view);
                let context = format!("yaw {yaw} pitch {pitch}: {sun}");
                assert!((sun.length() - 1.0).abs() < 1e-5, "{context}");
                assert!((sun.y - 45f32.to_radians().sin()).abs() < 1e-5, "{context}");
                let level = Vec3::new(sun.x, 0.0, sun.z).normalize();
                let side = level.dot(back).clamp(-1.0, 1.0).acos().to_degrees();
                assert!((side - 30.0).abs() < 0.01, "{context}: {side} degrees");
                // The image's right, from the camera's rays through the
                // middle row's last and first pixels.
                let camera = voxtrace::Camera::new(view).unwrap();
                let (w, h) = (view.width, view.height);
                let right = camera.get_ray(w - 1, h / 2).dir() - camera.get_ray(0, h / 2).dir();
                assert!(right.dot(level) > 0.0, "{context}");
            }
        }
        for down in [Vec3::Y, -Vec3::Y] {
            let view = CameraSettings {
                lookfrom: down * 40.0,
                lookat: Vec3::ZERO,
                ..CameraSettings::default()
            };
            assert_eq!(shoulder_sun(&view), DEFAULT_SUN);
        }
    }
}
