//! `voxtrace`: renders the seeded terrain to a PNG.
//!
//! Exit codes: 0 on success, 2 on bad arguments, unusable input or output, or
//! a scene that does not fit in memory, with one line on stderr naming the
//! problem.

mod args;
mod progress;

use std::fs::File;
use std::io::BufWriter;
use std::process::ExitCode;
use std::time::Instant;

use clap::Parser;
use voxtrace::glam::Vec3;
use voxtrace::rayon::ThreadPoolBuilder;
use voxtrace::{
    encode_png, render_parallel_with_progress, render_span, Camera, CameraSettings, DenseScene,
    Framebuffer, IAabb, OctreeScene, RayStats, Rect, RenderOptions, Scene, VoxelGenerator,
};

use args::{Args, Backend};
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

fn run(args: &Args) -> Result<(), String> {
    let n = args.size;
    let seed = args.seed.unwrap_or_else(|| {
        let seed = random_seed();
        eprintln!("seed: {seed}");
        seed
    });
    let position = args.position.unwrap_or(Vec3::splat((n - 10) as f32));
    let camera = Camera::new(CameraSettings {
        width: args.width,
        height: args.height,
        vertical_fov: args.fov,
        lookfrom: position,
        lookat: args.lookat,
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

    // Open the output first: a bad path fails now, not after the render.
    let file = File::create(&args.out)
        .map_err(|e| format!("cannot write --out {}: {e}", args.out.display()))?;
    let result = render_to(args, seed, &camera, region, file);
    if result.is_err() {
        let _ = std::fs::remove_file(&args.out);
    }
    result
}

/// Builds the scene and renders it: on the calling thread with `--threads 1`,
/// otherwise on a rayon pool of that many threads (all cores by default).
fn render_to(
    args: &Args,
    seed: u64,
    camera: &Camera,
    region: Rect,
    file: File,
) -> Result<(), String> {
    let work = || build_and_render(args, seed, camera, region, file);
    match args.threads {
        Some(1) => work(),
        threads => {
            let count = threads.map_or(0, usize::from); // 0: rayon picks all cores
            ThreadPoolBuilder::new()
                .num_threads(count)
                .build()
                .map_err(|e| format!("cannot start {count} worker threads: {e}"))?
                .install(work)
        }
    }
}

fn build_and_render(
    args: &Args,
    seed: u64,
    camera: &Camera,
    region: Rect,
    file: File,
) -> Result<(), String> {
    let terrain = VoxelGenerator::new(seed);
    let bounds = IAabb::centered(args.size);
    let threaded = args.threads != Some(1);
    let started = Instant::now();
    let describe = |e: voxtrace::Error| {
        let backend = format!("{:?}", args.backend).to_lowercase();
        format!(
            "cannot build the {backend} scene of size {}: {e}",
            args.size
        )
    };
    match args.backend {
        Backend::Dense => {
            let built = if threaded {
                DenseScene::build_parallel(&terrain, bounds)
            } else {
                DenseScene::build(&terrain, bounds)
            };
            let scene = built.map_err(|e| match e {
                voxtrace::Error::OutOfMemory { .. } | voxtrace::Error::SizeOverflow => {
                    // Exact even when it overflows usize: one byte per voxel.
                    let bytes = (2 * u128::from(args.size.unsigned_abs())).pow(3);
                    format!(
                        "the dense array for --size {} needs {bytes} bytes (one per voxel), \
                         more than can be allocated; try --backend octree",
                        args.size
                    )
                }
                e => describe(e),
            })?;
            finish(args, &scene, camera, region, started, file)
        }
        Backend::Octree => {
            let built = if threaded {
                OctreeScene::build_parallel(&terrain, bounds)
            } else {
                OctreeScene::build(&terrain, bounds)
            };
            let scene = built.map_err(describe)?;
            finish(args, &scene, camera, region, started, file)
        }
    }
}

fn finish<S: Scene + Sync>(
    args: &Args,
    scene: &S,
    camera: &Camera,
    region: Rect,
    build_started: Instant,
    file: File,
) -> Result<(), String> {
    let build = build_started.elapsed();
    let options = RenderOptions { flat: args.flat };
    let no_memory = || {
        format!(
            "out of memory: cannot allocate a {}x{} image",
            region.width, region.height
        )
    };

    let progress = Progress::rows(region.height);
    let render_started = Instant::now();
    let (pixels, rays) = if args.threads == Some(1) {
        // The scalar path, row by row for the progress bar.
        let area = region.area().map_err(|e| e.to_string())?;
        let mut pixels = Vec::new();
        pixels.try_reserve_exact(area).map_err(|_| no_memory())?;
        pixels.resize(area, 0);
        let mut rays = RayStats::default();
        let rows = pixels.chunks_exact_mut(region.width as usize);
        for (y, row) in (region.y..).zip(rows) {
            rays += render_span(scene, camera, &options, region.x, y, row);
            progress.advance(1);
        }
        (pixels, rays)
    } else {
        let frame = Framebuffer::new(region.width, region.height).map_err(|_| no_memory())?;
        let rays =
            render_parallel_with_progress(scene, camera, &options, region, &frame, &|rows| {
                progress.advance(rows);
            })
            .map_err(|e| e.to_string())?;
        (frame.into_pixels(), rays)
    };
    let render = render_started.elapsed();
    progress.finish();

    let encode_started = Instant::now();
    encode_png(BufWriter::new(file), region.width, region.height, &pixels)
        .map_err(|e| format!("cannot write --out {}: {e}", args.out.display()))?;
    let encode = encode_started.elapsed();

    if args.stats {
        let ms = |d: std::time::Duration| d.as_secs_f64() * 1e3;
        let mrays = rays.primary_rays as f64 / render.as_secs_f64().max(1e-9) / 1e6;
        eprintln!("build_ms: {:.3}", ms(build));
        eprintln!("render_ms: {:.3}", ms(render));
        eprintln!("encode_ms: {:.3}", ms(encode));
        eprintln!("primary_rays: {}", rays.primary_rays);
        eprintln!("shadow_rays: 0");
        eprintln!("ao_rays: 0");
        eprintln!("storage_bytes: {}", scene.storage_bytes());
        eprintln!("mrays_per_s: {mrays:.3}");
    }
    Ok(())
}
