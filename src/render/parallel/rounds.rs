//! The threaded render in rounds: each round is bands of rows on the
//! rayon pool, each band continuing its own pixels' samples
//! ([`crate::render::rounds`]), and the caller's predicate is asked on the
//! calling thread between rounds, when every band of the round is done.

#[cfg(feature = "path")]
use rayon::iter::{IndexedParallelIterator, ParallelIterator};
#[cfg(feature = "path")]
use rayon::slice::ParallelSliceMut;

use crate::error::Error;
use crate::render::camera::Camera;
use crate::render::framebuffer::Framebuffer;
use crate::render::options::RenderOptions;
use crate::render::parallel::{check_frame, render_parallel_with_progress};
#[cfg(feature = "path")]
use crate::render::rounds::in_rounds;
use crate::render::rounds::{PixelSamples, RoundsDone};
#[cfg(feature = "path")]
use crate::render::shader::{Resumable, RoundsJob, Shader};
#[cfg(feature = "path")]
use crate::render::stats::RayStats;
use crate::render::stats::Rect;
#[cfg(feature = "path")]
use crate::render::tiles::resume_tiles;
use crate::scene::Scene;

/// [`crate::render_region_in_rounds`] on the current rayon pool, into
/// `frame` as [`crate::render_parallel`] writes it: after each round
/// every pixel of `frame` holds its value so far, and `keep_going(n)` is
/// asked after round `n` (while a pixel is left that is not done) whether
/// round `n + 1` begins. Byte-identical to the scalar render in rounds,
/// and so to [`crate::render_parallel`] with
/// [`crate::Rounds::options_after`] the rounds taken, for any number of
/// threads. `rows_done(n)` hears of each band of `n` rows finished in
/// every round (keep it cheap).
///
/// `frame` must be exactly `region.width x region.height`
/// ([`Error::SizeMismatch`] otherwise); `pixels` holds at least one
/// [`PixelSamples`] per pixel (overwritten). Allocates nothing beyond
/// rayon's own job bookkeeping.
// (The arguments of `render_parallel_with_progress`, the pixels' state
// and the predicate: bundling them would hide which is which.)
#[allow(clippy::too_many_arguments)]
pub fn render_parallel_in_rounds<S, P>(
    scene: &S,
    camera: &Camera,
    options: &RenderOptions,
    region: Rect,
    frame: &Framebuffer,
    pixels: &mut [PixelSamples],
    rows_done: &P,
    keep_going: impl FnMut(u32) -> bool,
) -> Result<RoundsDone, Error>
where
    S: Scene + Sync + ?Sized,
    P: Fn(u32) + Sync + ?Sized,
{
    check_frame(camera, options, region, frame)?;
    let required = region.area()?;
    if pixels.len() < required {
        return Err(Error::BufferTooSmall {
            required,
            actual: pixels.len(),
        });
    }
    let pixels = &mut pixels[..required];
    pixels.fill(PixelSamples::default());
    // Path-traced: in rounds. (Only the path tracer samples in rounds.)
    #[cfg(feature = "path")]
    let pixels =
        match Shader::new(options, camera, scene.materials()).dispatch_rounds(FrameInRounds {
            scene,
            camera,
            region,
            frame,
            pixels,
            rows_done,
            keep_going,
        }) {
            Ok(done) => return Ok(done),
            Err(job) => job.pixels,
        };
    #[cfg(not(feature = "path"))]
    let _ = keep_going;
    // Not path-traced: one pass, one round.
    pixels.fill(PixelSamples::finished());
    let rays = render_parallel_with_progress(scene, camera, options, region, frame, rows_done)?;
    Ok(RoundsDone {
        rays,
        rounds: 1,
        complete: true,
    })
}

/// Rows per task of a round: a quarter of a tile. Every round ends with
/// a wait for its slowest task, and after the first the work left gathers
/// where pixels are still noisy, so tasks are finer than the one-pass
/// render's bands; their tiles are 16 x 4 (any tiling gives the same
/// pixels). On study.vox at 320x180 the rounds' CPU time is the one-pass
/// render's (2.2 s on one thread of the project's 2-core VM, both ways).
#[cfg(feature = "path")]
const BAND: u32 = 4;

/// A threaded frame in rounds: one task per band of [`BAND`] rows a
/// round, each with its band's pixel states.
#[cfg(feature = "path")]
struct FrameInRounds<'a, S: ?Sized, P: ?Sized, F> {
    scene: &'a S,
    camera: &'a Camera,
    region: Rect,
    frame: &'a Framebuffer,
    pixels: &'a mut [PixelSamples],
    rows_done: &'a P,
    keep_going: F,
}

#[cfg(feature = "path")]
impl<S, P, F> RoundsJob for FrameInRounds<'_, S, P, F>
where
    S: Scene + Sync + ?Sized,
    P: Fn(u32) + Sync + ?Sized,
    F: FnMut(u32) -> bool,
{
    type Output = RoundsDone;

    fn run<K: Resumable>(self, kernel: &K) -> RoundsDone {
        let FrameInRounds {
            scene,
            camera,
            region,
            frame,
            pixels,
            rows_done,
            keep_going,
        } = self;
        let band_len = region.width as usize * BAND as usize;
        let round = |n: u32| {
            // The bands of `render_parallel`, one job each.
            pixels
                .par_chunks_mut(band_len)
                .with_max_len(1)
                .enumerate()
                .map(|(band, states)| {
                    let band = band as u32;
                    let y = region.y + band * BAND;
                    let rect = Rect {
                        y,
                        height: BAND.min(region.y + region.height - y),
                        ..region
                    };
                    let put = |dx, dy, rgba| {
                        frame.set(dx, band * BAND + dy, rgba);
                    };
                    let done = resume_tiles(kernel, scene, camera, rect, states, n, put);
                    rows_done(rect.height);
                    done
                })
                .reduce(
                    || (RayStats::default(), false),
                    |a, b| (a.0 + b.0, a.1 || b.1),
                )
        };
        in_rounds(round, keep_going)
    }
}
