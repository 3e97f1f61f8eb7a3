//! One render of a region of a frame on a storage already chosen, in one
//! pass or in rounds ([`Pass`]): the work behind
//! [`crate::BuiltScene::render_with`] and
//! [`crate::BuiltScene::render_in_rounds`], whatever the storage.

use std::collections::TryReserveError;
use std::time::{Duration, Instant};

use voxtrace::{
    render, render_in_rounds, Camera, Framebuffer, PixelSamples, RayStats, Rect, RenderOptions,
    RoundsDone, Scene, Target,
};

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

/// What a render draws and where it reports its rows.
pub(crate) struct RenderJob<'a> {
    pub(crate) camera: &'a Camera,
    pub(crate) region: Rect,
    pub(crate) options: &'a RenderOptions,
    /// On the current rayon pool, else the scalar path on this thread.
    pub(crate) threaded: bool,
    pub(crate) progress: &'a (dyn Fn(u32) + Sync),
}

/// How a [`RenderJob`] takes its samples.
pub(crate) enum Pass<'k> {
    /// Every pixel's samples at once.
    Once,
    /// In rounds over the whole region while `keep_going`, asked after
    /// each round, says so; the mean radiance kept with `keep_radiance`.
    Rounds {
        keep_going: &'k mut dyn FnMut(u32) -> bool,
        keep_radiance: bool,
    },
}

impl RenderJob<'_> {
    /// Renders `scene` as it is, in `pass`; the rounds taken with
    /// [`Pass::Rounds`]. The time counted is the render's and its
    /// frame's (zeroed on the pool, as the render writes it), not the
    /// samples kept between rounds.
    pub(crate) fn run<S: Scene + Sync>(
        &self,
        scene: &S,
        pass: Pass<'_>,
    ) -> Result<(Rendered, Option<RoundsDone>), String> {
        let RenderJob {
            camera,
            region,
            options,
            threaded,
            progress,
        } = *self;
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
