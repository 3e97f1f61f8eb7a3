//! `voxtrace-report speed`: the seed paper's table measured here, with the
//! CLI's build and render path, plus storage, build times, octree scaling,
//! and a plot of render time and memory against scene size.

use std::fmt::Write as _;

use voxtrace::{Camera, CameraSettings, Rect, RenderOptions, VoxelGenerator};
use voxtrace_cli::{above_position, on_threads, paper_position, Backend, BuiltScene};

use crate::common_args::Output;
use crate::measure::{cpu_name, format_bytes, format_ms, median_of};
use crate::plot::{Chart, Line, Series};
use crate::surface::surface_voxels;
use plotters::chart::SeriesLabelPosition;

/// Options of the `speed` report.
#[derive(Debug, clap::Args)]
pub struct SpeedArgs {
    /// 1920x1080 only, sizes up to 250, 3 runs: a few minutes.
    #[arg(long)]
    quick: bool,
    /// Timed runs per figure (after one untimed warm-up) [default: 5, quick: 3].
    #[arg(long, value_parser = clap::value_parser!(u16).range(1..))]
    runs: Option<u16>,
    /// Terrain seed.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    #[command(flatten)]
    output: Output,
}

/// The seed paper's scene sizes, and the octree-only sizes past them.
const TABLE_SIZES: [i32; 3] = [50, 100, 250];
const SCALING_SIZES: [i32; 3] = [500, 1024, 2048];
const FULL_HD: (u32, u32) = (1920, 1080);
const UHD_8K: (u32, u32) = (7680, 4320);

/// The seed paper's figures (Ryzen 5 2600, 6 cores / 12 threads), per size:
/// 1080p dense, 1080p octree, 8K dense, 8K octree, in milliseconds.
const PAPER_MS: [(i32, [f64; 4]); 3] = [
    (50, [37.557, 211.86, 261.11, 2523.0]),
    (100, [192.48, 247.86, 3020.3, 3552.6]),
    (250, [811.93, 122.55, 10016.0, 2099.5]),
];
const PAPER_CORES: f64 = 6.0;

/// Where the camera stands.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum View {
    /// The paper's: `size - 10` on every axis.
    Paper,
    /// Above the terrain, outside the volume.
    Above,
}

impl View {
    fn name(self) -> &'static str {
        match self {
            View::Paper => "paper camera",
            View::Above => "camera above",
        }
    }
}

/// The figures for one storage at one size.
struct Measured {
    size: i32,
    backend: Backend,
    build_ms: f64,
    bytes: u64,
    surface_voxels: u64,
    /// Median render time per (resolution, view).
    renders: Vec<((u32, u32), View, f64)>,
}

impl Measured {
    fn render_ms(&self, resolution: (u32, u32), view: View) -> Option<f64> {
        self.renders
            .iter()
            .find(|(r, v, _)| *r == resolution && *v == view)
            .map(|m| m.2)
    }
}

/// Measures the grid, writes `speed.md` and `speed.png` into `--out-dir`.
pub fn run(args: &SpeedArgs) -> Result<(), String> {
    let runs = usize::from(args.runs.unwrap_or(if args.quick { 3 } else { 5 }));
    args.output.prepare()?;

    let (measured, threads) = on_threads(args.output.threads, || {
        let threads = voxtrace::rayon::current_num_threads();
        Ok((measure_all(args, runs)?, threads))
    })?;

    let command = format!(
        "cargo run --release -p voxtrace-report -- speed{}",
        if args.quick { " --quick" } else { "" }
    );
    let markdown = tables(&measured, threads, runs, args.seed, &command);
    args.output
        .write("speed", &markdown, &charts(&measured, threads))
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
                let rendered =
                    scene.render(&camera, Rect::full(&camera), &options, true, &|_| {})?;
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
    let lookfrom = match view {
        View::Paper => paper_position(size),
        View::Above => above_position(size),
    };
    Camera::new(CameraSettings {
        width,
        height,
        lookfrom,
        ..CameraSettings::default()
    })
    .map_err(|e| e.to_string())
}

fn find(measured: &[Measured], size: i32, backend: Backend) -> Option<&Measured> {
    measured
        .iter()
        .find(|m| m.size == size && m.backend == backend)
}

/// `dense / octree`: above 1 the octree is faster.
fn ratio(dense: Option<f64>, octree: Option<f64>) -> String {
    match (dense, octree) {
        (Some(d), Some(o)) if o > 0.0 => format!("{:.2}", d / o),
        _ => "—".to_string(),
    }
}

fn cell(ms: Option<f64>) -> String {
    ms.map_or_else(|| "—".to_string(), format_ms)
}

fn tables(measured: &[Measured], threads: usize, runs: usize, seed: u64, command: &str) -> String {
    let mut md = String::new();
    let _ = writeln!(
        md,
        "Measured by `{command}` on {} with {threads} threads: seed {seed}, \
         median of {runs} runs after a warm-up, the CLI's build and render path \
         (parallel build, `render_parallel`, frame allocation included).\n",
        cpu_name()
    );
    for view in [View::Paper, View::Above] {
        let _ = writeln!(
            md,
            "{}\n",
            match view {
                View::Paper => "Render time per frame, the paper's camera at (size - 10)·(1, 1, 1); ratio = dense / octree (above 1: the octree is faster):",
                View::Above => "The same with the camera above the terrain, outside the volume:",
            }
        );
        let _ = writeln!(
            md,
            "| size | 1920x1080 dense | 1920x1080 octree | ratio | 7680x4320 dense | 7680x4320 octree | ratio |\n|---|---|---|---|---|---|---|"
        );
        for size in TABLE_SIZES {
            let (Some(dense), Some(octree)) = (
                find(measured, size, Backend::Dense),
                find(measured, size, Backend::Octree),
            ) else {
                continue;
            };
            let mut row = format!("| {size} ");
            for res in [FULL_HD, UHD_8K] {
                let (d, o) = (dense.render_ms(res, view), octree.render_ms(res, view));
                let _ = write!(row, "| {} | {} | {} ", cell(d), cell(o), ratio(d, o));
            }
            let _ = writeln!(md, "{row}|");
        }
        md.push('\n');
    }

    let _ = writeln!(
        md,
        "Per core against the paper (6 cores / 12 threads; here {threads} threads), 1920x1080, the paper's camera: \
         paper ms × 6 / (ms here × {threads}), above 1 means more frames per core here:\n"
    );
    let _ = writeln!(
        md,
        "| size | paper dense | here dense | per core | paper octree | here octree | per core |\n|---|---|---|---|---|---|---|"
    );
    for (size, paper) in PAPER_MS {
        let per_core = |paper_ms: f64, here: Option<f64>| {
            here.map_or_else(
                || "—".to_string(),
                |ms| format!("{:.1}×", paper_ms * PAPER_CORES / (ms * threads as f64)),
            )
        };
        let here =
            |backend| find(measured, size, backend).and_then(|m| m.render_ms(FULL_HD, View::Paper));
        let (d, o) = (here(Backend::Dense), here(Backend::Octree));
        let _ = writeln!(
            md,
            "| {size} | {} | {} | {} | {} | {} | {} |",
            format_ms(paper[0]),
            cell(d),
            per_core(paper[0], d),
            format_ms(paper[1]),
            cell(o),
            per_core(paper[1], o),
        );
    }
    md.push('\n');

    let _ = writeln!(
        md,
        "Storage (`storage_bytes`, as `--stats` prints it) and build time; surface voxels are the solid voxels with a face on empty space or on the volume's boundary:\n"
    );
    let _ = writeln!(
        md,
        "| size | dense bytes | dense build | octree bytes | octree build | surface voxels | octree bytes per surface voxel |\n|---|---|---|---|---|---|---|"
    );
    let sizes: Vec<i32> = {
        let mut s: Vec<i32> = measured.iter().map(|m| m.size).collect();
        s.dedup();
        s
    };
    for &size in &sizes {
        let dense = find(measured, size, Backend::Dense);
        let Some(octree) = find(measured, size, Backend::Octree) else {
            continue;
        };
        let _ = writeln!(
            md,
            "| {size} | {} | {} | {} | {} | {} | {:.2} |",
            dense.map_or_else(|| "—".to_string(), |d| format_bytes(d.bytes)),
            cell(dense.map(|d| d.build_ms)),
            format_bytes(octree.bytes),
            format_ms(octree.build_ms),
            format_bytes(octree.surface_voxels),
            octree.bytes as f64 / octree.surface_voxels.max(1) as f64,
        );
    }
    md.push('\n');

    let scaling: Vec<&Measured> = measured
        .iter()
        .filter(|m| SCALING_SIZES.contains(&m.size))
        .collect();
    if !scaling.is_empty() {
        let _ = writeln!(
            md,
            "The octree alone past the paper's sizes (a volume of (2·size)^3 voxels), 1920x1080:\n"
        );
        let _ = writeln!(
            md,
            "| size | volume | build | bytes | paper camera | camera above |\n|---|---|---|---|---|---|"
        );
        for m in scaling {
            let side = 2 * m.size;
            let _ = writeln!(
                md,
                "| {} | {side}^3 | {} | {} | {} | {} |",
                m.size,
                format_ms(m.build_ms),
                format_bytes(m.bytes),
                cell(m.render_ms(FULL_HD, View::Paper)),
                cell(m.render_ms(FULL_HD, View::Above)),
            );
        }
    }
    md
}

fn charts(measured: &[Measured], threads: usize) -> Vec<Chart> {
    let color = |backend| match backend {
        Backend::Dense => 0,
        Backend::Octree => 1,
    };
    let series = |backend: Backend,
                  name: String,
                  line: Line,
                  value: &dyn Fn(&Measured) -> Option<f64>| Series {
        name,
        color: color(backend),
        line,
        points: measured
            .iter()
            .filter(|m| m.backend == backend)
            .filter_map(|m| value(m).map(|v| (f64::from(m.size), v)))
            .collect(),
    };
    let mut time = Vec::new();
    for backend in [Backend::Dense, Backend::Octree] {
        for (view, label, line) in [
            (View::Paper, "paper camera", Line::Thick),
            (View::Above, "camera above", Line::Thin),
        ] {
            time.push(series(
                backend,
                format!("{} {label}", backend.name()),
                line,
                &|m| m.render_ms(FULL_HD, view),
            ));
        }
    }
    for (column, backend) in [(0, Backend::Dense), (1, Backend::Octree)] {
        time.push(Series {
            name: format!("{}, seed paper (12 threads)", backend.name()),
            color: color(backend),
            points: PAPER_MS
                .iter()
                .map(|(size, ms)| (f64::from(*size), ms[column]))
                .collect(),
            line: Line::Dashed,
        });
    }
    let memory = [Backend::Dense, Backend::Octree]
        .into_iter()
        .map(|backend| {
            series(backend, backend.name().to_string(), Line::Thick, &|m| {
                Some(m.bytes as f64 / 1e6)
            })
        })
        .collect();
    vec![
        Chart {
            title: format!("Render time, 1920x1080, {threads} threads"),
            x_label: "scene size (volume = (2·size)³)".to_string(),
            y_label: "ms per frame (median)".to_string(),
            series: time,
            legend: SeriesLabelPosition::UpperLeft,
        },
        Chart {
            title: "Storage".to_string(),
            x_label: "scene size (volume = (2·size)³)".to_string(),
            y_label: "MB (storage_bytes / 10⁶)".to_string(),
            series: memory,
            legend: SeriesLabelPosition::UpperLeft,
        },
    ]
}
