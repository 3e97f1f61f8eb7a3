//! A note for each flag or effect that changes nothing, so that a user is
//! not left wondering why. The options themselves are the
//! shared crate's ([`voxtrace_flags::render_options`]), from
//! [`Args::effects`](crate::args::Args::effects).

use voxtrace::{CameraSettings, Projection, RenderOptions};

use crate::args::GivenFlags;
use crate::output;

/// Notes for flags a path-traced frame does not use (it lights with its
/// own light rays and bounces).
pub(crate) fn unused_in_path(asked: &RenderOptions) -> Vec<String> {
    let mut unused = Vec::new();
    if asked.shadows {
        unused.push("--shadows");
    }
    if asked.occlusion.is_some() {
        unused.push("--ao");
    }
    if unused.is_empty() {
        return Vec::new();
    }
    vec![format!(
        "the scene is path-traced (its light rays cast the shadows): ignoring {}",
        unused.join(", ")
    )]
}

/// One note for each effect asked for that cannot run, so that a user is
/// not left wondering why it did not.
pub(crate) fn ignored_effects(asked: &RenderOptions) -> Vec<String> {
    let mut notes = Vec::new();
    let runs = asked.effective();
    if asked.shadows && !runs.shadows && asked.sun.is_none() && !(asked.flat || asked.debug) {
        notes.push(
            "the scene has no light (--sun none): its shadows (--shadows, or a model's \
             standard or final quality) trace no rays"
                .into(),
        );
    }
    let view = if asked.flat { "--flat" } else { "--debug" };
    let mut ignored = Vec::new();
    if asked.flat && asked.debug {
        ignored.push("--debug");
    }
    if asked.flat || asked.debug {
        if asked.shadows {
            ignored.push("--shadows");
        }
        if asked.occlusion.is_some() {
            ignored.push("--ao");
        }
        if asked.samples > 1 {
            ignored.push("--spp");
        }
        if asked.fog.is_some() {
            ignored.push("--fog");
        }
    }
    if !ignored.is_empty() {
        notes.push(format!(
            "{view} draws no effects: ignoring {}",
            ignored.join(", ")
        ));
    }
    notes
}

/// One note for each flag `given` that changes nothing for the camera
/// `settings`, the output `format` and the frame's `options` (as
/// resolved: `--quality final` may have turned occlusion on).
pub(crate) fn ignored_flags(
    given: &GivenFlags,
    settings: &CameraSettings,
    format: output::Format,
    options: &RenderOptions,
) -> Vec<String> {
    let mut notes = Vec::new();
    if given.vox && given.seed {
        notes.push("--seed shapes the terrain; a --vox scene does not use it".to_string());
    }
    if given.vox && given.size {
        notes.push("--size sets the terrain's volume; a --vox scene has its own".to_string());
    }
    // (With --ao, a frame that ignores occlusion is noted for --ao.)
    if given.ao_distance && !given.ao && options.occlusion.is_none() {
        notes.push(
            "--ao-distance has no effect without --ao (or --quality standard or final on a face-shaded scene)"
                .to_string(),
        );
    }
    let orthographic = matches!(settings.projection, Projection::Orthographic { .. });
    if given.ortho_height && !orthographic {
        notes.push(
            "--ortho-height has no effect on a perspective camera (add --projection orthographic)"
                .to_string(),
        );
    }
    if given.fov && orthographic {
        notes
            .push("--fov has no effect on an orthographic camera (see --ortho-height)".to_string());
    }
    if given.perspective && orthographic {
        notes.push("--view iso is orthographic: ignoring --projection perspective".to_string());
    }
    if given.transparent && !output::has_alpha(format) {
        notes.push(
            "this format has no alpha channel: --background transparent writes black there"
                .to_string(),
        );
    }
    notes
}
