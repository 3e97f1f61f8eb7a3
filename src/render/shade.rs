//! How a hit becomes a color. Integer arithmetic wherever it can be, so the
//! same hit gives the same bytes on every target.

use glam::{U8Vec3, UVec3, Vec3};

use crate::geom::{Face, Ray};
use crate::render::options::RenderOptions;
use crate::scene::Hit;

/// The sky of `--flat` renders: one constant color.
pub const FLAT_SKY: U8Vec3 = U8Vec3::new(135, 190, 235);
/// Sky color at the horizon (default look).
pub const SKY_HORIZON: U8Vec3 = U8Vec3::new(200, 224, 245);
/// Sky color straight up (default look).
pub const SKY_ZENITH: U8Vec3 = U8Vec3::new(86, 144, 220);

/// Brightness of a face the sun does not reach, as a fraction of full.
const AMBIENT: f32 = 0.4;

/// Brightness of each face, out of 256, in a scene without light: fixed
/// values that keep the terrain's shape readable. A ray starting inside a
/// voxel sees it at half brightness.
const UNLIT: [u16; 7] = [160, 214, 128, 256, 194, 176, 128];

/// Index of a face in per-face tables: `Face` order, then 6 for a ray that
/// started inside its voxel.
#[inline]
#[must_use]
pub(crate) fn face_index(face: Option<Face>) -> usize {
    match face {
        Some(Face::NegX) => 0,
        Some(Face::PosX) => 1,
        Some(Face::NegY) => 2,
        Some(Face::PosY) => 3,
        Some(Face::NegZ) => 4,
        Some(Face::PosZ) => 5,
        None => 6,
    }
}

/// Per-face brightness out of 256 under `sun` (Lambert: ambient plus the
/// cosine of the sun's angle to the face's normal), the brightness when the
/// sun is blocked, which faces the sun reaches, and the unit sun direction.
/// Computed once per frame, so pixels only multiply integers.
pub(crate) fn face_weights(sun: Option<Vec3>) -> ([u16; 7], [u16; 7], [bool; 7], Vec3) {
    let Some(sun) = sun.and_then(|s| s.try_normalize()) else {
        return (UNLIT, UNLIT, [false; 7], Vec3::Y);
    };
    let to_weight = |light: f32| (light * 256.0 + 0.5) as u16;
    let mut light = [to_weight(AMBIENT); 7];
    let mut sunlit = [false; 7];
    for face in [
        Face::NegX,
        Face::PosX,
        Face::NegY,
        Face::PosY,
        Face::NegZ,
        Face::PosZ,
    ] {
        let cosine = face.normal().as_vec3().dot(sun);
        let i = face_index(Some(face));
        sunlit[i] = cosine > 0.0;
        light[i] = to_weight(AMBIENT + (1.0 - AMBIENT) * cosine.max(0.0));
    }
    (light, [to_weight(AMBIENT); 7], sunlit, sun)
}

/// `albedo` at brightness `light` out of 256, in integers.
#[inline]
#[must_use]
pub(crate) fn lit(albedo: U8Vec3, light: u32) -> U8Vec3 {
    (albedo.as_uvec3() * light / 256)
        .min(UVec3::splat(255))
        .as_u8vec3()
}

/// `color` at distance `t` blended toward the horizon by `min(t / distance, 1)`.
#[inline]
#[must_use]
pub(crate) fn fog_blend(color: U8Vec3, t: f32, distance: f32) -> U8Vec3 {
    let f = (t / distance).min(1.0);
    let c = color.as_vec3();
    to_u8(c + (SKY_HORIZON.as_vec3() - c) * f)
}

/// The color a primary ray gets from its first hit alone: what a pixel is
/// when no secondary rays are traced (no shadows, no ambient occlusion) and
/// one sample is taken. `flat` gives the voxel's color or [`FLAT_SKY`];
/// `debug` is not drawn here (it needs the walk, see [`crate::render()`]).
#[must_use]
pub fn shade(hit: Option<&Hit>, ray: &Ray, options: &RenderOptions) -> U8Vec3 {
    match (hit, options.flat) {
        (Some(hit), true) => hit.voxel.color,
        (Some(hit), false) => {
            let (light, ..) = face_weights(options.sun);
            let color = lit(hit.voxel.color, u32::from(light[face_index(hit.face)]));
            match options.fog {
                Some(fog) => fog_blend(color, hit.t, fog.distance),
                None => color,
            }
        }
        (None, true) => FLAT_SKY,
        (None, false) => sky(ray.dir()),
    }
}

/// Vertical sky gradient, horizon to zenith; below the horizon stays at the
/// horizon color.
#[must_use]
pub fn sky(dir: Vec3) -> U8Vec3 {
    // Written so that a NaN component gives the horizon, not a NaN color.
    let t = if dir.y > 0.0 { dir.y.min(1.0) } else { 0.0 };
    let (h, z) = (SKY_HORIZON.as_vec3(), SKY_ZENITH.as_vec3());
    to_u8(h + (z - h) * t)
}

/// Rounds a color in `[0, 255]` to bytes; NaN becomes 0, out of range clamps.
#[must_use]
pub fn to_u8(c: Vec3) -> U8Vec3 {
    let r = |x: f32| (x + 0.5) as u8; // `as` saturates and maps NaN to 0
    U8Vec3::new(r(c.x), r(c.y), r(c.z))
}

/// Packs a color as RGBA8 with R in the first byte in memory on every
/// target, alpha 255.
#[inline]
#[must_use]
pub fn pack(c: U8Vec3) -> u32 {
    u32::from_ne_bytes([c.x, c.y, c.z, 255])
}

/// Packs a color with alpha `a`, R in the first byte.
#[inline]
#[must_use]
pub(crate) fn pack_alpha(c: U8Vec3, a: u8) -> u32 {
    u32::from_ne_bytes([c.x, c.y, c.z, a])
}

/// Packs a pixel from its samples: with a transparent background the mean
/// of the `hits` samples that hit something, alpha covering their share of
/// `samples` (a pixel no sample hit is 0); otherwise the mean of all
/// `samples`. `mean_of(n)` is the looks' own rounded mean of their sum over
/// `n` samples (integers for the face-shaded look, radiance for the path
/// tracer), so both round as they always have.
#[inline]
pub(crate) fn pack_mean(
    samples: u32,
    hits: u32,
    transparent: bool,
    mean_of: impl FnOnce(u32) -> U8Vec3,
) -> u32 {
    if !transparent {
        return pack(mean_of(samples));
    }
    if hits == 0 {
        return 0;
    }
    let alpha = (255 * hits + samples / 2) / samples;
    pack_alpha(mean_of(hits), alpha as u8)
}

/// The inverse of [`pack`].
#[inline]
#[must_use]
pub fn unpack(p: u32) -> [u8; 4] {
    p.to_ne_bytes()
}
