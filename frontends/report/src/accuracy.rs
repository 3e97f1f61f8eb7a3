//! `voxtrace-report accuracy`: what accuracy costs in time. Renders a
//! converged reference of one scene, then each setting along each accuracy
//! axis, and records time, rays and error (RMSE, PSNR) against the
//! reference. Then the path-traced material scenes over samples per pixel x
//! bounces ([`crate::path_accuracy`]), what a user gets by default
//! from adaptive sampling and the denoiser ([`crate::convergence`]), and
//! the geometric section
//! ([`crate::geometric`]): the exact walk against a textbook
//! float-accumulating one, time and pixels differing.

use std::fmt::Write as _;

use voxtrace::glam::Vec3;
use voxtrace::{
    render, Camera, CameraSettings, Framebuffer, IAabb, Occlusion, OctreeScene, RayStats, Rect,
    RenderOptions, Target, VoxelGenerator,
};
use voxtrace_cli::on_threads;

use crate::common_args::Output;
use crate::geometric;
use crate::measure::{count_of, cpu_name, format_ms, median_of};
use crate::plot::{Chart, Line, Series};
use crate::{convergence, path_accuracy};
use plotters::chart::SeriesLabelPosition;
use voxtrace_cli::image_error::{psnr, rmse};

/// Options of the `accuracy` report.
#[derive(Debug, clap::Args)]
pub struct AccuracyArgs {
    /// 1920x1080 instead of 640x360 (about nine times as long).
    #[arg(long, conflicts_with = "quick")]
    full: bool,
    /// 320x180, one run per setting, and the geometric section at sizes 50
    /// and 100 only: a smoke run, not figures for the README.
    #[arg(long)]
    quick: bool,
    /// Timed runs per setting (after one untimed warm-up) [default: 3,
    /// quick: 1].
    #[arg(long, value_parser = clap::value_parser!(u16).range(1..))]
    runs: Option<u16>,
    /// Measure one section only and write it as `<section>.md` (and its
    /// images), leaving `accuracy.md` as it is: for tuning, not the
    /// README's figures.
    #[arg(long, value_enum)]
    only: Option<Section>,
    #[command(flatten)]
    output: Output,
}

/// A section `--only` can run alone.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
enum Section {
    /// The default adaptive sampling, `--quality final` and the denoiser
    /// against uniform samples ([`convergence`]; under half the full
    /// report's time: its two references and rows, none of the others).
    Convergence,
}

/// The command that gives this report, for its header.
fn command(args: &AccuracyArgs) -> String {
    let features = if cfg!(feature = "denoise") {
        " --features denoise"
    } else {
        ""
    };
    let size = if args.full {
        " --full"
    } else if args.quick {
        " --quick"
    } else {
        ""
    };
    let only = match args.only {
        Some(Section::Convergence) => " --only convergence",
        None => "",
    };
    format!("cargo run --release -p voxtrace-report{features} -- accuracy{size}{only}")
}

/// `--only convergence`: the convergence section alone, into
/// `convergence.md` and its images.
fn run_convergence(args: &AccuracyArgs, runs: usize) -> Result<(), String> {
    let plan = if args.quick {
        &convergence::QUICK
    } else {
        &convergence::PLAN
    };
    let (converged, threads) = on_threads(args.output.threads, || {
        let threads = voxtrace::rayon::current_num_threads();
        convergence::measure_all(plan, runs, &args.output.out_dir).map(|m| (m, threads))
    })?;
    let md = format!(
        "Measured by `{}` on {} with {}.\n{}",
        command(args),
        cpu_name(),
        count_of(threads, "thread"),
        convergence::section(&converged, plan, runs)
    );
    args.output.write_markdown("convergence", &md)
}

/// The scene: terrain of seed 1 in a volume of side 128, seen from above
/// one corner, low enough that slopes shade each other.
const SEED: u64 = 1;
const SIZE: i32 = 64;
const EYE: Vec3 = Vec3::new(70.0, 58.0, 52.0);

/// The look being approximated: the default sun, hard shadows and ambient
/// occlusion within 8 voxels, over several samples per pixel.
fn look(samples: u16, ao_rays: u16, shadows: bool) -> RenderOptions {
    RenderOptions {
        shadows,
        occlusion: (ao_rays > 0).then_some(Occlusion {
            rays: ao_rays,
            distance: Occlusion::DEFAULT_DISTANCE,
        }),
        samples,
        ..RenderOptions::default()
    }
}

/// The reference: 256 samples per pixel with 4 occlusion rays each, so 1024
/// occlusion rays per pixel, spread over the pixel's area.
const REFERENCE: (u16, u16, bool) = (256, 4, true);

/// One accuracy axis: its name and the settings along it, cheapest first.
struct Axis {
    name: &'static str,
    settings: Vec<(String, RenderOptions)>,
}

fn axes() -> Vec<Axis> {
    vec![
        Axis {
            name: "samples per pixel (4 AO rays each, shadows)",
            settings: [1, 2, 4, 8, 16, 64]
                .into_iter()
                .map(|spp| (format!("spp {spp}"), look(spp, 4, true)))
                .collect(),
        },
        Axis {
            name: "AO rays (1 sample, shadows)",
            settings: [0, 4, 16, 64]
                .into_iter()
                .map(|ao| (format!("ao {ao}"), look(1, ao, true)))
                .collect(),
        },
        Axis {
            name: "shadows (1 sample, 16 AO rays)",
            settings: [false, true]
                .into_iter()
                .map(|on| {
                    let name = if on { "shadows on" } else { "shadows off" };
                    (name.to_string(), look(1, 16, on))
                })
                .collect(),
        },
    ]
}

/// One measured setting.
struct Row {
    axis: &'static str,
    setting: String,
    ms: f64,
    rays: RayStats,
    rmse: f64,
}

/// Renders the reference and every setting, writes `accuracy.md` and
/// `accuracy.png` into `--out-dir`.
pub fn run(args: &AccuracyArgs) -> Result<(), String> {
    let (width, height) = if args.full {
        (1920, 1080)
    } else if args.quick {
        (320, 180)
    } else {
        (640, 360)
    };
    args.output.prepare()?;
    let runs = usize::from(args.runs.unwrap_or(if args.quick { 1 } else { 3 }));
    if args.only == Some(Section::Convergence) {
        return run_convergence(args, runs);
    }
    let camera = Camera::new(CameraSettings {
        width,
        height,
        lookfrom: EYE,
        ..CameraSettings::default()
    })
    .map_err(|e| e.to_string())?;
    let scene = OctreeScene::build(&VoxelGenerator::new(SEED), IAabb::centered(SIZE))
        .map_err(|e| e.to_string())?;
    let frame = Framebuffer::new(width, height).map_err(|e| e.to_string())?;

    let (rows, reference_ms, threads) = on_threads(args.output.threads, || {
        let threads = voxtrace::rayon::current_num_threads();
        let render = |options: &RenderOptions| -> Result<(std::time::Duration, RayStats), String> {
            let started = std::time::Instant::now();
            let rays = render(
                &scene,
                &camera,
                options,
                Rect::full(&camera),
                Target::Framebuffer(&frame),
                None,
            )
            .map_err(|e| e.to_string())?;
            Ok((started.elapsed(), rays))
        };
        let (samples, ao, shadows) = REFERENCE;
        eprintln!("reference: {samples} spp x {ao} AO rays, shadows, {width}x{height}");
        let (elapsed, _) = render(&look(samples, ao, shadows))?;
        let reference = frame.to_vec();
        let mut rows = Vec::new();
        for axis in axes() {
            for (setting, options) in axis.settings {
                let mut rays = RayStats::default();
                let ms = median_of(runs, || {
                    let (elapsed, counted) = render(&options)?;
                    rays = counted;
                    Ok(elapsed)
                })?;
                let rmse = rmse(&frame.to_vec(), &reference);
                eprintln!("{setting}: {} rmse {rmse:.3}", format_ms(ms));
                rows.push(Row {
                    axis: axis.name,
                    setting,
                    ms,
                    rays,
                    rmse,
                });
            }
        }
        Ok((rows, elapsed.as_secs_f64() * 1e3, threads))
    })?;

    eprintln!("geometric: exact walk against the textbook walk, one thread");
    let sizes: &[i32] = if args.quick {
        &geometric::QUICK_SIZES
    } else {
        &geometric::SIZES
    };
    let geometric_rows = geometric::measure(SEED, sizes, (width, height), runs)?;

    let grid = if args.quick {
        &path_accuracy::QUICK
    } else {
        &path_accuracy::GRID
    };
    let materials = on_threads(args.output.threads, || {
        path_accuracy::measure_all(grid, runs)
    })?;
    let plan = if args.quick {
        &convergence::QUICK
    } else {
        &convergence::PLAN
    };
    let converged = on_threads(args.output.threads, || {
        convergence::measure_all(plan, runs, &args.output.out_dir)
    })?;

    let mut md = table(
        &rows,
        &command(args),
        width,
        height,
        threads,
        runs,
        reference_ms,
    );
    md.push_str(&path_accuracy::section(&materials, grid, runs));
    md.push_str(&convergence::section(&converged, plan, runs));
    md.push_str(&geometric::section(
        &geometric_rows,
        SEED,
        (width, height),
        runs,
    ));
    let charts = [
        chart(&rows, width, height),
        path_accuracy::chart(&materials, grid),
    ];
    args.output.write("accuracy", &md, &charts)?;
    Ok(())
}

fn table(
    rows: &[Row],
    command: &str,
    width: u32,
    height: u32,
    threads: usize,
    runs: usize,
    reference_ms: f64,
) -> String {
    let (samples, ao, _) = REFERENCE;
    let mut md = String::new();
    let runs_text = count_of(runs, "run");
    let threads_text = count_of(threads, "thread");
    let _ = writeln!(
        md,
        "Measured by `{command}` on {} with {threads_text}: terrain seed {SEED}, \
         size {SIZE} (octree), {width}x{height}, median of {runs_text}. \
         Error against a reference of {samples} samples per pixel with {ao} occlusion \
         rays each and shadows ({}).\n",
        cpu_name(),
        format_ms(reference_ms)
    );
    let _ = writeln!(
        md,
        "| axis | setting | time | primary rays | shadow rays | AO rays | RMSE | PSNR |\n|---|---|---|---|---|---|---|---|"
    );
    for row in rows {
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {} | {} | {:.2} | {:.1} dB |",
            row.axis,
            row.setting,
            format_ms(row.ms),
            row.rays.primary_rays,
            row.rays.shadow_rays,
            row.rays.ao_rays,
            row.rmse,
            psnr(row.rmse),
        );
    }
    md
}

fn chart(rows: &[Row], width: u32, height: u32) -> Chart {
    let mut series: Vec<Series> = Vec::new();
    for row in rows {
        if series.last().is_none_or(|s| s.name != row.axis) {
            series.push(Series {
                name: row.axis.to_string(),
                points: Vec::new(),
                color: series.len(),
                line: Line::Thick,
            });
        }
        if let Some(last) = series.last_mut() {
            // A setting equal to the reference has no error to plot on a
            // log axis; it is in the table.
            if row.rmse > 0.0 {
                last.points.push((row.ms, row.rmse));
            }
        }
    }
    Chart {
        title: format!("Error against time, {width}x{height}"),
        x_label: "ms per frame (median)".to_string(),
        y_label: "RMSE against the reference (0-255)".to_string(),
        series,
        legend: SeriesLabelPosition::LowerLeft,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_thread_and_one_run_are_singular() {
        let one = table(&[], "cmd", 8, 8, 1, 1, 1.0);
        assert!(
            one.contains("with 1 thread:") && one.contains("median of 1 run."),
            "{one}"
        );
        assert!(
            !one.contains("1 threads") && !one.contains("1 runs"),
            "{one}"
        );
        let two = table(&[], "cmd", 8, 8, 2, 3, 1.0);
        assert!(
            two.contains("with 2 threads:") && two.contains("median of 3 runs."),
            "{two}"
        );
    }
}
