//! What the flags ask the renderer for (the options, a `.vox` file's light
//! and materials folded in), and a note for each flag or effect that
//! changes nothing, so that a user is not left wondering why.

use clap::parser::ValueSource;
use clap::ArgMatches;
use voxtrace::{
    Background, CameraSettings, IAabb, Occlusion, Projection, RenderOptions, SceneMaterials,
    VoxModel,
};
use voxtrace_flags::Effects;

use crate::args::Args;
use crate::args::{BackgroundArg, ProjectionArg};
use crate::output;

/// Whether the flag `id` was given on the command line (not a default).
fn given(matches: &ArgMatches, id: &str) -> bool {
    matches.value_source(id) == Some(ValueSource::CommandLine)
}

/// A model's materials and light list as the renderer takes them.
pub(crate) fn materials_of(model: &VoxModel) -> SceneMaterials<'_> {
    SceneMaterials {
        table: model.materials(),
        emitters: model.emitters(),
    }
}

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

/// The effects the flags (and a .vox file's settings) ask for, as every
/// frontend reads them ([`voxtrace_flags::render_options`]).
pub(crate) fn render_options(
    args: &Args,
    bounds: IAabb,
    model: Option<&VoxModel>,
) -> RenderOptions {
    let BackgroundArg(background) = args.background;
    let effects = Effects {
        flat: args.flat,
        debug: args.debug,
        sun: args.sun.map(|sun| sun.0),
        shadows: args.shadows,
        occlusion: args.ao.map(|rays| Occlusion {
            rays,
            distance: args.ao_distance,
        }),
        samples: args.spp,
        fog: args.fog,
        background,
        bounces: args.bounces,
    };
    voxtrace_flags::render_options(&effects, bounds, model)
}

/// One note for each effect asked for that cannot run, so that a user is
/// not left wondering why it did not.
pub(crate) fn ignored_effects(asked: &RenderOptions) -> Vec<String> {
    let mut notes = Vec::new();
    let runs = asked.effective();
    if asked.shadows && !runs.shadows && asked.sun.is_none() && !(asked.flat || asked.debug) {
        notes.push("the scene has no light (--sun none): --shadows traces no shadow rays".into());
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

/// One note for each flag given that changes nothing.
pub(crate) fn ignored_flags(
    args: &Args,
    matches: &ArgMatches,
    settings: &CameraSettings,
    format: output::Format,
) -> Vec<String> {
    let mut notes = Vec::new();
    let vox = args.vox.is_some();
    if vox && args.seed.is_some() {
        notes.push("--seed shapes the terrain; a --vox scene does not use it".to_string());
    }
    if vox && given(matches, "size") {
        notes.push("--size sets the terrain's volume; a --vox scene has its own".to_string());
    }
    if given(matches, "ao_distance") && args.ao.is_none() {
        notes.push("--ao-distance has no effect without --ao".to_string());
    }
    let orthographic = matches!(settings.projection, Projection::Orthographic { .. });
    if given(matches, "ortho_height") && !orthographic {
        notes.push(
            "--ortho-height has no effect on a perspective camera (add --projection orthographic)"
                .to_string(),
        );
    }
    if given(matches, "fov") && orthographic {
        notes
            .push("--fov has no effect on an orthographic camera (see --ortho-height)".to_string());
    }
    if args.projection == ProjectionArg::Perspective && given(matches, "projection") && orthographic
    {
        notes.push("--view iso is orthographic: ignoring --projection perspective".to_string());
    }
    if args.background.0 == Background::Transparent && !output::has_alpha(format) {
        notes.push(
            "this format has no alpha channel: --background transparent writes black there"
                .to_string(),
        );
    }
    notes
}
