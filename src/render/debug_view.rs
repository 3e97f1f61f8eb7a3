//! The seed paper's debug view: the edges of the boxes a storage walks
//! through, each colored by a Pearson hash of the box's position.

use glam::U8Vec3;

use crate::geom::{IAabb, Ray};

/// Pearson's table: a permutation of `0..=255`, here a Fisher-Yates shuffle
/// driven by a fixed 64-bit LCG, computed at compile time.
const PERMUTATION: [u8; 256] = {
    let mut table = [0u8; 256];
    let mut i = 0;
    while i < 256 {
        table[i] = i as u8;
        i += 1;
    }
    let mut state: u64 = 0x2545_F491_4F6C_DD1D;
    let mut i = 255;
    while i > 0 {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        let j = ((state >> 33) % (i as u64 + 1)) as usize;
        let swap = table[i];
        table[i] = table[j];
        table[j] = swap;
        i -= 1;
    }
    table
};

/// Pearson hashing (the seed's Alg. 1), widened to three bytes the usual
/// way: channel `k` starts from `T[(first byte + k) mod 256]` and then mixes
/// in the remaining bytes with `h = T[h ^ byte]`.
#[must_use]
pub(crate) fn pearson_rgb(bytes: &[u8]) -> U8Vec3 {
    let channel = |k: u8| {
        let Some((&first, rest)) = bytes.split_first() else {
            return PERMUTATION[usize::from(k)];
        };
        let mut h = PERMUTATION[usize::from(first.wrapping_add(k))];
        for &b in rest {
            h = PERMUTATION[usize::from(h ^ b)];
        }
        h
    };
    U8Vec3::new(channel(0), channel(1), channel(2))
}

/// The color of a box's edges: the hash of its minimum corner and its side.
#[must_use]
pub(crate) fn box_color(cube: IAabb) -> U8Vec3 {
    let mut bytes = [0u8; 16];
    let min = cube.min.to_array();
    for (k, v) in min.iter().enumerate() {
        bytes[4 * k..4 * k + 4].copy_from_slice(&v.to_le_bytes());
    }
    bytes[12..].copy_from_slice(&cube.size().x.to_le_bytes());
    pearson_rgb(&bytes)
}

/// True when `ray` enters `cube` within `width_at_0 + width_per_t * t` of
/// one of its edges, `t` being the entry distance: the seed's test, "two
/// intersection points on separate faces close to each other", as one point
/// close to two faces. Lines so drawn stay about as wide on screen at every
/// distance (a perspective camera's pixels grow with `t`, an orthographic
/// camera's do not).
#[must_use]
pub(crate) fn enters_near_edge(ray: &Ray, cube: IAabb, width_at_0: f32, width_per_t: f32) -> bool {
    let lo = (cube.min.as_vec3() - ray.origin()) * ray.inv_dir();
    let hi = (cube.max.as_vec3() - ray.origin()) * ray.inv_dir();
    // A ray parallel to an axis' planes is inside that slab all along (the
    // walk visited the box); its crossings may be NaN (0 * inf) or infinite.
    let parallel = ray.dir().cmpeq(glam::Vec3::ZERO);
    let near = glam::Vec3::select(parallel, glam::Vec3::NEG_INFINITY, lo.min(hi));
    let t = near.max_element().max(0.0);
    let width = width_at_0 + width_per_t * t;
    if !(width > 0.0 && width.is_finite()) {
        return false;
    }
    let p = ray.at(t);
    let close = |a: usize| {
        (p[a] - cube.min[a] as f32).abs() <= width || (p[a] - cube.max[a] as f32).abs() <= width
    };
    u8::from(close(0)) + u8::from(close(1)) + u8::from(close(2)) >= 2
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{IVec3, Vec3};

    #[test]
    fn table_is_a_permutation() {
        let mut seen = [false; 256];
        for &v in &PERMUTATION {
            assert!(!seen[usize::from(v)]);
            seen[usize::from(v)] = true;
        }
    }

    #[test]
    fn neighbouring_boxes_get_different_colors() {
        let at = |x: i32| IAabb {
            min: IVec3::new(x, 0, 0),
            max: IVec3::new(x + 4, 4, 4),
        };
        assert_ne!(box_color(at(0)), box_color(at(4)));
        let bigger = IAabb {
            min: IVec3::ZERO,
            max: IVec3::splat(8),
        };
        assert_ne!(box_color(at(0)), box_color(bigger));
    }

    #[test]
    fn edges_are_found_near_edges_only() {
        let cube = IAabb {
            min: IVec3::ZERO,
            max: IVec3::splat(4),
        };
        // Straight down onto the top face: near its edge x = 0, or its middle.
        let down = |x: f32, z: f32| Ray::new(Vec3::new(x, 10.0, z), Vec3::NEG_Y).unwrap();
        assert!(enters_near_edge(&down(0.05, 2.0), cube, 0.0, 0.01));
        assert!(enters_near_edge(&down(3.95, 2.0), cube, 0.0, 0.01));
        assert!(!enters_near_edge(&down(2.0, 2.0), cube, 0.0, 0.01));
        assert!(!enters_near_edge(&down(0.2, 2.0), cube, 0.0, 0.01));
        // A ray starting inside has no entry point to draw.
        let inside = Ray::new(Vec3::splat(0.01), Vec3::X).unwrap();
        assert!(!enters_near_edge(&inside, cube, 0.0, 0.01));
    }
}
