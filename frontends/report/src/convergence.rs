//! The accuracy report's convergence section: what a path-traced frame
//! costs and how far it is from converged with the flags a user starts
//! from. For each path-traced scene ([`path_accuracy::for_each_scene`]):
//! 16 and 256 uniform samples, the default adaptive sampling, `--quality
//! final`, and (built with the feature `denoise`) 16 samples denoised, each
//! with its time, its samples per pixel and its error against a reference
//! of many uniform samples; and one image per scene with the frames side by
//! side, for the eye.

use std::fmt::Write as _;
use std::path::Path;
use std::time::{Duration, Instant};

use voxtrace::{render, Adaptive, Framebuffer, Rect, RenderOptions, Target};
#[cfg(feature = "denoise")]
use voxtrace::{render_in_rounds, PixelSamples};

use crate::measure::{count_of, format_ms, median_ms};
use crate::path_accuracy::{self, PathScene};
use voxtrace_cli::image_error::{psnr, rmse};

/// How the section measures.
pub struct Plan {
    /// Image size.
    pub size: (u32, u32),
    /// The reference's uniform samples per pixel.
    pub reference_spp: u16,
    /// The most uniform samples a row takes (256 in the full report).
    pub most_spp: u16,
}

/// The README's: 320x180 against 1024 samples (about four minutes per
/// scene on two cores).
pub const PLAN: Plan = Plan {
    size: (320, 180),
    reference_spp: 1024,
    most_spp: 256,
};

/// A smoke run: 160x90 against 64 samples.
pub const QUICK: Plan = Plan {
    size: (160, 90),
    reference_spp: 64,
    most_spp: 32,
};

/// How one row samples a frame.
#[derive(Clone, Copy)]
enum Sampling {
    /// `--spp N`.
    Uniform(u16),
    /// Without `--spp`: adaptive to the default's or `--quality final`'s
    /// noise level.
    Adaptive(Adaptive, &'static str),
    /// `--spp N --denoise`.
    #[cfg(feature = "denoise")]
    Denoised(u16),
}

impl Sampling {
    /// The row's name: the flags that give it.
    fn label(self) -> String {
        match self {
            Sampling::Uniform(n) => format!("`--spp {n}`"),
            Sampling::Adaptive(_, flags) => flags.to_string(),
            #[cfg(feature = "denoise")]
            Sampling::Denoised(n) => format!("`--spp {n} --denoise`"),
        }
    }

    /// `base` sampled this way.
    fn options(self, base: &RenderOptions) -> RenderOptions {
        let mut options = RenderOptions {
            samples: 1,
            adaptive: None,
            ..*base
        };
        options.lighting.path_trace = true;
        match self {
            Sampling::Uniform(n) => options.samples = n,
            Sampling::Adaptive(adaptive, _) => options.adaptive = Some(adaptive),
            #[cfg(feature = "denoise")]
            Sampling::Denoised(n) => options.samples = n,
        }
        options
    }
}

/// The rows, in the order the table and the image show them.
fn samplings(plan: &Plan) -> Vec<Sampling> {
    let mut rows = vec![
        Sampling::Uniform(16),
        Sampling::Adaptive(Adaptive::DEFAULT, "default (adaptive)"),
    ];
    #[cfg(feature = "denoise")]
    rows.push(Sampling::Denoised(16));
    rows.push(Sampling::Adaptive(Adaptive::FINAL, "`--quality final`"));
    rows.push(Sampling::Uniform(plan.most_spp));
    rows
}

/// One measured row.
struct Row {
    label: String,
    samples_per_pixel: f64,
    ms: f64,
    rmse: f64,
}

/// One scene's rows.
pub struct Measured {
    name: String,
    reference_ms: f64,
    rows: Vec<Row>,
}

/// Measures every scene (median of `runs` per row, the rows' runs
/// interleaved) and writes each
/// scene's frames side by side, then its reference, to
/// `convergence-NAME.png` in `out_dir`.
pub fn measure_all(plan: &Plan, runs: usize, out_dir: &Path) -> Result<Vec<Measured>, String> {
    let mut out = Vec::new();
    path_accuracy::for_each_scene(plan.size, |scene| {
        let (measured, strip) = measure(scene, plan, runs)?;
        let (width, height) = plan.size;
        let stem = scene.name.trim_end_matches(".vox");
        let path = out_dir.join(format!("convergence-{stem}.png"));
        let strip_width = width * (strip.len() / (width * height) as usize) as u32;
        voxtrace_cli::atomic::write_atomic(&path, |file| {
            voxtrace::encode_png(file, strip_width, height, &strip).map_err(|e| e.to_string())
        })
        .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
        out.push(measured);
        Ok(())
    })?;
    Ok(out)
}

/// One scene's rows, and its frames (then its reference) side by side.
fn measure(
    scene: &PathScene<'_>,
    plan: &Plan,
    runs: usize,
) -> Result<(Measured, Vec<u32>), String> {
    let (width, height) = plan.size;
    let frame = Framebuffer::new(width, height).map_err(|e| e.to_string())?;
    let camera = scene.camera;
    let render = |options: &RenderOptions| -> Result<(Duration, u64), String> {
        let started = Instant::now();
        let rays = render(
            scene.scene,
            camera,
            options,
            Rect::full(camera),
            Target::Framebuffer(&frame),
            None,
        )
        .map_err(|e| e.to_string())?;
        Ok((started.elapsed(), rays.primary_rays))
    };
    eprintln!(
        "{}: reference {} spp, {width}x{height}",
        scene.name, plan.reference_spp
    );
    let (reference_time, _) =
        render(&Sampling::Uniform(plan.reference_spp).options(scene.options))?;
    let reference = frame.to_vec();
    let pixels = u64::from(width) * u64::from(height);
    // A row's frame: its time (the denoiser's included), primary rays and
    // pixels.
    let run_row = |sampling: Sampling| -> Result<(Duration, u64, Vec<u32>), String> {
        let options = sampling.options(scene.options);
        #[cfg(feature = "denoise")]
        if let Sampling::Denoised(_) = sampling {
            // As the CLI does: rendered in rounds, keeping each pixel's
            // mean radiance for the filter.
            let started = Instant::now();
            let region = Rect::full(camera);
            let mut state = vec![PixelSamples::default(); (width * height) as usize];
            let done = render_in_rounds(
                scene.scene,
                camera,
                &options,
                region,
                Target::Framebuffer(&frame),
                &mut state,
                None,
                |_| true,
            )
            .map_err(|e| e.to_string())?;
            let radiance = voxtrace_cli::mean_radiance(&state)
                .map_err(|e| format!("the frame's radiance: {e}"))?;
            let mut image = frame.to_vec();
            let guides =
                voxtrace_cli::guides::render_guides(scene.scene, camera, &options, region, true);
            voxtrace_cli::denoise::denoise(&mut image, radiance, width, height, &guides)?;
            return Ok((started.elapsed(), done.rays.primary_rays, image));
        }
        let (took, primary) = render(&options)?;
        Ok((took, primary, frame.to_vec()))
    };
    let rows_sampled = samplings(plan);
    // An untimed pass warms the caches and keeps each row's frame and rays:
    // a pixel's samples depend only on the pixel, so every run renders
    // the same frame.
    let mut frames = Vec::new();
    let mut primaries = Vec::new();
    for &sampling in &rows_sampled {
        let (_, primary, image) = run_row(sampling)?;
        primaries.push(primary);
        frames.push(image);
    }
    // The timed runs alternate the rows, so a change in the machine's load
    // falls on every row alike rather than on whichever ran then.
    let mut times = vec![Vec::new(); rows_sampled.len()];
    for _ in 0..runs.max(1) {
        for (&sampling, row_times) in rows_sampled.iter().zip(&mut times) {
            row_times.push(run_row(sampling)?.0);
        }
    }
    let mut rows = Vec::new();
    for (((sampling, primary), image), mut row_times) in rows_sampled
        .into_iter()
        .zip(primaries)
        .zip(&frames)
        .zip(times)
    {
        let row = Row {
            label: sampling.label(),
            samples_per_pixel: primary as f64 / pixels as f64,
            ms: median_ms(&mut row_times),
            rmse: rmse(image, &reference),
        };
        eprintln!(
            "{} {}: {} {:.1} spp rmse {:.3}",
            scene.name,
            row.label,
            format_ms(row.ms),
            row.samples_per_pixel,
            row.rmse
        );
        rows.push(row);
    }
    frames.push(reference);
    let measured = Measured {
        name: scene.name.to_string(),
        reference_ms: reference_time.as_secs_f64() * 1e3,
        rows,
    };
    Ok((measured, side_by_side(&frames, width as usize)))
}

/// Frames of equal size, `width` pixels wide, left to right in one image.
fn side_by_side(frames: &[Vec<u32>], width: usize) -> Vec<u32> {
    let height = frames.first().map_or(0, |f| f.len() / width);
    let mut out = Vec::with_capacity(frames.len() * width * height);
    for y in 0..height {
        for frame in frames {
            out.extend_from_slice(&frame[y * width..(y + 1) * width]);
        }
    }
    out
}

/// The markdown of the section.
pub fn section(measured: &[Measured], plan: &Plan, runs: usize) -> String {
    let (width, height) = plan.size;
    let mut md = String::new();
    let _ = writeln!(
        md,
        "\n### Converging by default: adaptive sampling and the denoiser\n\n\
         Path-traced frames at {width}x{height} with the scene's own bounces, median of {} \
         per row, the rows' runs taken in turn after an untimed pass (a denoised row's \
         time includes its guides and the filter). Error \
         against a reference of {} uniform samples per pixel; a pixel's samples depend only \
         on the pixel and their index, so a uniform row's samples are the reference's first \
         ones, which flatters the uniform rows as they near it. `convergence-NAME.png` \
         shows the rows' frames left to right, then the reference.\n",
        count_of(runs, "run"),
        plan.reference_spp,
    );
    if cfg!(not(feature = "denoise")) {
        md.push_str(
            "(Built without the feature `denoise`: no denoised row; \
             `--features denoise` adds it, docs/denoise.md.)\n\n",
        );
    }
    for m in measured {
        let _ = writeln!(
            md,
            "**{}** (reference: {}):\n\n\
             | sampling | samples per pixel | time | RMSE | PSNR |\n|---|---|---|---|---|",
            m.name,
            format_ms(m.reference_ms)
        );
        for r in &m.rows {
            let _ = writeln!(
                md,
                "| {} | {:.1} | {} | {:.2} | {:.1} dB |",
                r.label,
                r.samples_per_pixel,
                format_ms(r.ms),
                r.rmse,
                psnr(r.rmse)
            );
        }
        md.push('\n');
    }
    md
}

#[cfg(test)]
mod tests {
    use super::side_by_side;

    #[test]
    fn frames_side_by_side_keep_their_rows() {
        // Two 2x2 frames: pixel values name frame, row and column.
        let a = vec![100, 101, 110, 111];
        let b = vec![200, 201, 210, 211];
        assert_eq!(
            side_by_side(&[a, b], 2),
            [100, 101, 200, 201, 110, 111, 210, 211]
        );
    }
}
