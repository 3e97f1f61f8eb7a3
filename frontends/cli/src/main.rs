//! `voxtrace`: renders the seeded terrain to a PNG.
//!
//! Exit codes: 0 on success, 2 on bad arguments, unusable input or output, or
//! a scene that does not fit in memory, with one line on stderr naming the
//! problem.

mod args;
mod output;
mod progress;

use std::fs::File;
use std::process::ExitCode;
use std::time::Instant;

use clap::Parser;
use voxtrace::glam::Vec3;
use voxtrace::{
    Bounces, Camera, CameraSettings, EffectPlan, Fog, IAabb, Lighting, Look, Occlusion, Rect,
    RenderOptions, SceneMaterials, VoxModel, VoxelGenerator,
};
use voxtrace_cli::{framing, on_threads, BuiltScene};

use args::Args;
use progress::Progress;

fn main() -> ExitCode {
    let args = match Args::try_parse() {
        Ok(args) => args,
        Err(e) => {
            use clap::error::ErrorKind;
            if matches!(e.kind(), ErrorKind::DisplayHelp | ErrorKind::DisplayVersion) {
                let _ = e.print();
                return ExitCode::SUCCESS;
            }
            // One line: clap's first line names the flag and the bad value.
            let text = e.render().to_string();
            eprintln!(
                "{}",
                text.lines().next().unwrap_or("error: invalid arguments")
            );
            return ExitCode::from(2);
        }
    };
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::from(2)
        }
    }
}

/// A seed from the clock and process id: different per run, printed so the
/// render can be reproduced.
fn random_seed() -> u64 {
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_nanos() as u64);
    let mut mix = voxtrace::SplitMix64::new(nanos ^ u64::from(std::process::id()) << 32);
    mix.next_u64() >> 1 // keep it readable as a positive i64 too
}

/// What the CLI renders.
enum Subject {
    /// The seeded terrain.
    Terrain { seed: u64 },
    /// A loaded `.vox` scene (boxed: its palette alone is 768 bytes).
    Model(Box<VoxModel>),
}

fn run(args: &Args) -> Result<(), String> {
    let subject = match &args.vox {
        Some(path) => Subject::Model(Box::new(
            VoxModel::load(path)
                .map_err(|e| format!("cannot load --vox {}: {e}", path.display()))?,
        )),
        None => Subject::Terrain {
            seed: args.seed.unwrap_or_else(|| {
                let seed = random_seed();
                eprintln!("seed: {seed}");
                seed
            }),
        },
    };
    let (bounds, position, lookat) = match &subject {
        Subject::Terrain { .. } => (
            IAabb::centered(args.size),
            args.position
                .unwrap_or(CameraSettings::paper(args.size).lookfrom),
            args.lookat.unwrap_or(Vec3::ZERO),
        ),
        Subject::Model(model) => {
            let aspect = args.width as f32 / args.height as f32;
            let (eye, center) = framing(model.bounds(), args.fov, aspect);
            (
                model.bounds(),
                args.position.unwrap_or(eye),
                args.lookat.unwrap_or(center),
            )
        }
    };
    let camera = Camera::new(CameraSettings {
        width: args.width,
        height: args.height,
        vertical_fov: args.fov,
        lookfrom: position,
        lookat,
        ..CameraSettings::default()
    })
    .map_err(|e| e.to_string())?;
    let region = args.region.unwrap_or(Rect::full(&camera));
    region.validate(&camera).map_err(|_| {
        format!(
            "--region {},{},{},{} does not fit in the {}x{} frame",
            region.x, region.y, region.width, region.height, args.width, args.height
        )
    })?;

    let model = match &subject {
        Subject::Model(model) => Some(model.as_ref()),
        Subject::Terrain { .. } => None,
    };
    let options = render_options(args, bounds, model);
    let plan = EffectPlan::new(&options, model.map(materials_of));
    let mut notes = ignored_effects(&options);
    if plan.look == Look::Path {
        notes.extend(unused_in_path(&options));
    }
    // The file's MATL values that could not be used as they are.
    let warnings: Vec<String> = match (model, &args.vox) {
        (Some(model), Some(path)) => model
            .warnings()
            .iter()
            .map(|w| format!("{}: {w}", path.display()))
            .collect(),
        _ => Vec::new(),
    };
    if args.vox.is_some() && args.seed.is_some() {
        notes.push("--seed shapes the terrain; a --vox scene does not use it".to_string());
    }

    // Check the output first: a bad path fails now, not after the render.
    let format = output::format_of(&args.out)?;
    let file = File::create(&args.out)
        .map_err(|e| format!("cannot write --out {}: {e}", args.out.display()))?;
    let result = render_to(
        args, &subject, bounds, &options, &plan, &camera, region, file, format,
    );
    match result {
        // Notes only after a success: an error stays the one line on stderr.
        Ok(()) => {
            warnings.iter().for_each(|w| eprintln!("warning: {w}"));
            notes.iter().for_each(|note| eprintln!("note: {note}"));
        }
        Err(_) => {
            let _ = std::fs::remove_file(&args.out);
        }
    }
    result
}

/// A model's materials and light list as the renderer takes them.
fn materials_of(model: &VoxModel) -> SceneMaterials<'_> {
    SceneMaterials {
        table: model.materials(),
        emitters: model.emitters(),
    }
}

/// The light of path-traced frames: the file's sun, sky and bounces where
/// it has them, `--bounces` over the file's.
fn lighting(args: &Args, model: Option<&VoxModel>) -> Lighting {
    let mut light = Lighting::DEFAULT;
    let settings = model.map(|m| *m.settings()).unwrap_or_default();
    if let (Some(sun), None) = (settings.sun, args.sun) {
        light.sun_intensity = sun.intensity;
        light.sun_radius = sun.radius;
    }
    light.sky = settings.sky.or(light.sky);
    if let Some((diffuse, specular)) = settings.bounces {
        light.bounces = Bounces { diffuse, specular };
    }
    if let Some(n) = args.bounces {
        light.bounces = Bounces {
            diffuse: n,
            specular: n,
        };
        light.path_trace = true;
    }
    light
}

/// The effects the flags (and a .vox file's settings) ask for; fog
/// thickens over the scene's scale.
fn render_options(args: &Args, bounds: IAabb, model: Option<&VoxModel>) -> RenderOptions {
    let file_sun = model.and_then(|m| m.settings().sun).map(|s| s.direction);
    RenderOptions {
        flat: args.flat,
        debug: args.debug,
        sun: args
            .sun
            .map_or(Some(file_sun.unwrap_or(voxtrace::DEFAULT_SUN)), |sun| sun.0),
        shadows: args.shadows,
        occlusion: args.ao.map(|rays| Occlusion {
            rays,
            distance: args.ao_distance,
        }),
        samples: args.spp,
        fog: args.fog.then_some(Fog {
            // 3 x --size for the terrain: one and a half times the volume's side.
            distance: 1.5 * bounds.size().max_element() as f32,
        }),
        lighting: lighting(args, model),
    }
}

/// Notes for flags a path-traced frame does not use (it lights with its
/// own light rays and bounces).
fn unused_in_path(asked: &RenderOptions) -> Vec<String> {
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
fn ignored_effects(asked: &RenderOptions) -> Vec<String> {
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

/// Builds the scene and renders it with the thread count of `--threads`,
/// then writes the PNG and, with `--stats`, the figures.
#[allow(clippy::too_many_arguments)] // one call site; a struct would only rename them
fn render_to(
    args: &Args,
    subject: &Subject,
    bounds: IAabb,
    options: &RenderOptions,
    plan: &EffectPlan,
    camera: &Camera,
    region: Rect,
    file: File,
    format: output::Format,
) -> Result<(), String> {
    let threaded = args.threads != Some(1);
    let (built, build, rendered) = on_threads(args.threads, || {
        let (built, build, materials) = match subject {
            Subject::Terrain { seed } => {
                let terrain = VoxelGenerator::new(*seed);
                let (built, build) =
                    BuiltScene::build_from(args.backend, &terrain, bounds, threaded)?;
                (built, build, None)
            }
            Subject::Model(model) => {
                let (built, build) =
                    BuiltScene::build_from(args.backend, model.as_ref(), bounds, threaded)?;
                (built, build, Some(materials_of(model)))
            }
        };
        let progress = Progress::rows(region.height);
        let rendered = built.render_with(materials, camera, region, options, threaded, &|rows| {
            progress.advance(rows);
        });
        progress.finish();
        Ok((built, build, rendered?))
    })?;

    let encode_started = Instant::now();
    output::write(file, format, region.width, region.height, &rendered.pixels)
        .map_err(|e| format!("cannot write --out {}: {e}", args.out.display()))?;
    let encode = encode_started.elapsed();

    if args.stats {
        let ms = |d: std::time::Duration| d.as_secs_f64() * 1e3;
        let rays = rendered.rays;
        let mrays = rays.primary_rays as f64 / rendered.elapsed.as_secs_f64().max(1e-9) / 1e6;
        eprintln!("build_ms: {:.3}", ms(build));
        eprintln!("render_ms: {:.3}", ms(rendered.elapsed));
        eprintln!("encode_ms: {:.3}", ms(encode));
        eprintln!("primary_rays: {}", rays.primary_rays);
        eprintln!("shadow_rays: {}", rays.shadow_rays);
        eprintln!("ao_rays: {}", rays.ao_rays);
        eprintln!("reflection_rays: {}", rays.reflection_rays);
        eprintln!("refraction_rays: {}", rays.refraction_rays);
        eprintln!("light_rays: {}", rays.light_rays);
        eprintln!("effects: {plan}");
        eprintln!("storage_bytes: {}", built.scene().storage_bytes());
        eprintln!("mrays_per_s: {mrays:.3}");
    }
    Ok(())
}
