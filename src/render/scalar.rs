//! The scalar tracer: renders rows of pixels into a caller's `&mut [u32]`.
//!
//! One function, [`render_pixel`], defines a pixel's value; spans of a row,
//! crops, the full frame and the threaded renderer are all made of it, so
//! they cannot disagree.

use crate::error::Error;
use crate::render::camera::Camera;
use crate::render::options::RenderOptions;
#[cfg(feature = "path")]
use crate::render::rounds::in_rounds;
use crate::render::rounds::{PixelSamples, RoundsDone};
use crate::render::shader::{FrameJob, Kernel, Shader};
#[cfg(feature = "path")]
use crate::render::shader::{Resumable, RoundsJob};
use crate::render::stats::{RayStats, Rect};
use crate::render::tiles::render_tiles;
#[cfg(feature = "path")]
use crate::render::tiles::resume_tiles;
use crate::scene::Scene;
use crate::scene::WalkMemory;

/// Renders pixel `(x, y)` of `camera`'s frame: its packed color and the rays
/// it traced. The same value every renderer (span, crop, frame, threaded)
/// gives that pixel. Prepares the frame's shader per call: loops should
/// call [`render_span`] or [`render_region`] instead.
pub fn render_pixel<S: Scene + ?Sized>(
    scene: &S,
    camera: &Camera,
    options: &RenderOptions,
    x: u32,
    y: u32,
) -> (u32, RayStats) {
    struct Pixel<'a, S: ?Sized> {
        scene: &'a S,
        x: u32,
        y: u32,
    }
    impl<S: Scene + ?Sized> FrameJob for Pixel<'_, S> {
        type Output = (u32, RayStats);
        fn run<K: Kernel>(self, kernel: &K) -> (u32, RayStats) {
            kernel.pixel(self.scene, self.x, self.y, 0.0, &mut WalkMemory::new())
        }
    }
    Shader::new(options, camera, scene.materials()).dispatch(Pixel { scene, x, y })
}

/// Renders pixels `(x0 + i, y)` for every `i` in `0..out.len()` into `out`.
///
/// The caller keeps the pixels inside the frame and the options valid
/// ([`RenderOptions::validate`]; invalid settings are turned off). Allocates
/// nothing.
pub fn render_span<S: Scene + ?Sized>(
    scene: &S,
    camera: &Camera,
    options: &RenderOptions,
    x0: u32,
    y: u32,
    out: &mut [u32],
) -> RayStats {
    let rect = Rect {
        x: x0,
        y,
        width: u32::try_from(out.len()).unwrap_or(u32::MAX),
        height: 1,
    };
    Shader::new(options, camera, scene.materials()).dispatch(Tiles {
        scene,
        camera,
        rect,
        out,
    })
}

/// The pixels of `rect` in tiles, into `out` (row-major, stride
/// `rect.width`).
struct Tiles<'a, S: ?Sized> {
    scene: &'a S,
    camera: &'a Camera,
    rect: Rect,
    out: &'a mut [u32],
}

impl<S: Scene + ?Sized> FrameJob for Tiles<'_, S> {
    type Output = RayStats;
    fn run<K: Kernel>(self, kernel: &K) -> RayStats {
        let Tiles {
            scene,
            camera,
            rect,
            out,
        } = self;
        let stride = rect.width as usize;
        render_tiles(kernel, scene, camera, rect, |dx, dy, rgba| {
            if let Some(pixel) = out.get_mut(dy as usize * stride + dx as usize) {
                *pixel = rgba;
            }
        })
    }
}

/// Renders the crop `region` of the frame into `out`, row-major with stride
/// `region.width`: byte-identical to the same pixels of a full render.
///
/// `out` needs at least `region.width * region.height` elements; the rest is
/// left alone. Single-threaded; allocates nothing.
pub fn render_region<S: Scene + ?Sized>(
    scene: &S,
    camera: &Camera,
    options: &RenderOptions,
    region: Rect,
    out: &mut [u32],
) -> Result<RayStats, Error> {
    region.validate(camera)?;
    options.validate()?;
    let required = region.area()?;
    if out.len() < required {
        return Err(Error::BufferTooSmall {
            required,
            actual: out.len(),
        });
    }
    Ok(
        Shader::new(options, camera, scene.materials()).dispatch(Tiles {
            scene,
            camera,
            rect: region,
            out: &mut out[..required],
        }),
    )
}

/// Renders the whole frame into `out` (row-major, `width * height` RGBA8
/// pixels, R in the first byte). Single-threaded; allocates nothing.
pub fn render<S: Scene + ?Sized>(
    scene: &S,
    camera: &Camera,
    options: &RenderOptions,
    out: &mut [u32],
) -> Result<RayStats, Error> {
    render_region(scene, camera, options, Rect::full(camera), out)
}

/// Renders the crop `region` into `out` as [`render_region`] does, its
/// samples taken in rounds over the whole crop ([`crate::Rounds`]):
/// after each round every pixel of `out`
/// holds its value so far, and `keep_going(n)`, asked after round `n`
/// while a pixel is left that is not done, says whether round `n + 1`
/// begins (round 1 always runs). The crop after `n` rounds is byte for
/// byte [`render_region`]'s with [`crate::Rounds::options_after`] `n`,
/// and with every round taken it is [`render_region`]'s own.
///
/// `pixels` is the state each pixel keeps between rounds, at least one
/// per pixel of `region` (overwritten: no need to clear it). Single-
/// threaded; allocates nothing.
pub fn render_region_in_rounds<S: Scene + ?Sized>(
    scene: &S,
    camera: &Camera,
    options: &RenderOptions,
    region: Rect,
    out: &mut [u32],
    pixels: &mut [PixelSamples],
    keep_going: impl FnMut(u32) -> bool,
) -> Result<RoundsDone, Error> {
    region.validate(camera)?;
    options.validate()?;
    let required = region.area()?;
    for actual in [out.len(), pixels.len()] {
        if actual < required {
            return Err(Error::BufferTooSmall { required, actual });
        }
    }
    let pixels = &mut pixels[..required];
    pixels.fill(PixelSamples::default());
    let shader = Shader::new(options, camera, scene.materials());
    let out = &mut out[..required];
    // Path-traced: in rounds. (Only the path tracer samples in rounds.)
    #[cfg(feature = "path")]
    let (out, pixels) = match shader.dispatch_rounds(RegionInRounds {
        scene,
        camera,
        rect: region,
        out,
        pixels,
        keep_going,
    }) {
        Ok(done) => return Ok(done),
        Err(job) => (job.out, job.pixels),
    };
    #[cfg(not(feature = "path"))]
    let _ = keep_going;
    // Not path-traced: one pass, one round.
    pixels.fill(PixelSamples::finished());
    let rays = shader.dispatch(Tiles {
        scene,
        camera,
        rect: region,
        out,
    });
    Ok(RoundsDone {
        rays,
        rounds: 1,
        complete: true,
    })
}

/// The pixels of `rect` in rounds, into `out` (row-major, stride
/// `rect.width`), each pixel's state in `pixels` (the same layout).
#[cfg(feature = "path")]
struct RegionInRounds<'a, S: ?Sized, F> {
    scene: &'a S,
    camera: &'a Camera,
    rect: Rect,
    out: &'a mut [u32],
    pixels: &'a mut [PixelSamples],
    keep_going: F,
}

#[cfg(feature = "path")]
impl<S: Scene + ?Sized, F: FnMut(u32) -> bool> RoundsJob for RegionInRounds<'_, S, F> {
    type Output = RoundsDone;
    fn run<K: Resumable>(self, kernel: &K) -> RoundsDone {
        let RegionInRounds {
            scene,
            camera,
            rect,
            out,
            pixels,
            keep_going,
        } = self;
        let stride = rect.width as usize;
        let round = |n| {
            resume_tiles(kernel, scene, camera, rect, pixels, n, |dx, dy, rgba| {
                if let Some(pixel) = out.get_mut(dy as usize * stride + dx as usize) {
                    *pixel = rgba;
                }
            })
        };
        in_rounds(round, keep_going)
    }
}
