//! `voxtrace-report speed`: the seed paper's table measured here, with the
//! CLI's build and render path, plus storage, build times, octree scaling,
//! and a plot of render time and memory against scene size; with
//! `--vs-binary`, this revision's binary against another ([`crate::speed_vs`]).

use voxtrace::{Camera, CameraSettings, Rect, RenderOptions, VoxelGenerator};
use voxtrace_cli::{on_threads, Backend, BuiltScene};

use crate::common_args::Output;
use crate::measure::{format_ms, median_of};
use crate::speed_data::{Measured, View, FULL_HD, SCALING_SIZES, TABLE_SIZES, UHD_8K};
use crate::speed_tables::{charts, tables};
use crate::speed_vs::{self, VsArgs};
use crate::surface::surface_voxels;

/// Options of the `speed` report.
#[derive(Debug, clap::Args)]
pub struct SpeedArgs {
    /// 1920x1080 only, the paper's sizes (50, 100, 250), 3 runs: under a
    /// minute on 2 cores (50 s measured with other builds sharing them).
    #[arg(long)]
    quick: bool,
    /// Timed runs per figure (after one untimed warm-up) [default: 5, quick: 3].
    #[arg(long, value_parser = clap::value_parser!(u16).range(1..))]
    runs: Option<u16>,
    /// Terrain seed.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    #[command(flatten)]
    vs: VsArgs,
    #[command(flatten)]
    output: Output,
}

/// Measures the grid, writes `speed.md` and `speed.png` into `--out-dir`.
pub fn run(args: &SpeedArgs) -> Result<(), String> {
    let runs = usize::from(args.runs.unwrap_or(if args.quick { 3 } else { 5 }));
    args.output.prepare()?;
    let binaries = args.vs.binaries()?;

    let (measured, threads) = on_threads(args.output.threads, || {
        let threads = voxtrace::rayon::current_num_threads();
        Ok((measure_all(args, runs)?, threads))
    })?;
    // After the in-process grid, so the processes do not compete with it.
    let vs = match &binaries {
        Some((ours, theirs)) => {
            let threads = args.output.threads.map_or(threads, usize::from);
            let rows = speed_vs::measure((ours, theirs), &measured, args.seed, threads, runs)?;
            Some((rows, theirs, threads))
        }
        None => None,
    };

    let mut command = format!(
        "cargo run --release -p voxtrace-report -- speed{}",
        if args.quick { " --quick" } else { "" }
    );
    if let Some(theirs) = &args.vs.vs_binary {
        command.push_str(&format!(" --vs-binary {}", theirs.display()));
    }
    let mut markdown = tables(&measured, threads, runs, args.seed, &command);
    if let Some((rows, theirs, threads)) = &vs {
        markdown.push('\n');
        markdown.push_str(&speed_vs::table(rows, theirs, *threads, runs));
    }
    markdown.push_str(&embree_tables());
    args.output
        .write("speed", &markdown, &charts(&measured, threads))
}

/// The tables `benches/embree/run.sh` left in `target/embree/SIZE/` (Intel
/// Embree on the same terrain and rays, one thread), smallest size first,
/// under one heading; nothing when the script has not run.
fn embree_tables() -> String {
    let Ok(dir) = std::fs::read_dir("target/embree") else {
        return String::new();
    };
    let mut found: Vec<(i64, String)> = dir
        .filter_map(Result::ok)
        .filter_map(|entry| {
            let size = entry.file_name().to_str()?.parse().ok()?;
            let table = std::fs::read_to_string(entry.path().join("table.md")).ok()?;
            Some((size, table))
        })
        .collect();
    if found.is_empty() {
        return String::new();
    }
    found.sort();
    let mut text =
        String::from("\n### Against Intel Embree, one thread (`benches/embree/run.sh SIZE`)\n");
    for (_, table) in found {
        text.push('\n');
        text.push_str(&table);
    }
    text
}

fn measure_all(args: &SpeedArgs, runs: usize) -> Result<Vec<Measured>, String> {
    let sizes: Vec<i32> = if args.quick {
        TABLE_SIZES.to_vec()
    } else {
        TABLE_SIZES.iter().chain(&SCALING_SIZES).copied().collect()
    };
    let terrain = VoxelGenerator::new(args.seed);
    let mut measured = Vec::new();
    for size in sizes {
        let surface = surface_voxels(&terrain, size);
        let in_table = TABLE_SIZES.contains(&size);
        let backends: &[Backend] = if in_table {
            &[Backend::Dense, Backend::Octree]
        } else {
            &[Backend::Octree]
        };
        let resolutions: &[(u32, u32)] = if in_table && !args.quick {
            &[FULL_HD, UHD_8K]
        } else {
            &[FULL_HD]
        };
        for &backend in backends {
            measured.push(measure_one(
                args.seed,
                size,
                backend,
                resolutions,
                runs,
                surface,
            )?);
        }
    }
    Ok(measured)
}

fn measure_one(
    seed: u64,
    size: i32,
    backend: Backend,
    resolutions: &[(u32, u32)],
    runs: usize,
    surface_voxels: u64,
) -> Result<Measured, String> {
    let mut scene = None;
    let build_ms = median_of(runs, || {
        let (built, elapsed) = BuiltScene::build(backend, size, seed, true)?;
        scene = Some(built);
        Ok(elapsed)
    })?;
    let scene = scene.ok_or("no scene was built")?;
    let name = backend.name();
    eprintln!("size {size} {name}: build {}", format_ms(build_ms));
    let options = RenderOptions::default();
    let mut renders = Vec::new();
    for &(width, height) in resolutions {
        for view in [View::Paper, View::Above] {
            let camera = camera(size, (width, height), view)?;
            let ms = median_of(runs, || {
                let rendered = scene.render_with(
                    None,
                    &camera,
                    Rect::full(&camera),
                    &options,
                    true,
                    &|_| {},
                )?;
                Ok(rendered.elapsed)
            })?;
            eprintln!(
                "size {size} {name} {width}x{height} {}: render {}",
                view.name(),
                format_ms(ms)
            );
            renders.push(((width, height), view, ms));
        }
    }
    Ok(Measured {
        size,
        backend,
        build_ms,
        bytes: scene.scene().storage_bytes() as u64,
        surface_voxels,
        renders,
    })
}

fn camera(size: i32, (width, height): (u32, u32), view: View) -> Result<Camera, String> {
    let view = match view {
        View::Paper => CameraSettings::paper(size),
        View::Above => CameraSettings::above(size),
    };
    Camera::new(CameraSettings {
        width,
        height,
        ..view
    })
    .map_err(|e| e.to_string())
}
