//! `voxtrace`: renders the seeded terrain to a PNG.
//!
//! Exit codes: 0 on success, 2 on bad arguments, unusable input or output, or
//! a scene that does not fit in memory, with one line on stderr naming the
//! problem.

mod args;
mod memory;
mod output;
mod progress;

use std::process::ExitCode;
use std::time::Instant;

use clap::Parser;
use voxtrace::glam::Vec3;
use voxtrace::{
    Camera, CameraSettings, Fog, IAabb, Occlusion, Rect, RenderOptions, VoxModel, VoxelGenerator,
};
use voxtrace_cli::atomic::{remove_on_signal, AtomicFile};
use voxtrace_cli::{framing, on_threads, BuiltScene};

use args::Args;
use progress::{Progress, Spinner};

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
    // Before any output exists: an interrupted run then removes its
    // temporary file and leaves `--out` as it was.
    let result = remove_on_signal().and_then(|()| run(&args));
    match result {
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

    let options = render_options(args, bounds);
    let mut notes = ignored_effects(&options);
    if args.vox.is_some() && args.seed.is_some() {
        notes.push("--seed shapes the terrain; a --vox scene does not use it".to_string());
    }

    // Check the output first: a bad path fails now, not after the render.
    // The frame goes to a temporary file beside `--out`, which replaces it
    // only once complete; on any error it is removed (dropped uncommitted).
    let format = output::format_of(&args.out)?;
    let file = AtomicFile::create(&args.out)
        .map_err(|e| format!("cannot write --out {}: {e}", args.out.display()))?;
    // Refuse what cannot fit before building it, naming the bytes.
    let voxels = match &subject {
        Subject::Model(model) => Some(model.voxel_count() as u64),
        Subject::Terrain { .. } => None,
    };
    let pixels = u64::from(region.width) * u64::from(region.height);
    memory::budget(args.backend, bounds, voxels, pixels, args.max_memory).check(args.backend)?;
    render_to(
        args, &subject, bounds, &options, &camera, region, file, format,
    )?;
    // Notes only after a success: an error stays the one line on stderr.
    notes.iter().for_each(|note| eprintln!("note: {note}"));
    Ok(())
}

/// The effects the flags ask for; fog thickens over the scene's scale.
fn render_options(args: &Args, bounds: IAabb) -> RenderOptions {
    RenderOptions {
        flat: args.flat,
        debug: args.debug,
        sun: args.sun.map_or(Some(voxtrace::DEFAULT_SUN), |sun| sun.0),
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
    }
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
    camera: &Camera,
    region: Rect,
    mut file: AtomicFile,
    format: output::Format,
) -> Result<(), String> {
    let threaded = args.threads != Some(1);
    let (built, build, rendered) = on_threads(args.threads, || {
        let spinner = Spinner::start(format!("building the {} scene", args.backend.name()));
        let (built, build) = match subject {
            Subject::Terrain { seed } => {
                let terrain = VoxelGenerator::new(*seed);
                BuiltScene::build_from(args.backend, &terrain, bounds, threaded)?
            }
            Subject::Model(model) => {
                BuiltScene::build_from(args.backend, model.as_ref(), bounds, threaded)?
            }
        };
        drop(spinner);
        let progress = Progress::rows(region.height);
        let rendered = built.render(camera, region, options, threaded, &|rows| {
            progress.advance(rows);
        });
        progress.finish();
        Ok((built, build, rendered?))
    })?;

    let encode_started = Instant::now();
    output::write(
        &mut file,
        format,
        region.width,
        region.height,
        &rendered.pixels,
    )
    .and_then(|()| file.commit().map_err(|e| e.to_string()))
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
        eprintln!("storage_bytes: {}", built.scene().storage_bytes());
        eprintln!("mrays_per_s: {mrays:.3}");
    }
    Ok(())
}
