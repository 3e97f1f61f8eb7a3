//! The page's effect toggles as `RenderOptions`, built as the CLI's
//! `frontends/cli/src/effects.rs` builds them from `--shadows`, `--ao N`
//! and `--fog` (a `.vox` file's sun, sky and bounces folded in), so that
//! the page's picture is the desktop's for the same flags. The end-to-end
//! test (`test/e2e.mjs`) compares the two byte for byte.

use voxtrace::{Bounces, Fog, IAabb, Lighting, Occlusion, RenderOptions, VoxModel, DEFAULT_SUN};

/// `vt_render`'s `effects` bits.
pub const SHADOWS: u32 = 1;
/// Distance fog (`--fog`).
pub const FOG: u32 = 2;

/// The options for the toggles in `effects` ([`SHADOWS`], [`FOG`]) and
/// `ao_rays` ambient-occlusion rays (0: off), over the scene `bounds`
/// (fog thickens over their largest side), lit as `model` says when there
/// is one.
pub fn render_options(
    effects: u32,
    ao_rays: u16,
    bounds: IAabb,
    model: Option<&VoxModel>,
) -> RenderOptions {
    let settings = model.map(|m| *m.settings()).unwrap_or_default();
    let mut lighting = Lighting::DEFAULT;
    if let Some(sun) = settings.sun {
        lighting.sun_intensity = sun.intensity;
        lighting.sun_radius = sun.radius;
    }
    lighting.sky = settings.sky.or(lighting.sky);
    if let Some((diffuse, specular)) = settings.bounces {
        lighting.bounces = Bounces { diffuse, specular };
    }
    RenderOptions {
        sun: Some(settings.sun.map_or(DEFAULT_SUN, |s| s.direction)),
        shadows: effects & SHADOWS != 0,
        occlusion: (ao_rays > 0).then_some(Occlusion {
            rays: ao_rays,
            distance: Occlusion::DEFAULT_DISTANCE,
        }),
        fog: (effects & FOG != 0).then_some(Fog {
            distance: 1.5 * bounds.size().max_element() as f32,
        }),
        lighting,
        ..RenderOptions::default()
    }
}
