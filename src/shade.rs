//! How a hit becomes a color. Integer arithmetic wherever it can be, so the
//! same hit gives the same bytes on every target.

use glam::{U8Vec3, Vec3};

use crate::geom::{Face, Hit, Ray};

/// The sky of `--flat` renders: one constant color.
pub const FLAT_SKY: U8Vec3 = U8Vec3::new(135, 190, 235);
/// Sky color at the horizon (default look).
pub const SKY_HORIZON: U8Vec3 = U8Vec3::new(200, 224, 245);
/// Sky color straight up (default look).
pub const SKY_ZENITH: U8Vec3 = U8Vec3::new(86, 144, 220);

/// The look of a frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct RenderOptions {
    /// Unshaded: every pixel is exactly the color of the voxel its ray hits
    /// first, the sky is [`FLAT_SKY`]. What palette checks and reference
    /// renderers compare against.
    pub flat: bool,
}

/// Brightness of each face, out of 256: a fixed light from above and
/// slightly to one side, so that the terrain's shape reads (the seed paper's
/// Fig. 1 look). A ray starting inside a voxel sees it at half brightness.
fn face_light(face: Option<Face>) -> u16 {
    match face {
        Some(Face::PosY) => 256,
        Some(Face::PosX) => 214,
        Some(Face::NegZ) => 194,
        Some(Face::PosZ) => 176,
        Some(Face::NegX) => 160,
        Some(Face::NegY) => 128,
        None => 128,
    }
}

/// The color of a primary ray: its hit, or the sky.
#[must_use]
pub fn shade(hit: Option<&Hit>, ray: &Ray, options: &RenderOptions) -> U8Vec3 {
    match (hit, options.flat) {
        (Some(hit), true) => hit.voxel.color,
        (Some(hit), false) => {
            let light = face_light(hit.face);
            let c = hit.voxel.color.as_u16vec3() * light / 256;
            c.as_u8vec3()
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

/// The inverse of [`pack`].
#[inline]
#[must_use]
pub fn unpack(p: u32) -> [u8; 4] {
    p.to_ne_bytes()
}
