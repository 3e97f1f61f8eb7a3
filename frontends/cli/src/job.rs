//! The render stage: what every frame of one run shares ([`Job`]), the
//! memory check before anything is built, the build, every frame rendered
//! and written, and the `--stats` of it all.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU32, Ordering};
use std::time::{Duration, Instant};

use voxtrace::{
    Background, Camera, CameraSettings, EffectPlan, RayStats, Rect, RenderOptions, Rounds,
    RoundsDone,
};
use voxtrace_cli::atomic::AtomicFile;
use voxtrace_cli::errors::show_path;
use voxtrace_cli::{on_threads, say, Backend, BuiltScene, Rendered, ROUND_STATE_BYTES};
use voxtrace_flags::describe;

use crate::budget::Budget;
use crate::denoise_flag;
use crate::farm::{self, TileJob};
use crate::memory;
use crate::output::{self, Format};
use crate::progress::{Progress, Spinner};
use crate::subject::Subject;

/// One frame to render: its camera, and the settings it was made from
/// (for the flags `--stats` prints and the voxel it starts in).
pub struct Frame {
    /// The settings, as `--frames` turned them.
    pub settings: CameraSettings,
    /// The camera they make, checked.
    pub camera: Camera,
}

/// What every frame of one run shares.
pub struct Job<'a> {
    /// The storage to build.
    pub backend: Backend,
    /// Worker threads (`Some(1)`: the scalar path on this thread).
    pub threads: Option<u16>,
    /// What the frames show.
    pub subject: &'a Subject<'a>,
    /// The effects.
    pub options: &'a RenderOptions,
    /// The crop of every frame that is rendered.
    pub region: Rect,
    /// The files' format (a tile's part is PNG whatever it says).
    pub format: Format,
    /// The render-farm tile this run renders, written as a part.
    pub tile: Option<&'a TileJob>,
    /// `--denoise`: every frame is denoised before it is written.
    pub denoise: bool,
    /// `--time-limit` of a path-traced frame: each frame's samples taken
    /// in rounds until the budget is spent.
    pub budget: Option<Budget>,
    /// How a path-traced frame's samples divide into rounds (its plan's);
    /// `None` for a face-shaded frame.
    pub rounds: Option<Rounds>,
}

/// What a run cost, for `--stats`.
pub struct Totals {
    /// Wall time of the build.
    pub build: Duration,
    /// Rays traced over every frame, by kind.
    pub rays: RayStats,
    /// Pixels rendered over every frame.
    pub pixels: u64,
    /// Wall time of the renders alone.
    pub render: Duration,
    /// Wall time of the encoding and writing.
    pub encode: Duration,
    /// Wall time of `--denoise`: the guides traced and the filter.
    pub denoise: Duration,
    /// The built storage's bytes.
    pub storage_bytes: usize,
    /// The rounds each frame took, under `--time-limit`.
    pub rounds: Vec<RoundsDone>,
}

impl Job<'_> {
    /// Refuses a scene and frame (with `--denoise`'s images) that cannot
    /// fit in `max_memory` (`None`: what the OS says is available) before
    /// anything is built, naming the bytes.
    ///
    /// # Errors
    /// [`memory::Budget::check`]'s one line.
    pub fn check_memory(&self, max_memory: Option<u64>) -> Result<(), String> {
        let region = self.region;
        let pixels = u64::from(region.width) * u64::from(region.height);
        let encoder = match self.tile {
            // A part is a PNG with its placement, streamed by the same encoder.
            Some(_) => output::encoder_bytes(Format::Png, region.width, region.height, true),
            None => {
                let alpha = self.options.background == Background::Transparent;
                output::encoder_bytes(self.format, region.width, region.height, alpha)
            }
        };
        // The denoiser's images live beside the encoder's buffers.
        let denoise = if self.denoise {
            u128::from(pixels) * denoise_flag::BYTES_PER_PIXEL
        } else {
            0
        };
        // A render in rounds keeps each pixel's samples between rounds
        // (and `--denoise` keeps their mean radiance, counted in its bytes).
        let rounds = if self.renders_in_rounds() {
            u128::from(pixels) * u128::from(ROUND_STATE_BYTES)
        } else {
            0
        };
        let encoder = encoder + denoise + rounds;
        let bounds = self.subject.shown.bounds();
        let loaded = self.subject.loaded();
        memory::budget(self.backend, bounds, loaded, (pixels, encoder), max_memory)
            .check(self.backend)
    }

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
        let failed = |e: String| format!("cannot write --out {}: {e}", show_path(path));
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
    /// path, `out` being the first path or `-` (standard output).
    ///
    /// The first path's file is created before the build, and every other
    /// path checked, so that a bad path fails before the work: a temporary
    /// file beside it from then on, which replaces the path only once
    /// complete and is removed on any error.
    ///
    /// # Errors
    /// One line: the file cannot be created, the scene built, a frame
    /// rendered or written.
    pub fn render_all(
        &self,
        cameras: &[Frame],
        out: &Path,
        paths: &[PathBuf],
    ) -> Result<Totals, String> {
        let mut first = if output::is_stdout(out) {
            None
        } else {
            Some(output::create(&paths[0])?)
        };
        // A turntable's later frames fail now too, before any is replaced.
        for path in paths.iter().skip(1) {
            output::check(path)?;
        }
        let threaded = self.threads != Some(1);
        let region = self.region;
        on_threads(self.threads, || {
            let spinner = Spinner::start(format!("building the {} scene", self.backend.name()));
            let (built, build, materials) = self.subject.build(self.backend, threaded)?;
            drop(spinner);
            let total_rows = region.height.saturating_mul(cameras.len() as u32);
            // Every round of a render in rounds goes over the rows again.
            let most = self.rows_passes();
            let total_rows = total_rows.saturating_mul(most);
            let progress = Progress::rows(total_rows);
            let mut totals = Totals {
                build,
                rays: RayStats::default(),
                pixels: 0,
                render: Duration::ZERO,
                encode: Duration::ZERO,
                denoise: Duration::ZERO,
                storage_bytes: built.scene().storage_bytes(),
                rounds: Vec::new(),
            };
            let rendered = cameras.iter().zip(paths).try_for_each(|(frame, path)| {
                let camera = &frame.camera;
                // The rows this frame reported: a render in rounds that
                // ends early (or the scalar path's last round) reports
                // fewer than it was counted for, and the rest are added.
                let reported = AtomicU32::new(0);
                let advance = |rows| {
                    reported.fetch_add(rows, Ordering::Relaxed);
                    progress.advance(rows);
                };
                let rendered = self.render_one(&built, materials, camera, &advance);
                let counted = region.height.saturating_mul(most);
                progress.advance(counted.saturating_sub(reported.into_inner()));
                let (mut rendered, rounds) = rendered?;
                totals.rounds.extend(rounds);
                if self.denoise {
                    let started = Instant::now();
                    let frame = (&mut rendered.pixels[..], rendered.radiance.take());
                    let (scene, options) = (built.scene(), self.options);
                    denoise_flag::apply(scene, camera, options, region, threaded, frame)?;
                    totals.denoise += started.elapsed();
                }
                let started = Instant::now();
                self.write(first.take(), path, rendered.pixels)?;
                totals.rays += rendered.rays;
                totals.pixels += u64::from(region.width) * u64::from(region.height);
                totals.render += rendered.elapsed;
                totals.encode += started.elapsed();
                Ok::<_, String>(())
            });
            progress.finish();
            rendered.map(|()| totals)
        })
    }

    /// Renders one frame's `camera` of `built` with `materials`, in
    /// rounds under a budget (then also the rounds it took) or for
    /// `--denoise`'s radiance, reporting finished rows to `progress`.
    fn render_one(
        &self,
        built: &BuiltScene,
        materials: Option<voxtrace::SceneMaterials<'_>>,
        camera: &Camera,
        progress: &(dyn Fn(u32) + Sync),
    ) -> Result<(Rendered, Option<RoundsDone>), String> {
        let (region, options) = (self.region, self.options);
        let threaded = self.threads != Some(1);
        let keep_radiance = self.keeps_radiance();
        let mut keep_going: Box<dyn FnMut(u32) -> bool> = match &self.budget {
            None if !keep_radiance => {
                return built
                    .render_with(materials, camera, region, options, threaded, progress)
                    .map(|r| (r, None));
            }
            // Every round, for the radiance the samples leave behind.
            None => Box::new(|_| true),
            Some(budget) => Box::new(budget.keep_going()),
        };
        let rounds = built.render_in_rounds(
            materials,
            camera,
            region,
            options,
            threaded,
            progress,
            &mut *keep_going,
            keep_radiance,
        )?;
        // Without a budget the rounds are an implementation detail.
        Ok((rounds.0, self.budget.is_some().then_some(rounds.1)))
    }

    /// Whether the render keeps each pixel's mean radiance: for
    /// `--denoise`, which reads it as high dynamic range color, unless the
    /// background is transparent (the mean there is the color times its
    /// coverage, where the bytes hold the color).
    fn keeps_radiance(&self) -> bool {
        self.denoise && self.rounds.is_some() && self.options.background != Background::Transparent
    }

    /// Whether a frame renders in rounds: under a budget, or to keep its
    /// radiance.
    fn renders_in_rounds(&self) -> bool {
        self.budget.is_some() || self.keeps_radiance()
    }

    /// How many times a frame's render goes over its rows: each round of
    /// a render in rounds, else once.
    fn rows_passes(&self) -> u32 {
        match self.rounds {
            Some(rounds) if self.renders_in_rounds() => rounds.most,
            _ => 1,
        }
    }

    /// Prints `--stats`: what the run cost, the `plan`'s effects, the
    /// scene's box, and the flags that make the first frame's `camera`
    /// (`--up` only when `explicit_up`).
    pub fn print_stats(
        &self,
        totals: &Totals,
        plan: &EffectPlan,
        camera: &CameraSettings,
        explicit_up: bool,
    ) {
        let Totals {
            build,
            rays,
            pixels,
            render,
            encode,
            denoise,
            storage_bytes,
            ref rounds,
        } = *totals;
        // One camera ray per sample: what adaptive sampling spent.
        let samples_per_pixel = rays.primary_rays as f64 / pixels.max(1) as f64;
        let bounds = self.subject.shown.bounds();
        let ms = |d: Duration| d.as_secs_f64() * 1e3;
        let mrays = rays.primary_rays as f64 / render.as_secs_f64().max(1e-9) / 1e6;
        let v = |v: voxtrace::glam::IVec3| format!("{},{},{}", v.x, v.y, v.z);
        say!("build_ms: {:.3}", ms(build));
        say!("render_ms: {:.3}", ms(render));
        say!("encode_ms: {:.3}", ms(encode));
        if self.denoise {
            say!("denoise_ms: {:.3}", ms(denoise));
        }
        say!("primary_rays: {}", rays.primary_rays);
        say!("shadow_rays: {}", rays.shadow_rays);
        say!("ao_rays: {}", rays.ao_rays);
        say!("reflection_rays: {}", rays.reflection_rays);
        say!("refraction_rays: {}", rays.refraction_rays);
        say!("light_rays: {}", rays.light_rays);
        // The route each ray took: answered together (a packet, or a tile
        // clear forever) or walked alone.
        say!("rays_in_packets: {}", rays.packet_rays);
        say!("rays_alone: {}", rays.total() - rays.packet_rays);
        say!("samples_per_pixel: {samples_per_pixel:.2}");
        say!("effects: {plan}");
        say!("storage_bytes: {storage_bytes}");
        say!("mrays_per_s: {mrays:.3}");
        say!("scene_min: {}", v(bounds.min));
        say!("scene_max: {}", v(bounds.max));
        say!("camera: {}", describe(camera, explicit_up));
        if let Some(budget) = &self.budget {
            for line in budget.stats(rounds) {
                say!("{line}");
            }
        }
    }
}
