//! The page's effect toggles as `RenderOptions`: the CLI's `--shadows`,
//! `--ao N` and `--fog`, read by the crate the CLI reads them with
//! ([`voxtrace_flags::render_options`], a `.vox` file's sun, sky and
//! bounces folded in), so that the page's picture is the desktop's for the
//! same flags. The end-to-end test (`test/e2e.mjs`) compares the two byte
//! for byte.

use voxtrace::{CameraSettings, IAabb, Occlusion, RenderOptions, VoxModel};
use voxtrace_flags::{Effects, Quality, Sampling};

/// `vt_render`'s `effects` bits.
pub const SHADOWS: u32 = 1;
/// Distance fog (`--fog`).
pub const FOG: u32 = 2;

/// The options for the toggles in `effects` ([`SHADOWS`], [`FOG`]) and
/// `ao_rays` ambient-occlusion rays (0: off), over the scene `bounds`
/// seen from `view` (fog is scaled and a model's sun placed as the CLI
/// does), lit as `model` says when there is one.
pub fn render_options(
    effects: u32,
    ao_rays: u16,
    bounds: IAabb,
    model: Option<&VoxModel>,
    view: &CameraSettings,
) -> RenderOptions {
    let effects = Effects {
        shadows: effects & SHADOWS != 0,
        occlusion: (ao_rays > 0).then_some(Occlusion {
            rays: ao_rays,
            distance: Occlusion::DEFAULT_DISTANCE,
        }),
        fog: effects & FOG != 0,
        // The page is a quick preview, one sample a pixel even for a
        // model (the command it prints says `--quality draft`).
        sampling: Sampling {
            quality: Some(Quality::Draft),
            ..Sampling::default()
        },
        ..Effects::default()
    };
    voxtrace_flags::render_options(&effects, bounds, model, view)
}
