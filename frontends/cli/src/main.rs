//! `voxtrace`: renders the seeded terrain, or a `.vox` scene, to an image.
//!
//! Exit codes: 0 on success, 2 on bad arguments, unusable input or output, or
//! a scene that does not fit in memory, with one line on stderr naming the
//! problem.

mod args;
mod effects;
mod farm;
mod memory;
mod output;
mod progress;
mod view;
mod vox_camera;

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::{Duration, Instant};

use clap::{ArgMatches, CommandFactory, FromArgMatches};
use voxtrace::glam::Vec3;
use voxtrace::{
    Background, Camera, CameraSettings, EffectPlan, IAabb, Look, RayStats, Rect, RenderOptions,
    VoxModel, VoxelGenerator, VoxelSource,
};
use voxtrace_cli::atomic::{exit_with_error, remove_on_signal, AtomicFile};
use voxtrace_cli::errors::{self, escape_controls};
use voxtrace_cli::say;
use voxtrace_cli::{
    export_vox, frame_path, on_threads, terrain_box, turntable, BuiltScene, FrameRange,
};
use voxtrace_flags::{describe, Boxes, Stage};

use args::{Args, Command};
use effects::{ignored_effects, ignored_flags, materials_of, render_options, unused_in_path};
use progress::{Progress, Spinner};
use view::camera_settings;

fn main() -> ExitCode {
    let argv: Vec<String> = std::env::args_os()
        .map(|a| a.to_string_lossy().into_owned())
        .collect();
    let parsed = Args::command()
        .try_get_matches_from(&argv)
        .and_then(|m| Args::from_arg_matches(&m).map(|a| (a, m)));
    let (args, matches) = match parsed {
        Ok(parsed) => parsed,
        Err(e) => return errors::clap_failure(&e, &argv),
    };
    if let Some(Command::Stitch(stitch)) = &args.command {
        return match farm::run_stitch(stitch) {
            Ok(()) => ExitCode::SUCCESS,
            Err(message) => exit_with_error(&message),
        };
    }
    // Before any output exists: an interrupted run then removes its
    // temporary files and leaves every output file as it was.
    match remove_on_signal().and_then(|()| run(&args, &matches)) {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => exit_with_error(&message),
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
    /// The seeded terrain; a `random` seed is printed.
    Terrain { seed: u64, random: bool },
    /// A loaded `.vox` scene (boxed: its palette alone is 768 bytes).
    Model(Box<VoxModel>),
}

impl Subject {
    /// The material at `pos`, to tell a camera inside a voxel.
    fn material(&self, pos: voxtrace::glam::IVec3) -> u8 {
        match self {
            Subject::Terrain { seed, .. } => VoxelGenerator::new(*seed).material(pos),
            Subject::Model(model) => model.material(pos),
        }
    }
}

/// The terrain's seed, and whether it was drawn at random (and so must be
/// printed, once the run is known to go ahead).
fn terrain_seed(args: &Args) -> (u64, bool) {
    match args.seed {
        Some(seed) => (seed, false),
        None => (random_seed(), true),
    }
}

fn run(args: &Args, matches: &ArgMatches) -> Result<(), String> {
    if let Some(path) = &args.export_vox {
        return export(args, path);
    }
    farm::check_flags(args)?;
    if args.farm.tiles.is_some() && args.frames.is_some() {
        return Err("--tiles renders one tile of a still: it does not take --frames".into());
    }
    let subject = match &args.vox {
        Some(path) => Subject::Model(Box::new(
            VoxModel::load(path)
                .map_err(|e| format!("cannot load --vox {}: {e}", path.display()))?,
        )),
        None => {
            let (seed, random) = terrain_seed(args);
            Subject::Terrain { seed, random }
        }
    };
    let (bounds, stage, cameras) = match &subject {
        Subject::Terrain { .. } => (
            IAabb::centered(args.size),
            Stage {
                boxes: Boxes::Bounds(IAabb::centered(args.size)),
                target: Vec3::ZERO,
                default_position: Some(CameraSettings::paper(args.size).lookfrom),
            },
            None,
        ),
        Subject::Model(model) => (
            model.bounds(),
            Stage {
                boxes: Boxes::Model(model),
                target: (model.bounds().min + model.bounds().max).as_vec3() * 0.5,
                default_position: None,
            },
            args.vox.as_deref().map(|path| (path, model.as_ref())),
        ),
    };
    let settings = camera_settings(args, &stage, cameras)?;
    let frames = args.frames.unwrap_or(1);
    let range = match farm::task_frames(args, args.frames)? {
        Some(range) => range,
        None => args.frame_range.unwrap_or(FrameRange::all(frames)),
    };
    range.check_within(frames)?;
    // Every frame's camera, checked before anything is built.
    let cameras = range
        .frames()
        .map(|k| {
            let s = turntable(settings, k, frames);
            Camera::new(s).map(|c| (k, s, c)).map_err(|e| e.to_string())
        })
        .collect::<Result<Vec<_>, String>>()?;
    let first = &cameras[0].2;
    let model = match &subject {
        Subject::Model(model) => Some(model.as_ref()),
        Subject::Terrain { .. } => None,
    };
    let options = render_options(args, bounds, model);
    let plan = EffectPlan::new(&options, model.map(materials_of));
    let tile = farm::select(args, first, &options)?;
    let region = match &tile {
        Some(tile) => tile.placement.rect,
        None => args.region.unwrap_or(Rect::full(first)),
    };
    region.validate(first).map_err(|_| {
        format!(
            "--region {},{},{},{} does not fit in the {}x{} frame",
            region.x, region.y, region.width, region.height, args.width, args.height
        )
    })?;

    let out = tile.as_ref().map_or(&args.out, |tile| &tile.out);
    let format = output::format_of(out, args.format)?;
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
    notes.extend(ignored_flags(args, matches, &settings, format));

    // Check the output first: a bad path fails now, not after the render.
    let to_stdout = output::is_stdout(out);
    if to_stdout && tile.is_some() {
        return Err(
            "--tiles writes a part file for `voxtrace stitch`: --out - cannot be one".into(),
        );
    }
    if to_stdout && args.frames.is_some() {
        return Err("--frames writes one file per frame: --out - cannot hold them".into());
    }
    if to_stdout {
        output::check_stdout()?;
    }
    let paths: Vec<PathBuf> = if args.frames.is_some() {
        range
            .frames()
            .map(|k| frame_path(&args.out, k))
            .collect::<Result<_, _>>()?
    } else {
        vec![out.clone()]
    };
    // Refuse what cannot fit before building it, naming the bytes.
    let loaded = match &subject {
        Subject::Model(model) => Some((model.voxel_count() as u64, model.heap_bytes() as u128)),
        Subject::Terrain { .. } => None,
    };
    let pixels = u64::from(region.width) * u64::from(region.height);
    let encoder = match &tile {
        // A part is a PNG with its placement, streamed by the same encoder.
        Some(_) => output::encoder_bytes(output::Format::Png, region.width, region.height, true),
        None => {
            let alpha = options.background == Background::Transparent;
            output::encoder_bytes(format, region.width, region.height, alpha)
        }
    };
    let frame = (pixels, encoder);
    memory::budget(args.backend, bounds, loaded, frame, args.max_memory).check(args.backend)?;
    // The first file is a temporary one beside its path from now on, which
    // replaces the path only once complete; on any error it is removed.
    let first_file = if to_stdout {
        None
    } else {
        Some(output::create(&paths[0])?)
    };
    let job = Job {
        args,
        subject: &subject,
        bounds,
        options: &options,
        plan: &plan,
        region,
        format,
        tile: tile.as_ref(),
    };
    job.render_all(&cameras, &paths, first_file, &mut notes)?;
    // The seed, warnings and notes only after a success: an error stays
    // the one line on stderr. Escaped: a path a warning quotes cannot
    // start a line of its own.
    if let Subject::Terrain { seed, random: true } = subject {
        say!("seed: {seed}");
    }
    warnings
        .iter()
        .for_each(|w| say!("warning: {}", escape_controls(w)));
    notes
        .iter()
        .for_each(|note| say!("note: {}", escape_controls(note)));
    Ok(())
}

/// `--export-vox`: the terrain as a `.vox` file.
fn export(args: &Args, path: &Path) -> Result<(), String> {
    let (seed, random) = terrain_seed(args);
    let mut bytes = Vec::new();
    let terrain = VoxelGenerator::new(seed);
    let count = export_vox(&terrain, terrain_box(&terrain, args.size), &mut bytes)?;
    std::fs::write(path, &bytes)
        .map_err(|e| format!("cannot write --export-vox {}: {e}", path.display()))?;
    // Only now: an error stays the one line on stderr.
    if random {
        say!("seed: {seed}");
    }
    if args.stats {
        say!("voxels: {count}");
        say!("file_bytes: {}", bytes.len());
    }
    Ok(())
}

/// What every frame of one run shares.
struct Job<'a> {
    args: &'a Args,
    subject: &'a Subject,
    bounds: IAabb,
    options: &'a RenderOptions,
    /// The effects the frames simulate, for `--stats`.
    plan: &'a EffectPlan,
    region: Rect,
    format: output::Format,
    /// The render-farm tile this run renders, written as a part.
    tile: Option<&'a farm::TileJob>,
}

impl Job<'_> {
    /// Writes one frame's pixels into `first` (the first path's file,
    /// created up front) or else `path` (standard output for `-`), in the
    /// run's format, as a part with `--tiles`; a file replaces its path
    /// only once written whole.
    fn write(
        &self,
        first: Option<AtomicFile>,
        path: &Path,
        pixels: Vec<u32>,
    ) -> Result<(), String> {
        let region = self.region;
        let alpha = self.options.background == Background::Transparent;
        let failed = |e: String| format!("cannot write --out {}: {e}", path.display());
        if first.is_none() && output::is_stdout(path) {
            let out = output::stdout().map_err(|e| failed(e.to_string()))?;
            return output::write(out, self.format, region.width, region.height, pixels, alpha)
                .map_err(failed);
        }
        let mut file = match first {
            Some(file) => file,
            None => output::create(path)?,
        };
        match self.tile {
            Some(tile) => farm::write_tile(&mut file, tile, &pixels),
            None => output::write(
                &mut file,
                self.format,
                region.width,
                region.height,
                pixels,
                alpha,
            ),
        }
        .and_then(|()| file.commit().map_err(|e| e.to_string()))
        .map_err(failed)
    }

    /// Builds the scene once and renders every frame's camera into its
    /// path (`first` is the first path, already created; `None` for
    /// standard output), then prints `--stats`.
    fn render_all(
        &self,
        cameras: &[(u32, CameraSettings, Camera)],
        paths: &[PathBuf],
        first: Option<AtomicFile>,
        notes: &mut Vec<String>,
    ) -> Result<(), String> {
        let args = self.args;
        let threaded = args.threads != Some(1);
        let region = self.region;
        let inside = cameras.iter().any(|(_, s, _)| {
            let cell = s.lookfrom.floor().as_ivec3();
            self.bounds.contains(cell) && self.subject.material(cell) != 0
        });
        if inside {
            notes.push(
                "the camera starts inside a solid voxel: its rays see only that voxel (move it with --position)"
                    .to_string(),
            );
        }
        let mut first = first;
        let (built, build, totals) = on_threads(args.threads, || {
            let spinner = Spinner::start(format!("building the {} scene", args.backend.name()));
            let (built, build, materials) = match self.subject {
                Subject::Terrain { seed, .. } => {
                    let terrain = VoxelGenerator::new(*seed);
                    let (built, build) =
                        BuiltScene::build_from(args.backend, &terrain, self.bounds, threaded)?;
                    (built, build, None)
                }
                Subject::Model(model) => {
                    let (built, build) = BuiltScene::build_from(
                        args.backend,
                        model.as_ref(),
                        self.bounds,
                        threaded,
                    )?;
                    (built, build, Some(materials_of(model)))
                }
            };
            drop(spinner);
            let total_rows = region.height.saturating_mul(cameras.len() as u32);
            let progress = Progress::rows(total_rows);
            let mut totals = (RayStats::default(), Duration::ZERO, Duration::ZERO);
            for ((_, _, camera), path) in cameras.iter().zip(paths) {
                let rendered =
                    built.render_with(materials, camera, region, self.options, threaded, &|rows| {
                        progress.advance(rows);
                    });
                let rendered = match rendered {
                    Ok(r) => r,
                    Err(e) => {
                        progress.finish();
                        return Err(e);
                    }
                };
                let started = Instant::now();
                if let Err(e) = self.write(first.take(), path, rendered.pixels) {
                    progress.finish();
                    return Err(e);
                }
                totals.0 += rendered.rays;
                totals.1 += rendered.elapsed;
                totals.2 += started.elapsed();
            }
            progress.finish();
            Ok((built, build, totals))
        })?;
        if args.stats {
            let (rays, render, encode) = totals;
            let ms = |d: Duration| d.as_secs_f64() * 1e3;
            let mrays = rays.primary_rays as f64 / render.as_secs_f64().max(1e-9) / 1e6;
            let v = |v: voxtrace::glam::IVec3| format!("{},{},{}", v.x, v.y, v.z);
            say!("build_ms: {:.3}", ms(build));
            say!("render_ms: {:.3}", ms(render));
            say!("encode_ms: {:.3}", ms(encode));
            say!("primary_rays: {}", rays.primary_rays);
            say!("shadow_rays: {}", rays.shadow_rays);
            say!("ao_rays: {}", rays.ao_rays);
            say!("reflection_rays: {}", rays.reflection_rays);
            say!("refraction_rays: {}", rays.refraction_rays);
            say!("light_rays: {}", rays.light_rays);
            say!("effects: {}", self.plan);
            say!("storage_bytes: {}", built.scene().storage_bytes());
            say!("mrays_per_s: {mrays:.3}");
            say!("scene_min: {}", v(self.bounds.min));
            say!("scene_max: {}", v(self.bounds.max));
            say!("camera: {}", describe(&cameras[0].1, args.up.is_some()));
        }
        Ok(())
    }
}
