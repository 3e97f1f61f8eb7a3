//! One render of a region of a frame on a storage already chosen, in one
//! pass or in rounds ([`Pass`]): the work behind
//! [`crate::BuiltScene::render_with`] and
//! [`crate::BuiltScene::render_in_rounds`], whatever the storage.

use std::collections::TryReserveError;
use std::time::Instant;

use voxtrace::{
    render_parallel_in_rounds, render_parallel_with_progress, render_region,
    render_region_in_rounds, Camera, Framebuffer, PixelSamples, RayStats, Rect, RenderOptions,
    RoundsDone, Scene,
};

use crate::pipeline::Rendered;

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
        // Zeroed on the render's own pool (this runs inside its `install`).
        let new_frame =
            || Framebuffer::new_parallel(region.width, region.height).map_err(|_| no_memory());
        let new_pixels = || filled(area, 0u32).ok_or_else(no_memory);
        match pass {
            Pass::Once if threaded => {
                let started = Instant::now();
                let frame = new_frame()?;
                let rays =
                    render_parallel_with_progress(scene, camera, options, region, &frame, progress)
                        .map_err(|e| e.to_string())?;
                Ok((rendered(frame.into_pixels(), rays, started, None), None))
            }
            Pass::Once => {
                // The scalar path, a band of rows at a time for the progress
                // callback (sixteen rows: the tiles primary rays are traced in).
                const BAND: u32 = 16;
                let started = Instant::now();
                let mut pixels = new_pixels()?;
                let mut rays = RayStats::default();
                let bands = pixels.chunks_mut(region.width as usize * BAND as usize);
                for (y, band) in (region.y..).step_by(BAND as usize).zip(bands) {
                    let rect = Rect {
                        y,
                        height: (band.len() / region.width as usize) as u32,
                        ..region
                    };
                    rays += render_region(scene, camera, options, rect, band)
                        .map_err(|e| e.to_string())?;
                    progress(rect.height);
                }
                Ok((rendered(pixels, rays, started, None), None))
            }
            Pass::Rounds {
                keep_going,
                keep_radiance,
            } => {
                let mut state = filled(area, PixelSamples::default()).ok_or_else(no_memory)?;
                let (pixels, done, started) = if threaded {
                    let started = Instant::now();
                    let frame = new_frame()?;
                    let done = render_parallel_in_rounds(
                        scene, camera, options, region, &frame, &mut state, progress, keep_going,
                    )
                    .map_err(|e| e.to_string())?;
                    (frame.into_pixels(), done, started)
                } else {
                    let started = Instant::now();
                    let mut pixels = new_pixels()?;
                    // The scalar path reports a round's rows when it ends.
                    let keep_going = |n| {
                        progress(region.height);
                        keep_going(n)
                    };
                    let done = render_region_in_rounds(
                        scene,
                        camera,
                        options,
                        region,
                        &mut pixels,
                        &mut state,
                        keep_going,
                    )
                    .map_err(|e| e.to_string())?;
                    (pixels, done, started)
                };
                let radiance = if keep_radiance {
                    mean_radiance(&state).map_err(|_| no_memory())?
                } else {
                    None
                };
                Ok((rendered(pixels, done.rays, started, radiance), Some(done)))
            }
        }
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

/// A [`Rendered`] whose render began at `started`.
fn rendered(
    pixels: Vec<u32>,
    rays: RayStats,
    started: Instant,
    radiance: Option<Vec<f32>>,
) -> Rendered {
    Rendered {
        pixels,
        rays,
        elapsed: started.elapsed(),
        radiance,
    }
}

/// `len` copies of `value`, or `None` where the memory is refused.
fn filled<T: Clone>(len: usize, value: T) -> Option<Vec<T>> {
    let mut items = Vec::new();
    items.try_reserve_exact(len).ok()?;
    items.resize(len, value);
    Some(items)
}
