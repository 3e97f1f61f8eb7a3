//! The one render path. A render is a region of a camera's frame, into a
//! [`Target`] (a caller's buffer on this thread, or the atomic
//! framebuffer on the rayon pool), in one pass ([`render`]) or in rounds
//! ([`render_in_rounds`]); both are one job ([`FrameJob`]) run with the
//! kernel of the frame's look, which cuts the region into bands of rows
//! and each band into tiles (`tiles.rs`). One pass is one
//! round that takes every sample, so the two cannot disagree, and since no
//! pixel depends on its band, tile or thread, every target, crop and
//! thread count gives the same bytes.

#[cfg(feature = "rayon")]
use rayon::iter::{IndexedParallelIterator, IntoParallelIterator, ParallelIterator};
#[cfg(feature = "rayon")]
use rayon::slice::ParallelSliceMut;

use crate::error::Error;
use crate::render::camera::Camera;
#[cfg(feature = "rayon")]
use crate::render::framebuffer::Framebuffer;
use crate::render::options::RenderOptions;
use crate::render::rounds::{PixelSamples, RoundsDone};
use crate::render::shader::{FrameSetup, Job, Kernel};
use crate::render::stats::{RayStats, Rect};
use crate::render::tiles::{render_tiles, Round, TILE};
use crate::scene::Scene;

/// Where a render writes its region's pixels, and on which threads.
#[derive(Debug)]
pub enum Target<'a> {
    /// A caller's buffer, row-major with stride the region's width and at
    /// least the region's area ([`Error::BufferTooSmall`] otherwise; the
    /// rest is left alone), rendered on this thread. Allocates nothing.
    Buffer(&'a mut [u32]),
    /// The atomic framebuffer, exactly the region's size
    /// ([`Error::SizeMismatch`] otherwise), rendered on the current rayon
    /// pool, a band of rows per task. Allocates nothing beyond rayon's own
    /// job bookkeeping.
    #[cfg(feature = "rayon")]
    Framebuffer(&'a Framebuffer),
}

/// Hears that a band of `n` rows is finished (from a worker thread, for a
/// progress bar; keep it cheap).
pub type RowsDone<'a> = Option<&'a (dyn Fn(u32) + Sync)>;

/// Renders the crop `region` of `camera`'s frame into `target` in one
/// pass: pixel `(x, y)` of the target is pixel `(region.x + x, region.y +
/// y)` of the frame ([`Rect::full`] for the whole frame), the same bytes
/// on every target and thread count; `rows_done` hears of each band of
/// rows finished. Returns the rays traced, by kind.
///
/// ```
/// use voxtrace::{render, Camera, CameraSettings, IAabb, OctreeScene};
/// use voxtrace::{Rect, RenderOptions, Target, VoxelGenerator};
///
/// let scene = OctreeScene::build(&VoxelGenerator::new(1), IAabb::centered(32))?;
/// let camera = Camera::new(CameraSettings { width: 64, height: 36, ..Default::default() })?;
/// let mut pixels = vec![0u32; 64 * 36]; // packed RGBA8, R in the first byte
/// let region = Rect::full(&camera);
/// let rays = render(&scene, &camera, &RenderOptions::default(), region, Target::Buffer(&mut pixels), None)?;
/// assert_eq!(rays.primary_rays, 64 * 36);
/// # Ok::<(), voxtrace::Error>(())
/// ```
///
/// # Errors
/// A region outside the frame or too large to address, invalid options
/// ([`RenderOptions::validate`]), or a target of the wrong size.
pub fn render<S: Scene + Sync + ?Sized>(
    scene: &S,
    camera: &Camera,
    options: &RenderOptions,
    region: Rect,
    target: Target<'_>,
    rows_done: RowsDone<'_>,
) -> Result<RayStats, Error> {
    let target = checked(camera, options, region, target)?;
    let job = FrameJob {
        scene,
        camera,
        region,
        target,
        samples: None,
        rows_done,
        keep_going: &mut |_| false,
    };
    Ok(FrameSetup::new(options, camera, scene.materials())
        .dispatch(job)
        .rays)
}

/// [`render`], the samples taken in rounds over the whole region
/// ([`crate::Rounds`]): after each round every pixel of `target` holds
/// its value so far, and `keep_going(n)`, asked on this thread after
/// round `n` while a pixel is left that is not done, says whether round
/// `n + 1` begins (round 1 always runs). The region after `n` rounds is
/// byte for byte [`render`]'s with [`crate::Rounds::options_after`] `n`,
/// and with every round taken it is [`render`]'s own. Only the path
/// tracer samples in rounds: any other frame is one round.
///
/// `samples` is the state each pixel keeps between rounds, at least one
/// per pixel of `region` (overwritten: no need to clear it).
///
/// # Errors
/// As [`render`]; also a `samples` shorter than the region's area.
// (The arguments of `render`, the pixels' state and the predicate:
// bundling them would hide which is which.)
#[allow(clippy::too_many_arguments)]
pub fn render_in_rounds<S: Scene + Sync + ?Sized>(
    scene: &S,
    camera: &Camera,
    options: &RenderOptions,
    region: Rect,
    target: Target<'_>,
    samples: &mut [PixelSamples],
    rows_done: RowsDone<'_>,
    mut keep_going: impl FnMut(u32) -> bool,
) -> Result<RoundsDone, Error> {
    let target = checked(camera, options, region, target)?;
    let required = region.area()?;
    if samples.len() < required {
        return Err(Error::BufferTooSmall {
            required,
            actual: samples.len(),
        });
    }
    let job = FrameJob {
        scene,
        camera,
        region,
        target,
        samples: Some(&mut samples[..required]),
        rows_done,
        keep_going: &mut keep_going,
    };
    Ok(FrameSetup::new(options, camera, scene.materials()).dispatch(job))
}

/// The checks every render makes before it starts: a region the camera
/// can render, usable options and a target of the region's size; the
/// target cut to the region's area.
fn checked<'a>(
    camera: &Camera,
    options: &RenderOptions,
    region: Rect,
    target: Target<'a>,
) -> Result<Target<'a>, Error> {
    region.validate(camera)?;
    options.validate()?;
    let required = region.area()?;
    match target {
        Target::Buffer(out) if out.len() < required => Err(Error::BufferTooSmall {
            required,
            actual: out.len(),
        }),
        Target::Buffer(out) => Ok(Target::Buffer(&mut out[..required])),
        #[cfg(feature = "rayon")]
        Target::Framebuffer(frame) => {
            let actual = (frame.width(), frame.height());
            if actual != (region.width, region.height) {
                return Err(Error::SizeMismatch {
                    expected: (region.width, region.height),
                    actual,
                });
            }
            Ok(Target::Framebuffer(frame))
        }
    }
}

/// A checked render: its region, target, and pixels' state between rounds
/// (`None`: one pass).
struct FrameJob<'a, S: ?Sized> {
    scene: &'a S,
    camera: &'a Camera,
    region: Rect,
    target: Target<'a>,
    samples: Option<&'a mut [PixelSamples]>,
    rows_done: RowsDone<'a>,
    keep_going: &'a mut dyn FnMut(u32) -> bool,
}

impl<S: Scene + Sync + ?Sized> Job for FrameJob<'_, S> {
    type Output = RoundsDone;

    /// Round after round until no pixel is left that is not done or the
    /// caller says stop. A kernel that takes its samples in one pass
    /// makes every pixel in round 1, and its pixels' states say finished.
    fn run<K: Kernel>(mut self, kernel: &K) -> RoundsDone {
        let mut samples = self.samples.take();
        if !K::RESUMES {
            if let Some(samples) = samples.take() {
                samples.fill(PixelSamples::finished());
            }
        } else if let Some(samples) = samples.as_deref_mut() {
            samples.fill(PixelSamples::default());
        }
        let mut done = RoundsDone::default();
        loop {
            done.rounds += 1;
            let (rays, left) = self.round(kernel, samples.as_deref_mut(), done.rounds);
            done.rays += rays;
            if !left {
                done.complete = true;
                return done;
            }
            if !(self.keep_going)(done.rounds) {
                return done;
            }
        }
    }
}

/// Rows per task of a round of a render in rounds: every round ends with
/// a wait for its slowest task, and after the first the work left gathers
/// where pixels are still noisy, so tasks are finer than one pass's bands
/// of a tile's height (benches/README.md).
const ROUND_BAND: u32 = 4;

impl<S: Scene + Sync + ?Sized> FrameJob<'_, S> {
    /// Round `n` (one pass when `samples` is `None`) over the region, a
    /// band of rows at a time: on this thread into a buffer, else one
    /// rayon task per band, each band its own job (left to rayon's
    /// adaptive splitting, a thread would take a run of bands and walk it
    /// alone, and where the costly bands bunch up, the terrain under the
    /// sky, the other thread ran out of work). Only a band's tiles are
    /// compiled per kernel; the bands are handed out by code shared by
    /// every kernel. Returns the rays traced and whether a pixel is left
    /// that is not done.
    fn round<K: Kernel>(
        &mut self,
        kernel: &K,
        samples: Option<&mut [PixelSamples]>,
        n: u32,
    ) -> (RayStats, bool) {
        let (scene, camera, region) = (self.scene, self.camera, self.region);
        let rows = if samples.is_some() { ROUND_BAND } else { TILE };
        let bands = Bands {
            region,
            rows,
            rows_done: self.rows_done,
        };
        let tiles = BandTiles {
            kernel,
            scene,
            camera,
            bands,
            n,
        };
        match &mut self.target {
            Target::Buffer(out) => {
                let stride = region.width as usize;
                bands.into_buffer(out, samples, &mut |index, states, out| {
                    tiles.run(index, states, |dx, dy, rgba| {
                        out[dy as usize * stride + dx as usize] = rgba;
                    })
                })
            }
            #[cfg(feature = "rayon")]
            Target::Framebuffer(frame) => {
                let frame = &**frame;
                bands.into_framebuffer(samples, &|index, states| {
                    let y0 = index as u32 * rows;
                    tiles.run(index, states, |dx, dy, rgba| {
                        frame.set(dx, y0 + dy, rgba);
                    })
                })
            }
        }
    }
}

/// What a band's tiles give: the rays traced, and whether a pixel is left
/// that is not done.
type Traced = (RayStats, bool);

/// A band's pixels' states in a render in rounds (`None` in one pass).
type States<'a> = Option<&'a mut [PixelSamples]>;

/// A round's bands, each rendered tile by tile with one kernel.
struct BandTiles<'a, K, S: ?Sized> {
    kernel: &'a K,
    scene: &'a S,
    camera: &'a Camera,
    bands: Bands<'a>,
    /// The round (with pixels' states; ignored in one pass).
    n: u32,
}

impl<K: Kernel, S: Scene + ?Sized> BandTiles<'_, K, S> {
    /// Band `index` with its pixels' states (in a render in rounds), its
    /// pixels handed to `put(dx, dy, rgba)` at their offsets inside the
    /// band.
    fn run(
        &self,
        index: usize,
        states: Option<&mut [PixelSamples]>,
        put: impl FnMut(u32, u32, u32),
    ) -> Traced {
        let round = states.map(|samples| Round { n: self.n, samples });
        let rect = self.bands.rect(index);
        render_tiles(self.kernel, self.scene, self.camera, rect, round, put)
    }
}

/// The bands of `rows` rows of a region, handed out in order on this
/// thread or as rayon tasks.
#[derive(Clone, Copy)]
struct Bands<'a> {
    region: Rect,
    rows: u32,
    rows_done: RowsDone<'a>,
}

impl Bands<'_> {
    /// Band `index`'s rows of the region.
    fn rect(self, index: usize) -> Rect {
        let region = self.region;
        let y = region.y + index as u32 * self.rows;
        Rect {
            y,
            height: self.rows.min(region.y + region.height - y),
            ..region
        }
    }

    /// Every band in order on this thread: `band(index, states, pixels)`
    /// with the band's pixels' states (in a render in rounds) and its
    /// rows of `out`.
    fn into_buffer(
        self,
        out: &mut [u32],
        samples: Option<&mut [PixelSamples]>,
        band: &mut dyn FnMut(usize, States<'_>, &mut [u32]) -> Traced,
    ) -> Traced {
        let band_len = self.region.width as usize * self.rows as usize;
        let mut states = samples.map(|s| s.chunks_mut(band_len));
        let mut traced = (RayStats::default(), false);
        for (index, out) in out.chunks_mut(band_len).enumerate() {
            let states = states.as_mut().and_then(Iterator::next);
            let (rays, left) = band(index, states, out);
            traced = (traced.0 + rays, traced.1 || left);
            self.done(index);
        }
        traced
    }

    /// Every band as its own rayon task: `band(index, states)`, with the
    /// band's pixels' states in a render in rounds.
    #[cfg(feature = "rayon")]
    fn into_framebuffer(
        self,
        samples: Option<&mut [PixelSamples]>,
        band: &(dyn Fn(usize, States<'_>) -> Traced + Sync),
    ) -> Traced {
        let band_len = self.region.width as usize * self.rows as usize;
        let in_band = |index: usize, states| {
            let traced = band(index, states);
            self.done(index);
            traced
        };
        let nothing = || (RayStats::default(), false);
        let sum = |a: Traced, b: Traced| (a.0 + b.0, a.1 || b.1);
        match samples {
            Some(samples) => samples
                .par_chunks_mut(band_len)
                .with_max_len(1)
                .enumerate()
                .map(|(index, states)| in_band(index, Some(states)))
                .reduce(nothing, sum),
            None => {
                let bands = self.region.height.div_ceil(self.rows) as usize;
                let stride = spread_stride(bands);
                (0..bands)
                    .into_par_iter()
                    .with_max_len(1)
                    .map(|k| in_band(k * stride % bands, None))
                    .reduce(nothing, sum)
            }
        }
    }

    /// Tells the caller that band `index` is finished.
    fn done(self, index: usize) {
        if let Some(rows_done) = self.rows_done {
            rows_done(self.rect(index).height);
        }
    }
}

/// A step through `bands` bands that visits each once (coprime to it) and
/// spreads the first ones over the whole region (near the golden ratio of
/// it): the bands finished early are a fair sample of the frame's cost,
/// so a progress bar's time left does not run low over the cheap sky.
#[cfg(feature = "rayon")]
fn spread_stride(bands: usize) -> usize {
    let coprime = |s: usize| (2..=s).all(|d| s % d != 0 || bands % d != 0);
    // (`bands + 1` is coprime: the search ends.)
    ((bands * 1_000 / 1_618).max(1)..)
        .find(|&s| coprime(s))
        .unwrap_or(1)
}

#[cfg(all(test, feature = "rayon"))]
mod tests {
    /// Every band once; the order's first half in every quarter.
    #[test]
    fn the_band_order_is_a_spread_permutation() {
        for bands in 1..300 {
            let stride = super::spread_stride(bands);
            let order = |k: usize| k * stride % bands;
            let mut seen = [0u8; 300];
            (0..bands).for_each(|k| seen[order(k)] += 1);
            assert!(seen[..bands].iter().all(|&n| n == 1), "{bands} bands");
            let quarters = (0..bands / 2).fold(0, |q, k| q | 1 << (4 * order(k) / bands));
            assert!(bands < 16 || quarters == 15, "{bands} bands, {stride}");
        }
    }
}
