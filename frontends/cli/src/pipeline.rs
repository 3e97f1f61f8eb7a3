//! Build a storage from a voxel source, render a region of a frame in one
//! pass or in rounds ([`Pass`]).
//!
//! One thread count decides both steps: `Some(1)` runs the sequential build
//! and the render into a buffer on the calling thread; anything else runs
//! the parallel build and the render into the atomic framebuffer on a rayon
//! pool (see [`on_threads`]). Both give the same bytes.

use std::collections::TryReserveError;
use std::time::{Duration, Instant};

use crate::units::human_bytes;
use voxtrace::rayon::ThreadPoolBuilder;
use voxtrace::{
    render, render_in_rounds, Camera, Error, Framebuffer, IAabb, PixelSamples, RayStats, Rect,
    RenderOptions, RoundsDone, Scene, SceneMaterials, Target, VoxelGenerator, VoxelSource,
};
pub use voxtrace_flags::Backend;
use voxtrace_flags::{Built, Tracer};

/// Runs `work` with `threads` workers: on the calling thread for `Some(1)`,
/// otherwise inside a new rayon pool of that many threads (`None`: one per
/// core), so that the parallel build and render inside use exactly those.
pub fn on_threads<R: Send>(
    threads: Option<u16>,
    work: impl FnOnce() -> Result<R, String> + Send,
) -> Result<R, String> {
    match threads {
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

/// A storage of either kind, built and rendered as the CLI does: errors
/// in one line, the build and the render timed.
pub struct BuiltScene(pub Built);

impl BuiltScene {
    /// Builds `backend` over the volume `[-size, size)^3` of the terrain of
    /// `seed`, in parallel unless `threaded` is false; returns the scene and
    /// the build's wall time.
    ///
    /// # Errors
    /// As [`BuiltScene::build_from`].
    pub fn build(
        backend: Backend,
        size: i32,
        seed: u64,
        threaded: bool,
    ) -> Result<(BuiltScene, Duration), String> {
        let terrain = VoxelGenerator::new(seed);
        BuiltScene::build_from(backend, &terrain, IAabb::centered(size), threaded)
    }

    /// Builds `backend` from any voxel source over `bounds`, in parallel
    /// unless `threaded` is false; returns the scene and the build's wall
    /// time.
    ///
    /// # Errors
    /// A one-line message; for a dense array that cannot be allocated it
    /// names the bytes it needs.
    pub fn build_from<S: VoxelSource + Sync + ?Sized>(
        backend: Backend,
        source: &S,
        bounds: IAabb,
        threaded: bool,
    ) -> Result<(BuiltScene, Duration), String> {
        let started = Instant::now();
        let built = Built::build(backend, source, bounds, threaded);
        let built = built.map_err(|e| match (backend, e) {
            (Backend::Dense, Error::OutOfMemory { .. } | Error::SizeOverflow) => {
                // Exact even when it overflows usize: one byte per voxel.
                let size = bounds.size();
                let bytes: u128 = [size.x, size.y, size.z]
                    .iter()
                    .map(|&s| u128::from(s.unsigned_abs()))
                    .product();
                format!(
                    "the dense array for this scene needs {} (one per voxel), \
                     more than can be allocated; try --backend octree",
                    human_bytes(bytes)
                )
            }
            (_, Error::OutOfMemory { bytes }) => format!(
                "cannot build the {} scene: out of memory: could not allocate {}",
                backend.name(),
                human_bytes(bytes as u128)
            ),
            (_, e) => format!("cannot build the {} scene: {e}", backend.name()),
        })?;
        Ok((BuiltScene(built), started.elapsed()))
    }

    /// The storage as the tracer sees it.
    #[must_use]
    pub fn scene(&self) -> &(dyn Scene + Sync) {
        self.0.scene()
    }

    /// Renders `region` of `camera`'s frame of the storage shaded with
    /// `materials` (a `.vox` file's; `None`: all diffuse): into a buffer on
    /// the calling thread unless `threaded`, else into the atomic
    /// framebuffer on the current rayon pool. `progress` hears of every
    /// finished band's row count.
    ///
    /// # Errors
    /// A one-line message if the region does not fit the frame or its pixels
    /// cannot be allocated.
    pub fn render_with(
        &self,
        materials: Option<SceneMaterials<'_>>,
        camera: &Camera,
        region: Rect,
        options: &RenderOptions,
        threaded: bool,
        progress: &(dyn Fn(u32) + Sync),
    ) -> Result<Rendered, String> {
        let job = RenderJob {
            camera,
            region,
            options,
            threaded,
            progress,
            pass: Pass::Once,
        };
        let (rendered, _) = self.0.trace(materials, job)?;
        Ok(rendered)
    }

    /// [`BuiltScene::render_with`], the samples taken in rounds over the
    /// whole region (`voxtrace::render_in_rounds`, threaded or
    /// not): `keep_going(n)`, asked after round `n` while a pixel has
    /// samples left, says whether another round begins. `progress` hears
    /// of the rows of every round. Returns the rounds taken beside the
    /// frame, which is the one-pass frame of `voxtrace::Rounds`'
    /// options after them. With `keep_radiance`, the frame's mean radiance
    /// comes back too (for the denoiser) where it is path-traced.
    ///
    /// # Errors
    /// As [`BuiltScene::render_with`]; also when the pixels' state
    /// between rounds cannot be allocated.
    #[allow(clippy::too_many_arguments)]
    pub fn render_in_rounds(
        &self,
        materials: Option<SceneMaterials<'_>>,
        camera: &Camera,
        region: Rect,
        options: &RenderOptions,
        threaded: bool,
        progress: &(dyn Fn(u32) + Sync),
        keep_going: &mut dyn FnMut(u32) -> bool,
        keep_radiance: bool,
    ) -> Result<(Rendered, RoundsDone), String> {
        let job = RenderJob {
            camera,
            region,
            options,
            threaded,
            progress,
            pass: Pass::Rounds {
                keep_going,
                keep_radiance,
            },
        };
        let (rendered, done) = self.0.trace(materials, job)?;
        Ok((
            rendered,
            done.expect("a render in rounds reports its rounds"),
        ))
    }
}

/// The bytes a render in rounds keeps per pixel between rounds, beside
/// the frame ([`BuiltScene::render_in_rounds`]).
pub const ROUND_STATE_BYTES: u64 = std::mem::size_of::<PixelSamples>() as u64;

/// A rendered region: its pixels (row-major, `pack`ed RGBA8) and what it
/// cost.
pub struct Rendered {
    /// `region.width * region.height` pixels.
    pub pixels: Vec<u32>,
    /// Rays traced, by kind.
    pub rays: RayStats,
    /// Wall time of the render alone (no allocation of the scene, no
    /// encoding).
    pub elapsed: Duration,
    /// Each pixel's mean radiance (three `f32`, linear, not clamped to
    /// white), when a render in rounds was asked to keep it and its pixels
    /// are path-traced; `None` otherwise.
    pub radiance: Option<Vec<f32>>,
}

/// What a render draws, where it reports its rows and how it takes its
/// samples: run on each storage and materials by [`Built::trace`].
struct RenderJob<'a> {
    camera: &'a Camera,
    region: Rect,
    options: &'a RenderOptions,
    /// On the current rayon pool, else the scalar path on this thread.
    threaded: bool,
    progress: &'a (dyn Fn(u32) + Sync),
    pass: Pass<'a>,
}

/// How a [`RenderJob`] takes its samples.
enum Pass<'k> {
    /// Every pixel's samples at once.
    Once,
    /// In rounds over the whole region while `keep_going`, asked after
    /// each round, says so; the mean radiance kept with `keep_radiance`.
    Rounds {
        keep_going: &'k mut dyn FnMut(u32) -> bool,
        keep_radiance: bool,
    },
}

impl Tracer for RenderJob<'_> {
    type Output = Result<(Rendered, Option<RoundsDone>), String>;

    /// Renders `scene` as it is, in the job's pass; the rounds taken with
    /// [`Pass::Rounds`]. The time counted is the render's and its
    /// frame's (zeroed on the pool, as the render writes it), not the
    /// samples kept between rounds.
    fn trace<S: Scene + Sync>(self, scene: &S) -> Self::Output {
        let RenderJob {
            camera,
            region,
            options,
            threaded,
            progress,
            pass,
        } = self;
        let between = matches!(pass, Pass::Rounds { .. });
        let no_memory = || {
            format!(
                "out of memory: cannot allocate a {}x{} image{}",
                region.width,
                region.height,
                if between {
                    " and its samples between rounds"
                } else {
                    ""
                }
            )
        };
        region.validate(camera).map_err(|e| e.to_string())?;
        let area = region.area().map_err(|e| e.to_string())?;
        // On the pool into the atomic framebuffer, zeroed on the pool (this
        // runs inside its `install`), or on this thread into plain pixels.
        let started = Instant::now();
        let mut frame = None;
        let mut pixels = Vec::new();
        let target = if threaded {
            let fresh = Framebuffer::new_parallel(region.width, region.height);
            Target::Framebuffer(frame.insert(fresh.map_err(|_| no_memory())?))
        } else {
            pixels = filled(area, 0u32).ok_or_else(no_memory)?;
            Target::Buffer(&mut pixels)
        };
        let progress = Some(progress);
        let (rays, done, radiance) = match pass {
            Pass::Once => {
                let rays = render(scene, camera, options, region, target, progress);
                (rays.map_err(|e| e.to_string())?, None, None)
            }
            Pass::Rounds {
                keep_going,
                keep_radiance,
            } => {
                let mut state = filled(area, PixelSamples::default()).ok_or_else(no_memory)?;
                let done = render_in_rounds(
                    scene, camera, options, region, target, &mut state, progress, keep_going,
                )
                .map_err(|e| e.to_string())?;
                let radiance = if keep_radiance {
                    mean_radiance(&state).map_err(|_| no_memory())?
                } else {
                    None
                };
                (done.rays, Some(done), radiance)
            }
        };
        if let Some(frame) = frame {
            pixels = frame.into_pixels();
        }
        let rendered = Rendered {
            pixels,
            rays,
            elapsed: started.elapsed(),
            radiance,
        };
        Ok((rendered, done))
    }
}

/// The frame's mean radiance, three `f32` per pixel
/// ([`PixelSamples::mean_radiance`]): `None` unless every pixel is
/// path-traced (a face-shaded frame's are none).
///
/// # Errors
/// When the memory is refused.
pub fn mean_radiance(state: &[PixelSamples]) -> Result<Option<Vec<f32>>, TryReserveError> {
    let mut radiance = Vec::new();
    radiance.try_reserve_exact(3 * state.len())?;
    for pixel in state {
        let Some(mean) = pixel.mean_radiance() else {
            return Ok(None);
        };
        radiance.extend_from_slice(&mean.to_array());
    }
    Ok(Some(radiance))
}

/// `len` copies of `value`, or `None` where the memory is refused.
fn filled<T: Clone>(len: usize, value: T) -> Option<Vec<T>> {
    let mut items = Vec::new();
    items.try_reserve_exact(len).ok()?;
    items.resize(len, value);
    Some(items)
}
