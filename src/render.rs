//! The scalar tracer: renders rows of pixels into a caller's `&mut [u32]`.
//!
//! One function, [`render_pixel`], defines a pixel's value; spans of a row,
//! crops, the full frame and the threaded renderer are all made of it, so
//! they cannot disagree.

use crate::camera::Camera;
use crate::options::RenderOptions;
use crate::scene::Scene;
use crate::shader::{FrameJob, Kernel, Shader};
use crate::Error;

/// Rays traced for a frame or part of one, by kind.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct RayStats {
    /// Camera rays (one per pixel sample).
    pub primary_rays: u64,
    /// Camera rays that hit a voxel.
    pub primary_hits: u64,
    /// Rays toward the sun (shadows): one per primary hit on a face the sun
    /// shines on, 0 with shadows off or no sun.
    pub shadow_rays: u64,
    /// Ambient occlusion rays: the setting's ray count per primary hit that
    /// entered through a face, 0 with occlusion off.
    pub ao_rays: u64,
}

impl core::ops::AddAssign for RayStats {
    fn add_assign(&mut self, rhs: Self) {
        self.primary_rays += rhs.primary_rays;
        self.primary_hits += rhs.primary_hits;
        self.shadow_rays += rhs.shadow_rays;
        self.ao_rays += rhs.ao_rays;
    }
}

impl core::ops::Add for RayStats {
    type Output = RayStats;
    fn add(mut self, rhs: Self) -> RayStats {
        self += rhs;
        self
    }
}

/// A rectangle of pixels of a frame: columns `x..x + width`, rows
/// `y..y + height`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Rect {
    /// First column.
    pub x: u32,
    /// First row.
    pub y: u32,
    /// Columns.
    pub width: u32,
    /// Rows.
    pub height: u32,
}

impl Rect {
    /// The whole frame of `camera`.
    #[must_use]
    pub fn full(camera: &Camera) -> Rect {
        Rect {
            x: 0,
            y: 0,
            width: camera.width(),
            height: camera.height(),
        }
    }

    /// Pixels in the rectangle.
    pub fn area(&self) -> Result<usize, Error> {
        (self.width as usize)
            .checked_mul(self.height as usize)
            .ok_or(Error::SizeOverflow)
    }

    /// Checks the rectangle is non-empty and inside `camera`'s frame.
    pub fn validate(&self, camera: &Camera) -> Result<(), Error> {
        if self.width == 0 || self.height == 0 {
            return Err(Error::ZeroSize);
        }
        let fits = |start: u32, len: u32, total: u32| {
            start.checked_add(len).is_some_and(|end| end <= total)
        };
        if fits(self.x, self.width, camera.width()) && fits(self.y, self.height, camera.height()) {
            Ok(())
        } else {
            Err(Error::InvalidCamera {
                reason: "region lies outside the frame",
            })
        }
    }
}

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
            kernel.pixel(self.scene, self.x, self.y)
        }
    }
    Shader::new(options, camera).dispatch(Pixel { scene, x, y })
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
    Shader::new(options, camera).dispatch(Rows {
        scene,
        x0,
        y0: y,
        width: out.len().max(1),
        out,
    })
}

/// Rows of pixels `(x0.., y0..)`, `width` to a row, into `out`.
struct Rows<'a, S: ?Sized> {
    scene: &'a S,
    x0: u32,
    y0: u32,
    width: usize,
    out: &'a mut [u32],
}

impl<S: Scene + ?Sized> FrameJob for Rows<'_, S> {
    type Output = RayStats;
    fn run<K: Kernel>(self, kernel: &K) -> RayStats {
        let mut stats = RayStats::default();
        for (y, row) in (self.y0..).zip(self.out.chunks_mut(self.width)) {
            for (x, pixel) in (self.x0..).zip(row.iter_mut()) {
                let (rgba, rays) = kernel.pixel(self.scene, x, y);
                *pixel = rgba;
                stats += rays;
            }
        }
        stats
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
    Ok(Shader::new(options, camera).dispatch(Rows {
        scene,
        x0: region.x,
        y0: region.y,
        width: region.width as usize,
        out: &mut out[..required],
    }))
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
