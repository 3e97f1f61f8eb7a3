//! The guide images a denoiser reads beside the beauty render: per pixel,
//! the albedo (the first hit voxel's base color) and the normal (the hit
//! face's), traced through the library's public API.
//!
//! Both are deterministic (no light is sampled), so they are free of the
//! beauty's noise and a denoiser may trust them as clean. They are
//! averaged over the same footprint the beauty's samples cover: the pixel
//! center for one sample per pixel, else a 4x4 grid across the pixel, so
//! that edges are as soft in the guides as in the beauty.

use voxtrace::glam::Vec3;
use voxtrace::rayon::prelude::*;
use voxtrace::{sky, Background, Camera, Ray, Rect, RenderOptions, Scene};

/// Sub-pixel positions per side of the grid a guide pixel averages when
/// the beauty has more than one sample per pixel.
const GRID: u32 = 4;

/// The albedo and normal images of a region, row-major, three `f32` per
/// pixel (the layout the denoiser takes).
///
/// # Guarantees
/// Both hold `3 * width * height` values for the region they were traced
/// for. Albedo is in `[0, 1]`; a normal is the mean of axis unit vectors
/// (exactly one where every sub-pixel ray hits the same face), zero where
/// every ray misses.
#[derive(Clone, Debug, PartialEq)]
pub struct Guides {
    /// The first hit's base color over 255 (the path tracer's albedo), or
    /// the background a miss shows.
    pub albedo: Vec<f32>,
    /// The first hit face's outward normal; zero for a miss or a ray that
    /// starts inside a voxel.
    pub normal: Vec<f32>,
}

/// What `ray` sees for the guides: its albedo and normal.
fn first_hit(scene: &(dyn Scene + Sync), options: &RenderOptions, ray: &Ray) -> (Vec3, Vec3) {
    match scene.trace(ray) {
        Some(hit) => {
            let albedo = hit.voxel.color.as_vec3() / 255.0;
            let normal = hit.face.map_or(Vec3::ZERO, |f| f.normal().as_vec3());
            (albedo, normal)
        }
        None => (miss_albedo(options, ray.dir()), Vec3::ZERO),
    }
}

/// The albedo of a ray that hits nothing: what the beauty shows there
/// (the `--background` color, nothing for a transparent one, else the
/// sky: the path tracer's uniform sky radiance or the gradient), clamped
/// to `[0, 1]` as an albedo is.
fn miss_albedo(options: &RenderOptions, dir: Vec3) -> Vec3 {
    let color = match options.background {
        Background::Color(c) => c.as_vec3() / 255.0,
        Background::Transparent => Vec3::ZERO,
        Background::Sky => options
            .lighting
            .sky
            .unwrap_or_else(|| sky(dir).as_vec3() / 255.0),
    };
    color.clamp(Vec3::ZERO, Vec3::ONE)
}

/// Traces the guides of `region` of `camera`'s frame of `scene` for a
/// beauty rendered with `options` (its samples per pixel and background),
/// rows in parallel on the current rayon pool when `threaded`.
#[must_use]
pub fn render_guides(
    scene: &(dyn Scene + Sync),
    camera: &Camera,
    options: &RenderOptions,
    region: Rect,
    threaded: bool,
) -> Guides {
    let width = region.width as usize;
    let len = 3 * width * region.height as usize;
    let mut albedo = vec![0.0; len];
    let mut normal = vec![0.0; len];
    let step = 1.0 / GRID as f32;
    // Pixel (x, y)'s rays: the beauty's own center ray for one sample,
    // else the grid's (adaptive sampling takes several too).
    let centered = options.samples <= 1 && options.adaptive.is_none();
    let count = if centered { 1 } else { GRID * GRID };
    let ray = |x: u32, y: u32, k: u32| -> Ray {
        if centered {
            return camera.get_ray(x, y);
        }
        let dx = (k % GRID) as f32 * step + step / 2.0;
        let dy = (k / GRID) as f32 * step + step / 2.0;
        camera.get_ray_at(x as f32 + dx, y as f32 + dy)
    };
    let row = |(j, (albedo_row, normal_row)): (usize, (&mut [f32], &mut [f32]))| {
        let y = region.y + j as u32;
        for i in 0..width {
            let x = region.x + i as u32;
            let (mut a, mut n) = (Vec3::ZERO, Vec3::ZERO);
            for k in 0..count {
                let (ha, hn) = first_hit(scene, options, &ray(x, y, k));
                a += ha;
                n += hn;
            }
            let scale = 1.0 / count as f32;
            albedo_row[3 * i..3 * i + 3].copy_from_slice(&(a * scale).to_array());
            normal_row[3 * i..3 * i + 3].copy_from_slice(&(n * scale).to_array());
        }
    };
    let stride = 3 * width;
    if threaded {
        let rows = albedo
            .par_chunks_mut(stride)
            .zip(normal.par_chunks_mut(stride));
        rows.enumerate().for_each(row);
    } else {
        let rows = albedo.chunks_mut(stride).zip(normal.chunks_mut(stride));
        rows.enumerate().for_each(row);
    }
    Guides { albedo, normal }
}
