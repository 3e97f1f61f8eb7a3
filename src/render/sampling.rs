//! Deterministic sample positions: a low-discrepancy sequence keyed by pixel
//! and sample index, in integer arithmetic, so that every render is the same
//! on every thread count and target.

use glam::{Vec2, Vec3};

use crate::geom::Ray;
use crate::render::camera::Camera;

/// Mixes pixel coordinates and a stream number into 32 well-spread bits
/// (a fixed integer hash; no state, no randomness).
#[inline]
#[must_use]
pub(crate) fn pixel_key(x: u32, y: u32, stream: u32) -> u32 {
    let mut h = x.wrapping_mul(0x9E37_79B1)
        ^ y.wrapping_mul(0x85EB_CA77)
        ^ stream.wrapping_mul(0xC2B2_AE3D);
    // The finalizer of a well-tested 32-bit hash ("lowbias32").
    h ^= h >> 16;
    h = h.wrapping_mul(0x7FEB_352D);
    h ^= h >> 15;
    h = h.wrapping_mul(0x846C_A68B);
    h ^ (h >> 16)
}

/// Point `index` of Roberts' R2 sequence in `[0, 1)^2`, shifted by `key`
/// (Cranley-Patterson rotation) so that neighbouring pixels use different
/// points. In 32-bit fixed point: the steps are `2^32 / g` and `2^32 / g^2`
/// for the plastic number `g`, and the sum wraps exactly.
#[inline]
#[must_use]
pub(crate) fn r2(index: u32, key: u32) -> Vec2 {
    const STEP_X: u32 = 0xC13F_A9A9;
    const STEP_Y: u32 = 0x91E1_0DA5;
    let x = key.wrapping_add(index.wrapping_mul(STEP_X));
    let y = key.rotate_left(16).wrapping_add(index.wrapping_mul(STEP_Y));
    // The top 24 bits as an exact f32 in [0, 1).
    let unit = |v: u32| (v >> 8) as f32 * (1.0 / 16_777_216.0);
    Vec2::new(unit(x), unit(y))
}

/// Where sample `sample` of pixel `(x, y)` goes through the pixel, in a
/// frame of several samples per pixel: a point of the pixel's own
/// sequence, as an offset from its corner.
#[inline]
#[must_use]
pub(crate) fn sample_offset((x, y): (u32, u32), sample: u32) -> Vec2 {
    r2(sample, pixel_key(x, y, 0))
}

/// The camera ray of pixel `(x, y)`: through its center, or through the
/// point of sample `sample` ([`sample_offset`]) when one is given.
#[inline]
#[must_use]
pub(crate) fn sample_ray(camera: &Camera, (x, y): (u32, u32), sample: Option<u32>) -> Ray {
    match sample {
        None => camera.get_ray(x, y),
        Some(s) => {
            let offset = sample_offset((x, y), s);
            camera.get_ray_at(x as f32 + offset.x, y as f32 + offset.y)
        }
    }
}

/// A cosine-weighted direction on the hemisphere around `+z`, from a point
/// of the unit square: the density matches Lambert's law, so the fraction of
/// unoccluded rays estimates the ambient light.
#[inline]
#[must_use]
pub(crate) fn cosine_hemisphere(u: Vec2) -> Vec3 {
    let r = libm::sqrtf(u.x);
    let phi = core::f32::consts::TAU * u.y;
    // 1 - u.x is in (0, 1]: the direction never lies in the plane.
    Vec3::new(
        r * libm::cosf(phi),
        r * libm::sinf(phi),
        libm::sqrtf(1.0 - u.x),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn r2_points_fill_the_square_evenly() {
        // 256 points: every cell of a 4x4 grid gets 16 +- 4.
        let mut cells = [0u32; 16];
        for i in 0..256 {
            let p = r2(i, pixel_key(3, 5, 0));
            assert!((0.0..1.0).contains(&p.x) && (0.0..1.0).contains(&p.y));
            cells[(p.x * 4.0) as usize + 4 * (p.y * 4.0) as usize] += 1;
        }
        for count in cells {
            assert!((12..=20).contains(&count), "{cells:?}");
        }
    }

    #[test]
    fn hemisphere_directions_are_unit_and_upward() {
        for i in 0..1000 {
            let d = cosine_hemisphere(r2(i, 12345));
            assert!(d.z > 0.0);
            assert!((d.length() - 1.0).abs() < 1e-5);
        }
    }

    #[test]
    fn keys_differ_between_neighbours() {
        let k = pixel_key(10, 10, 0);
        assert_ne!(k, pixel_key(11, 10, 0));
        assert_ne!(k, pixel_key(10, 11, 0));
        assert_ne!(k, pixel_key(10, 10, 1));
    }
}
