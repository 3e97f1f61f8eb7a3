//! The threaded renderer (feature `rayon`): the scalar tracer's tiles,
//! one band of 16 rows per unit of work, written into the atomic
//! framebuffer; the same in rounds over the whole frame (`rounds.rs`);
//! and the framebuffer's own parallel pixel iterator (`pixels.rs`) for
//! users' per-pixel work.

pub(crate) mod pixels;
pub(crate) mod rounds;

use rayon::iter::{IndexedParallelIterator, IntoParallelIterator, ParallelIterator};

use crate::error::Error;
use crate::render::camera::Camera;
use crate::render::framebuffer::Framebuffer;
use crate::render::options::RenderOptions;
use crate::render::shader::{FrameJob, Kernel, Shader};
use crate::render::stats::{RayStats, Rect};
use crate::render::tiles::{render_tiles, TILE};
use crate::scene::Scene;

/// The checks every threaded render makes before it starts: a region the
/// camera can render, a framebuffer of the region's size
/// ([`Error::SizeMismatch`]) and usable options.
pub(crate) fn check_frame(
    camera: &Camera,
    options: &RenderOptions,
    region: Rect,
    frame: &Framebuffer,
) -> Result<(), Error> {
    region.validate(camera)?;
    let actual = (frame.width(), frame.height());
    if actual != (region.width, region.height) {
        return Err(Error::SizeMismatch {
            expected: (region.width, region.height),
            actual,
        });
    }
    options.validate()?;
    Ok(())
}

/// Renders the crop `region` of `camera`'s frame into `frame` on the current
/// rayon pool: pixel `(x, y)` of `frame` is pixel `(region.x + x,
/// region.y + y)` of the frame, byte-identical to the scalar
/// [`crate::render_region`] for any number of threads.
///
/// `frame` must be exactly `region.width x region.height`
/// ([`Error::SizeMismatch`] otherwise). Allocates nothing beyond rayon's
/// own job bookkeeping.
///
/// ```
/// use voxtrace::{render_parallel, Camera, CameraSettings, Framebuffer, IAabb};
/// use voxtrace::{OctreeScene, Rect, RenderOptions, VoxelGenerator};
///
/// let scene = OctreeScene::build(&VoxelGenerator::new(1), IAabb::centered(32))?;
/// let camera = Camera::new(CameraSettings { width: 64, height: 36, ..Default::default() })?;
/// let frame = Framebuffer::new(64, 36)?;
/// let pool = voxtrace::rayon::ThreadPoolBuilder::new().num_threads(2).build().unwrap();
/// let region = Rect::full(&camera);
/// let stats = pool.install(|| render_parallel(&scene, &camera, &RenderOptions::default(), region, &frame))?;
/// assert_eq!(stats.primary_rays, 64 * 36);
/// let pixels: Vec<u32> = frame.into_pixels(); // the layout `render` writes
/// # Ok::<(), voxtrace::Error>(())
/// ```
pub fn render_parallel<S: Scene + Sync + ?Sized>(
    scene: &S,
    camera: &Camera,
    options: &RenderOptions,
    region: Rect,
    frame: &Framebuffer,
) -> Result<RayStats, Error> {
    render_parallel_with_progress(scene, camera, options, region, frame, &|_| {})
}

/// [`render_parallel`], calling `rows_done(n)` from a worker thread each
/// time a band of `n` rows is finished (for a progress bar; keep it cheap).
pub fn render_parallel_with_progress<S, P>(
    scene: &S,
    camera: &Camera,
    options: &RenderOptions,
    region: Rect,
    frame: &Framebuffer,
    rows_done: &P,
) -> Result<RayStats, Error>
where
    S: Scene + Sync + ?Sized,
    P: Fn(u32) + Sync + ?Sized,
{
    check_frame(camera, options, region, frame)?;
    Ok(
        Shader::new(options, camera, scene.materials()).dispatch(Frame {
            scene,
            camera,
            region,
            frame,
            rows_done,
        }),
    )
}

/// A threaded frame: one task per band of [`TILE`] rows, traced in tiles.
struct Frame<'a, S: ?Sized, P: ?Sized> {
    scene: &'a S,
    camera: &'a Camera,
    region: Rect,
    frame: &'a Framebuffer,
    rows_done: &'a P,
}

impl<S, P> FrameJob for Frame<'_, S, P>
where
    S: Scene + Sync + ?Sized,
    P: Fn(u32) + Sync + ?Sized,
{
    type Output = RayStats;

    fn run<K: Kernel>(self, kernel: &K) -> RayStats {
        let Frame {
            scene,
            camera,
            region,
            frame,
            rows_done,
        } = self;
        // Bands of whole tiles: neighbouring rays stay on one thread, share
        // their tile's clear distance and walk the same nodes while they are
        // in cache; 1080 rows make 68 tasks. Each band is its own job: left
        // to rayon's adaptive splitting, a thread would take a run of
        // several bands and walk it alone, and where the costly bands bunch
        // up (the terrain under the sky) the other thread ran out of work.
        (0..region.height.div_ceil(TILE))
            .into_par_iter()
            .with_max_len(1)
            .map(|band| {
                let y = region.y + band * TILE;
                let rect = Rect {
                    y,
                    height: TILE.min(region.y + region.height - y),
                    ..region
                };
                let stats = render_tiles(kernel, scene, camera, rect, |dx, dy, rgba| {
                    frame.set(dx, band * TILE + dy, rgba);
                });
                rows_done(rect.height);
                stats
            })
            .reduce(RayStats::default, |a, b| a + b)
    }
}
